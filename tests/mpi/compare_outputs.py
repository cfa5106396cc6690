#!/usr/bin/env python3
"""A distributed run against the single-process run of the same scene (issue 25).

Runs SCENE once with `mfsd run` and once with `mpiexec -n RANKS mfsd run`,
then checks that every CSV series (energies, probes, boundary forces, measure
planes) agrees row by row within round-off, relative to each column's largest
magnitude (at least 1e-6 of the file's largest), and that the last snapshot's PVTU pieces hold every particle once
with the same displacements. Exit 0 when they agree; prints the worst column.

  compare_outputs.py MFSD MPIEXEC RANKS SCENE TOLERANCE [--migrates] [--skip FILE] [--set k=v ...]

--migrates: the distributed run must also have migrated particles between
the ranks (its report's "migrations: N", N > 0).
--skip FILE: a series left out, for a scene where it holds round-off alone
(the reaction on a body whose every node is prescribed sums to ~1e-8 N in
both runs); the test says why.
"""
import csv
import os
import re
import struct
import subprocess
import sys
import tempfile


def load(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(x) for x in r] for r in rows[1:]]


def vtu_arrays(path):
    """id and displacement of a .vtu written by mfsd (raw appended data)."""
    data = open(path, "rb").read()
    head, _, appended = data.partition(b'<AppendedData encoding="raw">\n_')
    out = {}
    for m in re.finditer(rb'<DataArray type="(\w+)"(?: Name="(\w+)")?(?: NumberOfComponents="(\d)")? format="appended" offset="(\d+)"', head):
        kind, name, _, offset = m.group(1).decode(), (m.group(2) or b"").decode(), m.group(3), int(m.group(4))
        if name not in ("id", "displacement"):
            continue
        size = struct.unpack_from("<Q", appended, offset)[0]
        fmt = {"Int64": "q", "Float64": "d", "Float32": "f"}[kind]
        count = size // struct.calcsize(fmt)
        out[name] = struct.unpack_from("<%d%s" % (count, fmt), appended, offset + 8)
    return out


def particles_of(folder):
    """id -> displacement of the last snapshot, from a .vtu or a .pvtu's pieces."""
    snaps = sorted(f for f in os.listdir(os.path.join(folder, "snapshots")) if re.search(r"_\d{5}\.p?vtu$", f) and "_rigid_" not in f)
    last = snaps[-1]
    if last.endswith(".pvtu"):
        text = open(os.path.join(folder, "snapshots", last)).read()
        pieces = re.findall(r'<Piece Source="([^"]+)"', text)
    else:
        pieces = [last]
    result = {}
    for p in pieces:
        a = vtu_arrays(os.path.join(folder, "snapshots", p))
        for k, i in enumerate(a["id"]):
            if i in result:
                raise SystemExit("particle %d is in two pieces" % i)
            result[i] = a["displacement"][3 * k:3 * k + 3]
    return last, result


def main():
    mfsd, mpiexec, ranks, scene, tol = sys.argv[1:6]
    extra = sys.argv[6:]
    migrates = "--migrates" in extra
    extra = [a for a in extra if a != "--migrates"]
    skipped = []
    while "--skip" in extra:
        k = extra.index("--skip")
        skipped.append(extra[k + 1])
        del extra[k:k + 2]
    tol = float(tol)
    work = tempfile.mkdtemp(prefix="mfsd_mpi_")
    serial, dist = os.path.join(work, "serial"), os.path.join(work, "ranks")
    subprocess.run([mfsd, "run", scene, "-q", "--threads", "1", "-o", serial] + extra, check=True)
    r = subprocess.run([mpiexec, "-n", ranks, "--oversubscribe", mfsd, "run", scene, "--threads", "1", "-o", dist]
                       + extra, check=True, capture_output=True, text=True)
    m = re.search(r"migrations: (\d+) \(rebalances (\d+)\)", r.stdout)
    if migrates:
        assert m and int(m.group(1)) > 0, "the distributed run migrated no particle:\n" + r.stdout[-2000:]
        print("%s migrations, %s rebalances" % (m.group(1), m.group(2)))
    worst, where = 0.0, ""
    series = sorted(f for f in os.listdir(serial) if f.endswith(".csv") and f not in skipped)
    assert series, "the scene writes no CSV series"
    for name in series:
        h1, a = load(os.path.join(serial, name))
        h2, b = load(os.path.join(dist, name))
        assert h1 == h2, "%s: columns differ" % name
        assert len(a) == len(b), "%s: %d rows against %d" % (name, len(a), len(b))
        if not a:  # a header alone (a scene without probes)
            continue
        # Each column relative to its largest magnitude, but not below 1e-6
        # of the file's largest: a column that is zero up to round-off
        # (the momentum across a symmetric bar) is compared at that floor.
        largest = max(abs(x) for r in a for x in r[1:]) or 1.0
        for k, column in enumerate(h1):
            scale = max(max(abs(r[k]) for r in a), 1e-6 * largest, 1e-300)
            for ra, rb in zip(a, b):
                d = abs(ra[k] - rb[k]) / scale
                if d > worst:
                    worst, where = d, "%s %s" % (name, column)
    last1, p1 = particles_of(serial)
    last2, p2 = particles_of(dist)
    assert last1.replace(".vtu", "") == last2.replace(".pvtu", ""), (last1, last2)
    assert sorted(p1) == sorted(p2), "the pieces hold %d particles, the run %d" % (len(p2), len(p1))
    scale = max(max(abs(x) for x in u) for u in p1.values()) or 1.0
    for i, u in p1.items():
        d = max(abs(x - y) for x, y in zip(u, p2[i])) / scale
        if d > worst:
            worst, where = d, "snapshot displacement of particle %d" % i
    print("%s on %s ranks: %d series, %d particles; worst relative difference %.3g (%s)" %
          (os.path.basename(scene), ranks, len(series), len(p1), worst, where or "none"))
    if worst > tol:
        raise SystemExit("FAILED: above the tolerance %g" % tol)


if __name__ == "__main__":
    main()
