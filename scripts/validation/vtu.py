"""Reads the VTU snapshots mfsd writes (raw appended binary, UInt64 headers)
into numpy arrays: read_vtu(path) -> {"points": (n, 3), "<field>": array}."""
import re

import numpy as np

_TYPES = {"Float32": np.float32, "Float64": np.float64, "Int32": np.int32, "Int64": np.int64, "UInt8": np.uint8}


def read_vtu(path):
    with open(path, "rb") as f:
        data = f.read()
    start = data.index(b"<AppendedData")
    start = data.index(b"_", start) + 1
    header = data[:start].decode("latin-1")
    out = {}
    for m in re.finditer(r"<DataArray ([^>]*)/>", header):
        attrs = dict(re.findall(r'(\w+)="([^"]*)"', m.group(1)))
        offset = int(attrs["offset"])
        nbytes = int(np.frombuffer(data, np.uint64, 1, start + offset)[0])
        dtype = _TYPES[attrs["type"]]
        arr = np.frombuffer(data, dtype, nbytes // np.dtype(dtype).itemsize, start + offset + 8)
        comps = int(attrs.get("NumberOfComponents", "1"))
        if comps > 1:
            arr = arr.reshape(-1, comps)
        out[attrs.get("Name", "points")] = arr
    return out
