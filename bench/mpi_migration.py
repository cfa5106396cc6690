#!/usr/bin/env python3
"""The cost of distributed runs whose particles move through the cuts (issue 25).

`mpiexec -n R mfsd run` with one thread per rank, against the single process
with one thread. ULSPH: the oscillating plate (little motion across the
cut), the J2 Taylor bar on a wall (H/dp 20) and the 3100 m/s disc through a
plate (contact between bodies), whose particles cross the cuts. RKPM: the
plate in its slot, the 3-D J2 Taylor bar to 20 us and Dienes' shear (nodes
migrate; the operators are refreshed). TLSPH with phase-field fracture: the
notched bar (no migration; s and ds/dt refreshed). Reports particle-steps/s (median of --repeats),
the migrations, rebalances and kilobytes moved (the run's report), and the
shares of rank 0's step taken by the migrate and halo stages. Needs an MPI
build (scripts/test.sh --mpi). Ranks beyond the cores share them
(--oversubscribe): say so with the figures. Writes
bench/results/mpi_migration-DATE.{json,md}.

  python3 bench/mpi_migration.py [--repeats 3]
"""
import argparse
import datetime
import json
import os
import re
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
BINARY = next(p for p in (os.path.join(ROOT, d, "mfsd") for d in ("build", "build-cpu")) if os.path.exists(p))
ENV = dict(os.environ, OMP_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_mpi_yield_when_idle="1")
SCENES = {"ULSPH oscillating plate, to 0.05 s": ("oscillating_plate_ulsph_2d.json", ["solver.end_time=0.05"]),
          "ULSPH J2 Taylor bar, H/dp 20": ("taylor_bar_ulsph_2d.json", []),
          "ULSPH disc through a plate (contact)": ("projectile_impact_ulsph_2d.json", []),
          "RKPM plate in its slot, to 0.02 s": ("oscillating_plate_rkpm_2d.json", ["solver.end_time=0.02"]),
          "RKPM J2 Taylor bar 3-D, to 20 us": ("taylor_bar_rkpm_3d.json", ["solver.end_time=2e-5"]),
          "RKPM Dienes shear": ("simple_shear_rkpm_2d.json", []),
          "TLSPH notched bar, phase-field fracture": ("notched_bar_2d.json", [])}


def one_run(scene, ranks, out):
    name, sets = scene
    cmd = [BINARY, "run", scene_path(name), "-o", out, "--threads", "1", "--set",
           "output.vtu=false"]
    for kv in sets:
        cmd += ["--set", kv]
    if ranks:
        cmd = ["mpiexec", "-n", str(ranks), "--oversubscribe"] + cmd
    text = subprocess.run(cmd, env=ENV, capture_output=True, text=True, check=True).stdout
    timing = json.load(open(os.path.join(out, "timing.json")))
    share = lambda name: sum(st["share"] for st in timing["stages"] if st["name"] == name)
    m = re.search(r"migrations: (\d+) \(rebalances (\d+)\), ([\d.]+) kB", text)
    sent = [float(x) for x in re.findall(r"mfsd:\s+\d+\s+\d+\s+\d+\s+([\d.]+)\s+[\d.]+\n", text)]
    return {"particles": timing["particles"], "rate": timing["particle_steps_per_second"],
            "steps": timing.get("steps"), "migrate_share": share("migrate"), "halo_share": share("halo"),
            "migrations": int(m.group(1)) if m else 0, "rebalances": int(m.group(2)) if m else 0,
            "moved_kB": float(m.group(3)) if m else 0.0, "sent_kB_per_step_max": max(sent, default=0.0)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args()
    out = os.path.join(ROOT, "out", "bench", "mpi_migration")
    os.makedirs(out, exist_ok=True)
    cases = []
    for label, scene in SCENES.items():
        for ranks in (0, 2, 4):
            runs = [one_run(scene, ranks, out) for _ in range(a.repeats)]
            r = sorted(runs, key=lambda x: x["rate"])[len(runs) // 2]
            r.update(scene=label, mpi_ranks=ranks, rate_runs=[x["rate"] for x in runs])
            cases.append(r)
            print(label, ranks, "%.3g" % r["rate"], file=sys.stderr)
    date = datetime.date.today().isoformat()
    base = os.path.join(ROOT, "bench", "results", "mpi_migration-" + date)
    json.dump({"date": date, "cores": os.cpu_count(), "cases": cases}, open(base + ".json", "w"), indent=1)
    lines = ["# Moving particles (ULSPH, RKPM) and phase-field fracture on one machine (%d cores), %s" % (os.cpu_count(), date), "",
             "`python3 bench/mpi_migration.py --repeats %d`; one thread per rank, medians; ranks beyond the "
             "cores share them." % a.repeats, "",
             "| scene | processes | particles | M particle-steps/s | vs 1 process | migrations | rebalances "
             "| moved, kB in all | migrate share | halo share | refreshes, kB per step per rank (max) |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for c in cases:
        serial = next(x["rate"] for x in cases if x["scene"] == c["scene"] and x["mpi_ranks"] == 0)
        lines.append("| %s | %s | %d | %.3g | %.2f | %d | %d | %.0f | %.1f %% | %.1f %% | %.1f |" % (
            c["scene"], ("%d (MPI)" % c["mpi_ranks"]) if c["mpi_ranks"] else "1", c["particles"], c["rate"] / 1e6,
            c["rate"] / serial, c["migrations"], c["rebalances"], c["moved_kB"], 100 * c["migrate_share"],
            100 * c["halo_share"], c["sent_kB_per_step_max"]))
    open(base + ".md", "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))


def scene_path(name):
    for folder in ("configs", os.path.join("tests", "regression", "scenes")):
        if os.path.exists(os.path.join(ROOT, folder, name)):
            return os.path.join(ROOT, folder, name)
    raise SystemExit("no scene " + name)


if __name__ == "__main__":
    main()
