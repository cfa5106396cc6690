#!/usr/bin/env python3
"""Where do the cpu and cuda backends part? Runs each case on both backends
for a few steps with a snapshot after every step (double precision) and
prints, per step, the largest velocity and displacement difference relative
to the largest value, and for the first step that differs beyond round-off
the particle that differs most (id, body, constrained flag, position).

  python3 scripts/gpu_divergence.py [--binary build/mfsd] [--steps 20]

Needs a CUDA device; used by scripts/gpu_check.sh when the cross-backend tests fail."""
import argparse
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, ".."))
sys.path.insert(0, os.path.join(HERE, "validation"))
import numpy as np  # noqa: E402
import vtu  # noqa: E402

CASES = [
    ("oscillating_plate_2d", ["constants.H_over_dp=10"]),
    ("cantilever_beam_2d", ["constants.dp=0.002"]),
    ("taylor_bar_2d", ["constants.H_over_dp=10"]),
    ("flyer_plate_2d", ["constants.L_over_dp=20"]),
    ("cantilever_large_deformation_3d", ["constants.dp=0.002", "constants.Tmax=0.0005"]),
    ("crack_branching_2d", ["constants.dp=0.5e-3"]),
]


def end_time(binary, case, sets, out):
    """The scene's end time as resolved by mfsd (it may be an expression)."""
    cmd = [binary, "run", os.path.join(ROOT, "configs", case + ".json"), "-o", out, "-q", "--max-steps", "1"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "run.json")) as f:
        return float(json.load(f)["scene"]["solver"]["end_time"])


def run(binary, case, sets, backend, steps, out):
    # A snapshot after every step: the smallest interval mfsd accepts
    # (end_time / 1e9) is far below any step of these cases.
    interval = 1.001e-9 * end_time(binary, case, sets, out + "_end_time")
    cmd = [binary, "run", os.path.join(ROOT, "configs", case + ".json"), "-o", out, "-q", "--backend", backend,
           "--max-steps", str(steps), "--set", f"output.interval={interval!r}",
           "--set", f"output.probe_interval={interval!r}"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return [vtu.read_vtu(p) for _, p in vtu.snapshots(out) if "_rigid_" not in p]


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "mfsd"))
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "gpu_divergence"))
    ap.add_argument("--backends", default="cpu,cuda", help="the two backends compared (cpu,cpu checks the script)")
    args = ap.parse_args()
    for case, sets in CASES:
        first, second = args.backends.split(",")
        a = run(args.binary, case, sets, first, args.steps, os.path.join(args.out, case + "_a"))
        b = run(args.binary, case, sets, second, args.steps, os.path.join(args.out, case + "_b"))
        print(f"== {case} {' '.join(sets)}: {len(a)} / {len(b)} snapshots")
        reported = False
        for k, (x, y) in enumerate(zip(a, b)):
            order_x, order_y = np.argsort(x["id"]), np.argsort(y["id"])
            rel = {}
            for f in ("velocity", "displacement"):
                fx, fy = np.asarray(x[f], float)[order_x], np.asarray(y[f], float)[order_y]
                scale = max(np.abs(fx).max(), 1e-300)
                rel[f] = np.abs(fx - fy).max() / scale
            print(f"  snapshot {k:3d}: velocity {rel['velocity']:.2e}  displacement {rel['displacement']:.2e}")
            if not reported and max(rel.values()) > 1e-13:
                reported = True
                fx = np.asarray(x["velocity"], float)[order_x]
                fy = np.asarray(y["velocity"], float)[order_y]
                d = np.abs(fx - fy).max(axis=1)
                worst = np.argsort(d)[::-1][:5]
                for i in worst:
                    j = order_x[i]
                    print(f"    id {int(x['id'][j])} body {int(x['body'][j])} constrained {int(x['constrained'][j])} "
                          f"at {np.asarray(x['points'], float)[j][:3]}: |dv| = {d[i]:.3e}, v_cpu = {fx[i]}, "
                          f"v_cuda = {fy[i]}")


if __name__ == "__main__":
    main()
