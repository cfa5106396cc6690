#!/usr/bin/env python3
"""Bending and twisting columns 3D (seed 000 sections 5.2-5.3, seed 003 sections 4.4-4.5).

  bending   H/dp = 4, 6, 12 to 3 s (genog; laplacian and none at 6 and 12):
            z(t) of point S (centre of the top face, mean of the particles
            within dp of it) and its first minimum. Hard case v0 = 20 m/s
            (genog and none, H/dp = 6 and 12).
  twisting  Omega0 = 105 (nu = 0.499) and 300 (nu = 0.49), H/dp = 4, 6, 10, to
            0.5 s, genog, laplacian and none: hourglass indicator over time and
            the final particle configuration (plots at H/dp = 10); and the
            energy kept by the isotropic and split damping forms (H/dp = 6).

Writes docs/validation/<study>_column.json and PNG plots.
Usage: scripts/validation/columns.py bending|twisting [--threads N] [--quick]
"""
import argparse
import glob
import json
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402
import vtu  # noqa: E402

DOCS = os.path.join(m.ROOT, "docs", "validation")
OUT = os.path.join(m.ROOT, "out", "validation")


def run(config, name, sets, threads):
    out = os.path.join(OUT, name)
    extra = ["--threads", str(threads)] if threads else []
    rc = m.run(config, sets, out, extra)
    e = m.read_csv(os.path.join(out, "energies.csv"))
    p = m.read_csv(os.path.join(out, "probes.csv"))
    t = m.read_json(os.path.join(out, "timing.json"))
    r = m.read_json(os.path.join(out, "run.json"))
    return {"name": name, "exit_code": rc, "status": r["status"], "out": out, "energies": e, "probes": p,
            "particles": t["particles"], "steps": t["steps"], "simulated_time": t["simulated_time"],
            "particle_steps_per_second": t["particle_steps_per_second"], "sets": sets}


def summary(r):
    e = r["energies"]
    s = {k: r[k] for k in ("name", "exit_code", "status", "particles", "steps", "simulated_time",
                           "particle_steps_per_second", "sets")} | {
        "hourglass_max_final": e["hourglass_max"][-1], "hourglass_mean_final": e["hourglass_mean"][-1],
        "hourglass_mean_peak": max(e["hourglass_mean"]), "total_energy_initial": e["total"][0],
        "total_energy_final": e["total"][-1]}
    p = r["probes"]
    if "S.position.z" in p:  # bending: first minimum of z(S) before 0.8 s
        k = min((i for i, t in enumerate(p["time"]) if t < 0.8), key=lambda i: p["S.position.z"][i])
        s["first_minimum_z"] = p["S.position.z"][k]
        s["first_minimum_t"] = p["time"][k]
    return s


def plt_setup():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def snapshot_axes(fig, pos, r, title, up=2, elev=20, azim=-60):
    """Last snapshot of run r as a 3-D scatter coloured by von Mises; `up` is the column axis."""
    files = sorted(glob.glob(os.path.join(r["out"], "snapshots", "*.vtu")))
    d = vtu.read_vtu(files[-1])
    ax = fig.add_subplot(*pos, projection="3d")
    order = [a for a in range(3) if a != up] + [up]
    x = d["points"][:, order]
    sc = ax.scatter(x[:, 0], x[:, 1], x[:, 2], c=d["von_mises"], s=2, cmap="jet")
    ax.set_title(title, fontsize=9)
    ax.view_init(elev=elev, azim=azim)
    ax.set_box_aspect(np.ptp(x, axis=0) + 1e-9)
    ax.set_axis_off()
    fig.colorbar(sc, ax=ax, shrink=0.6, label="von Mises [Pa]")


def save(study, payload):
    os.makedirs(DOCS, exist_ok=True)
    with open(os.path.join(DOCS, f"{study}_column.json"), "w") as f:
        json.dump(payload, f, indent=1)


def bending(threads, quick):
    cfg = "configs/bending_column_3d.json"
    res = [4, 6] if quick else [4, 6, 12]
    runs = []
    for hdp in res:
        runs.append(run(cfg, f"bending_genog_H{hdp}", {"constants.H_over_dp": hdp, "output.interval": 0.1}, threads))
    for hdp in res[-2:]:
        for hg in ("laplacian", "none"):
            runs.append(run(cfg, f"bending_{hg}_H{hdp}", {"constants.H_over_dp": hdp, "solver.hourglass": hg,
                                                           "output.interval": 0.1}, threads))
    hard = []
    for hdp in res[-2:]:
        for hg in ("genog", "none"):
            hard.append(run(cfg, f"bending_hard_{hg}_H{hdp}", {"constants.H_over_dp": hdp, "solver.hourglass": hg,
                                                                "constants.v0": 20, "output.interval": 0.05},
                            threads))
    top = res[-1]
    shown = [r for r in runs if r["name"].endswith(f"_H{top}") or r["name"] == f"bending_genog_H{res[-2]}"]
    hard_top = [r for r in hard if r["name"].endswith(f"_H{top}")]
    save("bending", {"command": "scripts/validation/columns.py bending", "machine": m.machine(),
                     "runs": [summary(r) for r in runs + hard]})
    plt = plt_setup()
    fig, ax = plt.subplots(figsize=(7, 4))
    for r in shown:
        ax.plot(r["probes"]["time"], r["probes"]["S.position.z"], label=r["name"].replace("bending_", ""))
    ax.set_xlabel("t [s]")
    ax.set_ylabel("z of S [m]")
    ax.set_title("Bending column, v0 = 10 m/s: top-face centre S")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(DOCS, "bending_column_z.png"), dpi=120)
    fig = plt.figure(figsize=(11, 4.5))
    for k, r in enumerate(hard_top):
        snapshot_axes(fig, (1, 3, k + 1), r, f"v0 = 20 m/s, {r['name'].split('_')[2]}, t = {r['simulated_time']:.2f} s")
    ax = fig.add_subplot(1, 3, 3)
    for r in hard_top:
        ax.plot(r["energies"]["time"], r["energies"]["hourglass_mean"], label=r["name"].split("_")[2])
    ax.set_xlabel("t [s]")
    ax.set_ylabel("mean hourglass indicator")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(DOCS, "bending_column_hard.png"), dpi=120)


def twisting(threads, quick):
    cfg = "configs/twisting_column_3d.json"
    resolutions = [4, 6] if quick else [4, 6, 10]
    hdp = resolutions[-1]
    runs = []
    for res in resolutions:
        for omega, nu in ((105, 0.499), (300, 0.49)):
            for hg in ("genog", "laplacian", "none"):
                runs.append(run(cfg, f"twisting_{omega}_{hg}_H{res}",
                                {"constants.H_over_dp": res, "constants.Omega0": omega,
                                 "bodies.column.material.poisson_ratio": nu, "solver.hourglass": hg,
                                 "output.interval": 0.01, "output.vtu": "true" if res == hdp else "false"}, threads))
    damping = [run(cfg, f"twisting_105_genog_H6_damping_{form}",
                   {"constants.H_over_dp": 6, "solver.damping.form": form, "output.vtu": "false"}, threads)
               for form in ("isotropic", "split")]
    save("twisting", {"command": "scripts/validation/columns.py twisting", "machine": m.machine(),
                      "runs": [summary(r) for r in runs], "damping": [summary(r) for r in damping]})
    runs = [r for r in runs if r["name"].endswith(f"_H{hdp}")]
    plt = plt_setup()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for ax, omega in zip(axes, (105, 300)):
        for r in runs:
            if f"_{omega}_" in r["name"]:
                ax.semilogy(r["energies"]["time"], r["energies"]["hourglass_mean"], label=r["name"].split("_")[2])
        ax.set_title(f"Twisting column, Omega0 = {omega} rad/s, H/dp = {hdp}")
        ax.set_xlabel("t [s]")
        ax.set_ylabel("mean hourglass indicator")
        ax.grid(alpha=0.3, which="both")
        ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(DOCS, "twisting_column_hourglass.png"), dpi=120)
    fig = plt.figure(figsize=(12, 5))
    for k, r in enumerate([r for r in runs if "_300_" in r["name"]]):
        snapshot_axes(fig, (1, 3, k + 1), r, f"Omega0 = 300, {r['name'].split('_')[2]}, t = {r['simulated_time']:.2f} s",
                      up=1)
    fig.tight_layout()
    fig.savefig(os.path.join(DOCS, "twisting_column_300.png"), dpi=120)


if __name__ == "__main__":
    import numpy as np  # noqa: F401  (used by snapshot_axes)
    globals()["np"] = np
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("study", choices=["bending", "twisting"])
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--quick", action="store_true", help="coarse resolutions, to try the script")
    a = ap.parse_args()
    {"bending": bending, "twisting": twisting}[a.study](a.threads, a.quick)
