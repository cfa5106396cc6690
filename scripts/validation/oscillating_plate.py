#!/usr/bin/env python3
"""Oscillating plate 2D (seed 000 section 5.1, seed 003 section 4.1).

  table        H/dp = 40, nu in {0.22, 0.30, 0.40}, vf in {0.05, 0.1}, genog and
               laplacian: period against seed 000 Table 1 (genog) and seed 003
               Table 1 (laplacian) and against theory (eq. 42).
  convergence  H/dp = 10, 20, 40 (nu = 0.3, vf = 0.05, the Table 1 case, so that
               the H/dp = 40 end point is a seed value): tip history and period
               against resolution; justifies the CI tolerance at H/dp = 10.

  variants     H/dp = 40, nu = 0.3, vf = 0.05: the holder fully constrained
               (instead of the frame of the authors' code) with genog, and
               laplacian with B0 in the remaining-stress force sum.

Writes docs/validation/oscillating_plate_<study>.json and .md and PNG plots.
Usage: scripts/validation/oscillating_plate.py table|convergence|variants [--threads N]
"""
import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402

CONFIG = "configs/oscillating_plate_2d.json"
DOCS = os.path.join(m.ROOT, "docs", "validation")
OUT = os.path.join(m.ROOT, "out", "validation", "oscillating_plate")

# Seed 000 Table 1 (SPH-GENOG) and seed 003 Table 1 (TL-SPH-HF), H/dp = 40, H = 0.02.
SEED = {
    ("genog", 0.05, 0.22): 0.29355, ("genog", 0.1, 0.22): 0.29261,
    ("genog", 0.05, 0.30): 0.28201, ("genog", 0.1, 0.30): 0.28088,
    ("genog", 0.05, 0.40): 0.26634, ("genog", 0.1, 0.40): 0.26515,
    ("laplacian", 0.05, 0.22): 0.29428, ("laplacian", 0.1, 0.22): 0.29373,
    ("laplacian", 0.05, 0.30): 0.28166, ("laplacian", 0.1, 0.30): 0.28096,
    ("laplacian", 0.05, 0.40): 0.26473, ("laplacian", 0.1, 0.40): 0.26382,
}


def theory_period(nu, E=2.0e6, rho=1000.0, H=0.02, L=0.2, kL=1.875):
    """Seed 000 eq. 42: omega^2 = E H^2 k^4 / (12 rho (1 - nu^2))."""
    k = kL / L
    omega = math.sqrt(E * H * H * k ** 4 / (12 * rho * (1 - nu * nu)))
    return 2 * math.pi / omega


FULL_HOLDER = json.dumps({"box": {"min": ["-(holder+4*dp)", "-(H/2+4*dp)"], "max": [0, "H/2+4*dp"]}})


def run_case(hourglass, vf, nu, res, end_time, threads, vtu=False, more=None, tag=""):
    name = f"{hourglass}_vf{vf}_nu{nu}_H{res}{tag}"
    out = os.path.join(OUT, name)
    sets = {
        "solver.hourglass": hourglass,
        "constants.vf": vf,
        "constants.H_over_dp": res,
        "bodies.plate.material.poisson_ratio": nu,
        "solver.end_time": end_time,
        "output.vtu": "true" if vtu else "false",
    }
    sets.update(more or {})
    extra = ["--threads", str(threads)] if threads else []
    if m.run(CONFIG, sets, out, extra) != 0:
        raise SystemExit(f"run {name} failed")
    p = m.read_csv(os.path.join(out, "probes.csv"))
    timing = m.read_json(os.path.join(out, "timing.json"))
    return {
        "hourglass": hourglass, "vf": vf, "nu": nu, "H_over_dp": res,
        "period": m.period(p["time"], p["tip.position.y"]),
        "first_period": m.first_period(p["time"], p["tip.position.y"]),
        "particles": timing["particles"], "steps": timing["steps"],
        "wall_seconds": timing["wall_seconds"], "output": os.path.relpath(out, m.ROOT),
        "time": p["time"], "tip_y": p["tip.position.y"],
    }


def save(study, payload):
    os.makedirs(DOCS, exist_ok=True)
    path = os.path.join(DOCS, f"oscillating_plate_{study}.json")
    with open(path, "w") as f:
        json.dump(payload, f, indent=1)
    print("wrote", os.path.relpath(path, m.ROOT))


def table(threads):
    rows = []
    for hourglass in ("genog", "laplacian"):
        for nu in (0.22, 0.30, 0.40):
            for vf in (0.05, 0.1):
                r = run_case(hourglass, vf, nu, 40, 0.62, threads)
                r.pop("time"), r.pop("tip_y")
                r["seed"] = SEED[(hourglass, vf, nu)]
                r["theory"] = theory_period(nu)
                r["error_vs_seed"] = r["period"] / r["seed"] - 1
                r["error_vs_theory"] = r["period"] / r["theory"] - 1
                rows.append(r)
                print(f"{hourglass:9s} nu={nu} vf={vf}: T={r['period']:.5f} seed={r['seed']:.5f} "
                      f"({100 * r['error_vs_seed']:+.2f} %) theory={r['theory']:.5f}", flush=True)
    md = ["| variant | nu | v_f | T mfsd [s] | T seed [s] | vs seed | T theory [s] | vs theory | particles |",
          "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        src = "seed 000 T1" if r["hourglass"] == "genog" else "seed 003 T1"
        md.append(f"| {r['hourglass']} | {r['nu']:.2f} | {r['vf']} | {r['period']:.5f} | {r['seed']:.5f} ({src}) | "
                  f"{100 * r['error_vs_seed']:+.2f} % | {r['theory']:.5f} | {100 * r['error_vs_theory']:+.2f} % | "
                  f"{r['particles']} |")
    save("table", {"command": "scripts/validation/oscillating_plate.py table", "machine": m.machine(), "rows": rows})
    with open(os.path.join(DOCS, "oscillating_plate_table.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))


def convergence(threads):
    runs = []
    for hourglass in ("genog", "laplacian"):
        for res in (10, 20, 40):
            r = run_case(hourglass, 0.05, 0.3, res, 1.0, threads)
            print(f"{hourglass} H/dp={res}: T={r['period']:.5f}", flush=True)
            runs.append(r)
    theory = theory_period(0.3)
    save("convergence", {"command": "scripts/validation/oscillating_plate.py convergence", "machine": m.machine(),
                         "theory": theory,
                         "runs": [{k: v for k, v in r.items() if k not in ("time", "tip_y")} for r in runs]})
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for ax, hourglass in zip(axes, ("genog", "laplacian")):
        for r in runs:
            if r["hourglass"] == hourglass:
                ax.plot(r["time"], r["tip_y"], label=f"H/dp = {r['H_over_dp']} (T = {r['period']:.4f} s)")
        ax.set_title(f"{hourglass}: tip midpoint, nu = 0.3, v_f = 0.05")
        ax.set_xlabel("t [s]")
        ax.set_ylabel("y [m]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(DOCS, "oscillating_plate_convergence.png"), dpi=120)
    fig, ax = plt.subplots(figsize=(5, 4))
    for hourglass, mk in (("genog", "o-"), ("laplacian", "s-")):
        rs = [r for r in runs if r["hourglass"] == hourglass]
        ax.plot([0.02 / r["H_over_dp"] for r in rs], [r["period"] for r in rs], mk, label=hourglass)
    ax.axhline(theory, color="k", ls="--", lw=1, label="theory (eq. 42)")
    ax.plot([0.0005], [SEED[("genog", 0.05, 0.30)]], "k^", label="seed 000 Table 1 (genog)")
    ax.plot([0.0005], [SEED[("laplacian", 0.05, 0.30)]], "kv", label="seed 003 Table 1 (laplacian)")
    ax.set_xscale("log")
    ax.set_xlabel("dp [m]")
    ax.set_ylabel("period T [s]")
    ax.set_title("Oscillating plate: period vs resolution")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(DOCS, "oscillating_plate_period_vs_dp.png"), dpi=120)
    print("wrote plots to", os.path.relpath(DOCS, m.ROOT))


def variants(threads):
    rows = []
    for hourglass, more, tag, what in (
            ("genog", {"clamps.0.region": FULL_HOLDER}, "_full_holder", "holder block fully constrained"),
            ("laplacian", {"solver.kernel_correction_in_force": "true"}, "_B0_in_force",
             "B0 in the remaining-stress force sum")):
        r = run_case(hourglass, 0.05, 0.3, 40, 0.62, threads, more=more, tag=tag)
        r.pop("time"), r.pop("tip_y")
        r["variant"] = what
        r["seed"] = SEED[(hourglass, 0.05, 0.3)]
        r["error_vs_seed"] = r["period"] / r["seed"] - 1
        rows.append(r)
        print(f"{hourglass} {what}: T={r['period']:.5f} ({100 * r['error_vs_seed']:+.2f} % vs seed)", flush=True)
    save("variants", {"command": "scripts/validation/oscillating_plate.py variants", "machine": m.machine(),
                      "rows": rows})


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("study", choices=["table", "convergence", "variants"])
    ap.add_argument("--threads", type=int, default=0)
    a = ap.parse_args()
    {"table": table, "convergence": convergence, "variants": variants}[a.study](a.threads)
