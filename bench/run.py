#!/usr/bin/env python3
"""Benchmark suites of mfsd (docs/performance.md):
  throughput  particle-steps/s, per-stage share, memory: bending column 3D and
              oscillating plate 2D at three sizes, 1 and all threads, float and double
  scaling     thread strong scaling and problem-size scaling (time per step vs particles)
  accuracy    speed against error: plate period and bending-column trajectory errors
              against wall time per simulated second, per hourglass variant,
              resolution and precision (Pareto plot)
  roofline    STREAM-like triad and the bandwidth the force and deformation-rate
              stages achieve, as a fraction of it, and the compute roof of one core
  scenes      the seed 001 scenes at the seeds' resolutions: speed, memory, and how
              long their full runs would take
  fracture    the cost of phase-field fracture: the four-point-bending beam with
              SVK, NH, fracture-SVK, fracture-NH and J2 (seed 001 section 4.4)
  all         every suite
Results: bench/results/<suite>-<date>.json, .md and .png."""
import argparse
import os
import shlex
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "suites"))
import bench_lib as b  # noqa: E402

SUITES = ["throughput", "scaling", "accuracy", "roofline", "scenes", "fracture"]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("suite", choices=SUITES + ["all"])
    p.add_argument("--backend", default="cpu", choices=["cpu", "cuda"])
    p.add_argument("--quick", action="store_true", help="smaller cases and one repeat (a smoke run)")
    p.add_argument("--repeats", type=int, default=0, help="repeats per configuration (default 3, quick 1)")
    p.add_argument("--only", default="",
                   help="throughput: only the cases whose label contains this text; accuracy: only those hourglass variants")
    p.add_argument("--mfsd-args", default="", help="extra options for every mfsd run, e.g. \"--pair-layout sliced\"")
    p.add_argument("--tag", default="", help="appended to the results' file names (<suite>-<date>-<tag>)")
    args = p.parse_args()
    if not os.path.exists(b.m.BINARY):
        sys.exit(f"[bench] no mfsd binary at {b.m.BINARY}; run scripts/bench.sh, which builds it")
    args.machine = b.machine(args.backend)
    b.EXTRA_ARGS = shlex.split(args.mfsd_args)
    b.RESULT_TAG = args.tag
    for suite in (SUITES if args.suite == "all" else [args.suite]):
        args.command = "scripts/bench.sh " + shlex.join([suite] + sys.argv[2:])
        __import__(suite).main(args)


if __name__ == "__main__":
    main()
