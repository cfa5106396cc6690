#!/usr/bin/env python3
"""Two mfsd binaries on one case, alternated in one run (A B A B ...), so that
the machine's drift falls on both alike: the median particle-steps/s of each
and their ratio. For speed changes measured before and after a commit
(docs/performance.md quotes such runs with this command).

Usage: bench/ab_binaries.py OLD_BINARY NEW_BINARY SCENE [--set k=v ...]
       [--threads 2] [--steps 300] [--repeats 3] [--precision double]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("old")
    p.add_argument("new")
    p.add_argument("scene")
    p.add_argument("--set", action="append", default=[], dest="sets")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--steps", type=int, default=300)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--precision", default="double")
    a = p.parse_args()
    rates = {a.old: [], a.new: []}
    with tempfile.TemporaryDirectory() as out:
        for _ in range(a.repeats):
            for binary in (a.old, a.new):
                cmd = [binary, "run", a.scene, "-q", "-o", out, "--threads", str(a.threads), "--precision",
                       a.precision, "--max-steps", str(a.steps + 5), "--warmup-steps", "5",
                       "--set", "output.vtu=false", "--set", "output.interval=1e9", "--set", "output.probe_interval=1e9"]
                for s in a.sets:
                    cmd += ["--set", s]
                if subprocess.run(cmd).returncode != 0:
                    sys.exit(f"failed: {' '.join(cmd)}")
                with open(os.path.join(out, "timing.json")) as f:
                    rates[binary].append(json.load(f)["particle_steps_per_second"])
    old, new = statistics.median(rates[a.old]), statistics.median(rates[a.new])
    for name, binary in (("old", a.old), ("new", a.new)):
        version = subprocess.run([binary, "--version"], capture_output=True, text=True).stdout.split("\n")[0]
        print(f"{name}: {version}: median {statistics.median(rates[binary]) / 1e6:.3f} M particle-steps/s "
              f"({', '.join(f'{r / 1e6:.3f}' for r in rates[binary])})")
    print(f"new / old = {new / old:.3f}; load average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
