"""Reads the VTU snapshots mfsd writes (raw appended binary, UInt64 headers)
into numpy arrays: read_vtu(path) -> {"points": (n, 3), "<field>": array};
snapshots(outdir) lists a run's snapshots with their times, mid_plane(d, dp)
selects the particle rows nearest the reference plane y = 0."""
import os
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


def snapshots(outdir):
    """(time, path) of a run's VTU snapshots, from its snapshots.pvd."""
    with open(os.path.join(outdir, "snapshots.pvd")) as f:
        return [(float(t), os.path.join(outdir, path)) for t, path in
                re.findall(r'timestep="([^"]+)" part="0" file="([^"]+)"', f.read())]


def nearest_snapshot(snaps, t):
    """(time, path) of the snapshot nearest to t in a snapshots() list."""
    return min(snaps, key=lambda s: abs(s[0] - t))


def mid_plane(d, dp):
    """Boolean mask of the particles whose reference y is nearest 0 (to 1 % of
    dp: one row, or the two rows at +-dp/2 of a lattice with an even count)."""
    y0 = np.abs(np.asarray(d["points"], dtype=float)[:, 1] - np.asarray(d["displacement"], dtype=float)[:, 1])
    return y0 < y0.min() + 0.01 * dp
