#!/usr/bin/env python3
"""Strong and weak scaling of the distributed engine on one machine (issue 25).

`mpiexec -n R mfsd run` of the 3-D bending column (genog TLSPH, SVK) with one
thread per rank, against the single process with one and with R threads.
Strong: one resolution on 1, 2, 4 ranks. Weak: about the same particles per
rank. Reports particle-steps/s (median of --repeats), the halo stage's share
of rank 0's step, and the bytes each rank sends per step (the run's rank
table). Needs an MPI build (scripts/test.sh --mpi). On a machine with fewer
cores than ranks the ranks share cores (--oversubscribe): say so with the
figures. Writes bench/results/mpi_scaling-DATE.{json,md}.

  python3 bench/mpi_scaling.py [--repeats 3] [--steps 200]
"""
import argparse
import datetime
import json
import os
import re
import statistics
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
BINARY = next(p for p in (os.path.join(ROOT, d, "mfsd") for d in ("build", "build-cpu")) if os.path.exists(p))
SCENE = os.path.join(ROOT, "configs", "bending_column_3d.json")
ENV = dict(os.environ, OMP_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def one_run(ranks, threads, h_over_dp, steps, out):
    cmd = [BINARY, "run", SCENE, "-o", out, "--threads", str(threads), "--max-steps", str(steps), "--warmup-steps",
           str(steps // 10), "--set", "constants.H_over_dp=%g" % h_over_dp, "--set", "output.vtu=false", "--set",
           "output.interval=1e9", "--set", "output.probe_interval=1e9"]
    if ranks:
        cmd = ["mpiexec", "-n", str(ranks), "--oversubscribe"] + cmd
    text = subprocess.run(cmd, env=dict(ENV, OMP_NUM_THREADS=str(threads)), capture_output=True, text=True,
                          check=True).stdout
    timing = json.load(open(os.path.join(out, "timing.json")))
    halo = sum(st["share"] for st in timing["stages"] if st["name"] == "halo")
    rows = re.findall(r"mfsd:\s+(\d+)\s+(\d+)\s+(\d+)\s+([\d.]+)\s+([\d.]+)\n", text)
    return {"particles": timing["particles"], "rate": timing["particle_steps_per_second"],
            "halo_share": halo,
            "ranks": [{"owned": int(r[1]), "ghosts": int(r[2]), "sent_kB_per_step": float(r[3]),
                       "exchanges_per_step": float(r[4])} for r in rows]}


def median_run(repeats, *args):
    runs = [one_run(*args) for _ in range(repeats)]
    best = sorted(runs, key=lambda r: r["rate"])[len(runs) // 2]
    best["rate_runs"] = [r["rate"] for r in runs]
    return best


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--strong", type=float, default=16, help="H/dp of the strong-scaling column")
    a = ap.parse_args()
    out = os.path.join(ROOT, "out", "bench", "mpi_scaling")
    os.makedirs(out, exist_ok=True)
    cores = os.cpu_count()
    cases = []
    for kind, ranks, h in [("strong", 0, a.strong), ("strong", 1, a.strong), ("strong", 2, a.strong),
                           ("strong", 4, a.strong), ("weak", 1, 12), ("weak", 2, 15), ("weak", 4, 19)]:
        r = median_run(a.repeats, ranks, 1, h, a.steps, out)
        r.update(kind=kind, mpi_ranks=ranks, h_over_dp=h, threads=1)
        cases.append(r)
        print(kind, ranks, h, "%.3g" % r["rate"], file=sys.stderr)
    # The OpenMP alternative on the same cores: one process, 2 threads.
    r = median_run(a.repeats, 0, min(2, cores), a.strong, a.steps, out)
    r.update(kind="strong", mpi_ranks=0, h_over_dp=a.strong, threads=min(2, cores))
    cases.append(r)
    date = datetime.date.today().isoformat()
    base = os.path.join(ROOT, "bench", "results", "mpi_scaling-" + date)
    json.dump({"date": date, "cores": cores, "steps": a.steps, "cases": cases}, open(base + ".json", "w"), indent=1)
    serial = next(c["rate"] for c in cases if c["kind"] == "strong" and c["mpi_ranks"] == 0 and c["threads"] == 1)
    lines = ["# Distributed engine on one machine (%d cores), %s" % (cores, date), "",
             "`python3 bench/mpi_scaling.py --repeats %d --steps %d`; 3-D bending column, genog TLSPH, double, "
             "one thread per rank; ranks beyond the cores share them." % (a.repeats, a.steps), "",
             "| scaling | processes | threads each | H/dp | particles | particles per rank | M particle-steps/s "
             "| vs 1 process, 1 thread | halo share of rank 0's step | ghosts per rank (max) | sent per rank per step, kB (max) |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for c in cases:
        n = max(1, c["mpi_ranks"])
        ghosts = max((r["ghosts"] for r in c["ranks"]), default=0)
        sent = max((r["sent_kB_per_step"] for r in c["ranks"]), default=0.0)
        lines.append("| %s | %s | %d | %g | %d | %d | %.3g | %.2f | %.1f %% | %d | %.1f |" % (
            c["kind"], ("%d (MPI)" % c["mpi_ranks"]) if c["mpi_ranks"] else "1", c["threads"], c["h_over_dp"],
            c["particles"], c["particles"] // n, c["rate"] / 1e6, c["rate"] / serial, 100 * c["halo_share"], ghosts, sent))
    open(base + ".md", "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
