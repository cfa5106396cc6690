#!/usr/bin/env python3
"""The CPU pair loops side by side (issue 24, item 1): each case run with
--pair-loop full and --pair-loop half, alternating, REPEATS times; prints the
median ns per particle-step of every stage and of the step, and half / full.
docs/performance.md, "The half-pair loop".
Usage: bench/pair_loop_ab.py [BINARY] [--repeats N] [--threads T] [--only NAME]"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
# (name, scene, steps, --set overrides)
CASES = [
    ("plate 2-D H/dp 40, genog", "configs/oscillating_plate_2d.json", 400, ["constants.H_over_dp=40"]),
    ("cantilever beam 2-D 64k, genog", "configs/cantilever_beam_2d.json", 100, ["constants.dp=0.00025"]),
    ("bending column 3-D H/dp 12, genog", "configs/bending_column_3d.json", 100, ["constants.H_over_dp=12"]),
    ("bending column 3-D H/dp 24, genog", "configs/bending_column_3d.json", 40, ["constants.H_over_dp=24"]),
    ("bending column 3-D H/dp 24, genog, float", "configs/bending_column_3d.json", 40,
     ["constants.H_over_dp=24", "solver.precision=float"]),
    ("bending column 3-D H/dp 24, laplacian", "configs/bending_column_3d.json", 40,
     ["constants.H_over_dp=24", "solver.hourglass=laplacian"]),
    ("twisting column 3-D H/dp 12, h = 1.65 dp, genog", "configs/twisting_column_3d.json", 60,
     ["constants.H_over_dp=12", "solver.h_over_dp=1.65"]),
    # Issue 24's side-by-side case against SoliDualSPHysics: about 51k
    # particles and 154 neighbours (target <= 3.5 ns per pair-step, double).
    ("twisting column 3-D H/dp 20, h = 1.66 dp, genog", "configs/twisting_column_3d.json", 20,
     ["constants.H_over_dp=20", "solver.h_over_dp=1.66"]),
]


def run(binary, scene, steps, sets, loop, threads, out):
    cmd = [binary, "run", os.path.join(ROOT, scene), "-o", out, "-q", "--threads", str(threads),
           "--max-steps", str(steps + 5), "--warmup-steps", "5", "--pair-loop", loop,
           "--set", "output.vtu=false", "--set", "output.interval=1e9", "--set", "output.probe_interval=1e9"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True)
    t = json.load(open(os.path.join(out, "timing.json")))
    r = json.load(open(os.path.join(out, "run.json")))
    assert r["pair_loop"] == loop, (r["pair_loop"], loop)
    stages = {s["name"]: s["nanoseconds_per_particle_step"] for s in t["stages"]}
    stages["step"] = sum(stages.values())
    return stages, t["particles"], r["neighbors"]["mean"], t.get("bytes_per_particle")


def main():
    ap = argparse.ArgumentParser(usage=__doc__)
    ap.add_argument("binary", nargs="?", default=os.path.join(ROOT, "build", "mfsd"))
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--only", default="")
    a = ap.parse_args()
    with open("/proc/loadavg") as f:
        load = f.read().split()[0]
    print(f"binary {a.binary}; {os.cpu_count()} cores, {a.threads} threads; load average {load}; "
          f"median of {a.repeats}, ns per particle-step")
    print("| case | particles | neighbours | loop | force | deformation_rate | step | step per pair | B/particle |")
    print("|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name, scene, steps, sets in CASES:
            if a.only and a.only not in name:
                continue
            res = {"full": [], "half": []}
            info = {}
            for _ in range(a.repeats):
                for loop in ("full", "half"):
                    st, n, nb, bpp = run(a.binary, scene, steps, sets, loop, a.threads, os.path.join(tmp, loop))
                    res[loop].append(st)
                    info[loop] = (n, nb, bpp)
            med = {l: {k: statistics.median(s[k] for s in res[l]) for k in res[l][0]} for l in res}
            for l in ("full", "half"):
                n, nb, bpp = info[l]
                m = med[l]
                nbs = f"{nb:.1f}" if isinstance(nb, (int, float)) else "?"
                bps = f"{bpp:.0f}" if bpp else "?"
                per_pair = f"{m['step'] / nb:.2f}" if isinstance(nb, (int, float)) and nb else "?"
                print(f"| {name} | {n} | {nbs} | {l} | {m['force']:.0f} | {m['deformation_rate']:.0f} | "
                      f"{m['step']:.0f} | {per_pair} | {bps} |")
            print(f"| {name} | | | half / full | {med['half']['force'] / med['full']['force']:.2f} | "
                  f"{med['half']['deformation_rate'] / med['full']['deformation_rate']:.2f} | "
                  f"{med['half']['step'] / med['full']['step']:.2f} | | |", flush=True)


if __name__ == "__main__":
    main()
