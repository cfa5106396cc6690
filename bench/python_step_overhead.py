#!/usr/bin/env python3
"""The cost of stepping from Python (issue 28, item 5): `sim.step(1)` called
N times against `mfsd run` of the same N steps, for the oscillating plate at
H/dp 28 (11,008 particles). Each form runs --repeats times, alternating;
the step time is the wall time of the N steps divided by N (the CLI's from
timing.json's stage sum; Python's from a perf_counter around the loop, so it
includes the call, the GIL release and the signal-handler swap of each step).
Writes bench/results/python_step_overhead-DATE.{json,md}.

  PYTHONPATH=build/python python3 bench/python_step_overhead.py [--steps 400] [--repeats 5] [--threads 2]
"""
import argparse
import datetime
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
sys.path.insert(0, os.path.join(ROOT, "build-cpu", "python"))
sys.path.insert(0, os.path.join(ROOT, "build", "python"))
import mfsd  # noqa: E402

SCENE = os.path.join(ROOT, "configs", "oscillating_plate_2d.json")
SETS = {"constants.H_over_dp": 28, "solver.end_time": 10.0, "output.vtu": False, "output.interval": 100.0,
        "output.probe_interval": 100.0}


def cli(binary, steps, threads, out):
    cmd = [binary, "run", SCENE, "-q", "--threads", str(threads), "-o", out, "--max-steps", str(steps)]
    for k, v in SETS.items():
        cmd += ["--set", "%s=%s" % (k, json.dumps(v))]
    subprocess.run(cmd, check=True)
    t = json.load(open(os.path.join(out, "timing.json")))
    return t["step_seconds"] / steps if "step_seconds" in t else sum(s["seconds"] for s in t["stages"]) / steps


def python(steps, threads, out, chunk):
    sim = mfsd.Simulation(mfsd.Scene.from_file(SCENE, set=SETS), threads=threads, output_dir=out)
    start = time.perf_counter()
    for _ in range(steps // chunk):
        sim.step(chunk)
    seconds = time.perf_counter() - start
    sim.finish()
    return seconds / steps, sim.fields["id"].shape[0]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--steps", type=int, default=400)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    binary = next(p for p in (os.path.join(ROOT, d, "mfsd") for d in ("build", "build-cpu")) if os.path.exists(p))
    work = tempfile.mkdtemp(prefix="mfsd_pybench_")
    runs = {"cli": [], "python step(1)": [], "python step(N)": []}
    particles = 0
    for r in range(a.repeats):
        runs["cli"].append(cli(binary, a.steps, a.threads, os.path.join(work, "cli%d" % r)))
        s, particles = python(a.steps, a.threads, os.path.join(work, "py1_%d" % r), 1)
        runs["python step(1)"].append(s)
        runs["python step(N)"].append(python(a.steps, a.threads, os.path.join(work, "pyN_%d" % r), a.steps)[0])
    med = {k: statistics.median(v) for k, v in runs.items()}
    date = datetime.date.today().isoformat()
    base = os.path.join(ROOT, "bench", "results", "python_step_overhead-" + date)
    json.dump({"date": date, "particles": particles, "steps": a.steps, "threads": a.threads, "runs": runs,
               "median": med}, open(base + ".json", "w"), indent=1)
    lines = ["# Stepping from Python against the CLI, %s" % date, "",
             "`PYTHONPATH=build/python python3 bench/python_step_overhead.py --steps %d --repeats %d --threads %d`; "
             "oscillating plate, H/dp 28, %d particles, double; medians of %d." % (a.steps, a.repeats, a.threads,
                                                                                  particles, a.repeats), "",
             "| form | us per step (median) | vs the CLI | all runs, us |", "|---|---|---|---|"]
    for k, v in runs.items():
        lines.append("| %s | %.1f | %.3f | %s |" % (k, 1e6 * med[k], med[k] / med["cli"],
                                                   ", ".join("%.1f" % (1e6 * x) for x in v)))
    open(base + ".md", "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
