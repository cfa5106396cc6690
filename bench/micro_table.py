#!/usr/bin/env python3
"""Markdown table of a Google Benchmark JSON file (scripts/bench.sh micro):
time per call and particles per second of each stage microbenchmark."""
import json
import os
import sys


def main(path):
    with open(path) as f:
        data = json.load(f)
    ctx = data.get("context", {})
    lines = [f"# Microbenchmarks, {ctx.get('date', '')}", "",
             f"Command: `scripts/bench.sh micro`  ",
             f"Machine: {ctx.get('num_cpus')} CPUs at {ctx.get('mhz_per_cpu')} MHz, "
             f"load average {', '.join(f'{x:.2f}' for x in ctx.get('load_avg', []))}; "
             f"OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'all')}; "
             "85,184 particles (44^3 jittered lattice), about 52 neighbours, genog, neo-Hookean.", "",
             "Force argument: /0 = scalar loop on separate Q, F^-1, u; /1 = packed neighbour record (the solver's CPU path).",
             "", "| benchmark | ms per call | M particles / s |", "|---|---|---|"]
    for b in data["benchmarks"]:
        ms = b["real_time"] if b.get("time_unit") == "ms" else b["real_time"] / 1e6
        lines.append(f"| {b['name']} | {ms:.2f} | {b.get('items_per_second', 0) / 1e6:.2f} |")
    out = os.path.splitext(path)[0] + ".md"
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"[bench] wrote {out}", file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv[1])
