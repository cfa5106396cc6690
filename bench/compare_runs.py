#!/usr/bin/env python3
"""Checks that a speed change did not change results beyond round-off: runs
two mfsd binaries on short versions of the plate, bending-column and
twisting-column scenes (one thread each, double) and prints the largest
relative difference of every probe column and of the final total energy.
Usage: bench/compare_runs.py OLD_MFSD NEW_MFSD [--threads N] [--old-args "ARGS"] [--new-args "ARGS"]
(the same binary twice with different arguments compares run options,
e.g. --new-args "--pair-loop half").
With --all-scenes [--max-steps N] it runs every shipped scene (configs/*.json)
for N steps (default 300) instead and compares every CSV file of the two runs
byte for byte (--old-configs DIR: the old binary reads DIR's scenes): a change that must not change results (a refactoring, a build
option) prints "identical" for each scene."""
import argparse
import shlex
import csv
import os
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
# (name, scene, --set overrides, extra arguments). The last six cover what the
# first three do not: walls and J2 (Taylor bar), contact between bodies,
# rigid bodies with contact, traction loads with the phase field, dynamic
# relaxation, clamps with a rigid punch.
CASES = [
    ("oscillating_plate", "configs/oscillating_plate_2d.json", ["solver.end_time=0.3"], []),
    ("bending_column", "configs/bending_column_3d.json", ["solver.end_time=0.5", "constants.H_over_dp=6"], []),
    ("twisting_column", "configs/twisting_column_3d.json", ["solver.end_time=0.2", "constants.H_over_dp=6"], []),
    ("taylor_bar", "configs/taylor_bar_2d.json", ["constants.H_over_dp=10"], []),
    ("colliding_blocks", "tests/regression/scenes/colliding_blocks_2d.json", [], []),
    ("oobleck_octopus", "configs/oobleck_octopus_2d.json", [], ["--max-steps", "2000"]),
    ("crack_branching", "configs/crack_branching_2d.json",
     ["constants.dp=1e-3", "constants.eps0=0.25e-3", "solver.end_time=3e-5"], []),
    ("hanging_column", "tests/regression/scenes/hanging_column_2d.json", [], ["--max-steps", "2000"]),
    ("punched_block", "tests/regression/scenes/punched_block_2d.json", [], ["--max-steps", "2000"]),
]


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def all_scenes(args):
    """Every configs/*.json for --max-steps steps; every CSV compared byte for byte."""
    scenes = sorted(f for f in os.listdir(os.path.join(ROOT, "configs")) if f.endswith(".json"))
    differ = []
    for scene in scenes:
        outs = []
        for tag, binary, more, configs in (("old", args.old, args.old_args, args.old_configs or "configs"),
                                           ("new", args.new, args.new_args, "configs")):
            out = os.path.join(ROOT, "out", "compare_all", f"{scene[:-5]}_{tag}")
            cmd = [binary, "run", os.path.join(ROOT, configs, scene), "-o", out, "-q", "--threads",
                   str(args.threads), "--max-steps", str(args.max_steps)] + shlex.split(more)
            subprocess.run(cmd, check=True)
            outs.append(out)
        csvs = sorted(f for f in os.listdir(outs[0]) if f.endswith(".csv"))
        if csvs != sorted(f for f in os.listdir(outs[1]) if f.endswith(".csv")):
            print(f"{scene}: the runs wrote different CSV files")
            differ.append(scene)
            continue
        changed = [f for f in csvs
                   if open(os.path.join(outs[0], f), "rb").read() != open(os.path.join(outs[1], f), "rb").read()]
        rows_n = sum(1 for _ in open(os.path.join(outs[0], "energies.csv"))) - 1
        print(f"{scene}: {args.max_steps} steps, {len(csvs)} CSV files ({rows_n} energy rows): "
              + ("identical" if not changed else "DIFFERENT in " + ", ".join(changed)), flush=True)
        if changed:
            differ.append(scene)
    print(f"{len(scenes) - len(differ)} of {len(scenes)} scenes identical" +
          (f"; different: {', '.join(differ)}" if differ else ""))
    return 1 if differ else 0


def main():
    ap = argparse.ArgumentParser(usage=__doc__)
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--old-args", default="")
    ap.add_argument("--new-args", default="")
    ap.add_argument("--all-scenes", action="store_true")
    ap.add_argument("--max-steps", type=int, default=300)
    ap.add_argument("--old-configs", help="the old binary's scenes (its checkout's configs/, when a scene gained a key)")
    args = ap.parse_args()
    if args.all_scenes:
        sys.exit(all_scenes(args))
    worst_all = 0.0
    for name, scene, sets, extra in CASES:
        outs = []
        for tag, binary, more in (("old", args.old, args.old_args), ("new", args.new, args.new_args)):
            out = os.path.join(ROOT, "out", "compare", f"{name}_{tag}")
            cmd = [binary, "run", os.path.join(ROOT, scene), "-o", out, "-q", "--threads", str(args.threads)]
            cmd += extra + shlex.split(more)
            for s in sets:
                cmd += ["--set", s]
            subprocess.run(cmd, check=True)
            outs.append(out)
        a, b = (rows(os.path.join(o, "probes.csv")) for o in outs)
        if len(a) != len(b):
            print(f"{name}: different number of probe rows ({len(a)} vs {len(b)})")
            worst_all = float("inf")
            continue
        worst, key = 0.0, None
        for ra, rb in zip(a, b):
            for k in ra:
                if k == "time":
                    continue
                d = abs(float(ra[k]) - float(rb[k])) / (1.0 + abs(float(ra[k])))
                if d > worst:
                    worst, key = d, k
        ea, eb = (rows(os.path.join(o, "energies.csv"))[-1]["total"] for o in outs)
        de = abs(float(ea) - float(eb)) / abs(float(ea))
        print(f"{name}: {len(a)} probe rows, largest relative difference {worst:.2e} ({key}); "
              f"final total energy {ea} vs {eb} ({de:.2e})")
        worst_all = max(worst_all, worst, de)
    print(f"largest relative difference: {worst_all:.2e} (probes.csv and energies.csv print 10 digits)")


if __name__ == "__main__":
    main()
