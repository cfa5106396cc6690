#!/usr/bin/env python3
"""Holzapfel-Ogden and active muscle (seed 000 sections 3.3-3.4, 5.2-5.4; issue 21).

  muscle     configs/muscle_contraction_3d.json at dp = 0.1, 0.05, 0.025 (--res
             10 20 40: cells per unit length): u_x(t) of the top-face centre
             (mean of the particles within dp of (1 - dp/2, 1/2, 1/2)), its
             value at t = 1.2 s against seed 000 Table 5, its maximum, and the
             energy balance with the active stress's work; with --long also
             to t = 4 s (the static answer the ramped activation tends to).
  bending    configs/bending_column_ho_3d.json, a_f/a = 0 (isotropic), 0.1,
             0.5, 1.0 at H/dp = 6 (--res) to 3 s: z(t) of S (seed 000 Fig. 7, 9)
             and its first minimum.
  twisting   configs/twisting_column_ho_3d.json, Omega0 = 330 and 480 rad/s,
             genog and none, H/dp = 6 (--res) to 0.5 s: the mean hourglass
             indicator over time (seed 000 Fig. 14-16).

Writes docs/validation/holzapfel_ogden_<study>.json and .png.
Usage: scripts/validation/holzapfel_ogden.py muscle|bending|twisting [--res N ...] [--threads N] [--reuse] [--long]
"""
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402

OUT = os.path.join(m.ROOT, "out", "validation", "holzapfel_ogden")
SEED_TABLE5 = {10: 0.4988, 20: 0.5248, 40: 0.5355}  # top displacement at dp = 1/res (reference 0.535)


def balance(e):
    return {"active_work": e["active_work"][-1], "balance": e["balance"][-1], "damping": e["damping"][-1],
            "kinetic": e["kinetic"][-1], "strain": e["strain"][-1]}


def muscle(args, plt):
    res = args.res or [10, 20, 40]
    runs = []
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for n in res:
        for end in ([1.2, 4.0] if args.long else [1.2]):
            out = os.path.join(OUT, f"muscle_{n}_{end:g}")
            p, e, t = m.run_and_read("configs/muscle_contraction_3d.json",
                                     {"constants.dp": 1.0 / n, "solver.end_time": end}, out, args.threads, args.reuse)
            u = p["top.displacement.x"]
            r = {"res": n, "dp": 1.0 / n, "end_time": end, "particles": t["particles"], "steps": t["steps"],
                 "u_final": u[-1], "u_max": max(u), "t_of_max": p["time"][u.index(max(u))],
                 "seed_table5": SEED_TABLE5.get(n), "energies": balance(e), "timing_commit": t["mfsd_commit_of_the_run"],
                 "particle_steps_per_second": t["particle_steps_per_second"]}
            if r["seed_table5"]:
                r["difference_to_seed"] = u[-1] / r["seed_table5"] - 1 if end == 1.2 else None
            runs.append(r)
            ax.plot(p["time"], u, label=f"dp = 1/{n}" + ("" if end == 1.2 else f", to {end:g} s"))
    for n, v in SEED_TABLE5.items():
        if n in res:
            ax.plot([1.2], [v], "k*", ms=9)
    ax.plot([], [], "k*", label="seed 000 Table 5 (t = 1.2 s)")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("u_x of the top-face centre")
    ax.set_title("Muscle contraction, T_a = -0.5 V_m ramped over 1 s")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return {"runs": runs}, fig


def bending(args, plt):
    res = (args.res or [6])[0]
    runs = []
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for k in [0.0, 0.1, 0.5, 1.0]:
        out = os.path.join(OUT, f"bending_{res}_{k:g}")
        p, e, t = m.run_and_read("configs/bending_column_ho_3d.json",
                                 {"constants.H_over_dp": res, "constants.k": k}, out, args.threads, args.reuse)
        z = p["S.position.z"]
        i = min((j for j, tt in enumerate(p["time"]) if tt < 0.8), key=lambda j: z[j])
        runs.append({"a_f_over_a": k, "H_over_dp": res, "first_minimum_z": z[i], "first_minimum_t": p["time"][i],
                     "particles": t["particles"], "steps": t["steps"], "balance_final": e["balance"][-1],
                     "total_initial": e["total"][0]})
        ax.plot(p["time"], z, label="isotropic" if k == 0 else f"a_f/a = {k:g}")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("z of S [m]")
    ax.set_title(f"Holzapfel-Ogden bending column, H/dp = {res} (seed 000 Fig. 9)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return {"runs": runs}, fig


def twisting(args, plt):
    res = (args.res or [6])[0]
    runs = []
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for omega in [330, 480]:
        for hg in ["genog", "none"]:
            out = os.path.join(OUT, f"twisting_{res}_{omega}_{hg}")
            p, e, t = m.run_and_read("configs/twisting_column_ho_3d.json",
                                     {"constants.H_over_dp": res, "constants.Omega0": omega, "solver.hourglass": hg},
                                     out, args.threads, args.reuse)
            runs.append({"Omega0": omega, "hourglass": hg, "H_over_dp": res, "steps": t["steps"],
                         "simulated_time": t["simulated_time"], "hourglass_mean_peak": max(e["hourglass_mean"]),
                         "hourglass_mean_final": e["hourglass_mean"][-1], "balance_final": e["balance"][-1],
                         "total_initial": e["total"][0]})
            ax.plot(e["time"], e["hourglass_mean"], label=f"{omega} rad/s, {hg}")
    ax.set_yscale("log")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("mean hourglass indicator")
    ax.set_title(f"Holzapfel-Ogden twisting column, H/dp = {res}")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return {"runs": runs}, fig


def main():
    def extra(ap):
        ap.add_argument("study", choices=["muscle", "bending", "twisting"])
        ap.add_argument("--long", action="store_true", help="muscle: also run to 4 s")
    args = m.study_arguments(__doc__, res_help="resolutions (see above)", extra=extra)
    m.ensure_python_packages()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    result, fig = {"muscle": muscle, "bending": bending, "twisting": twisting}[args.study](args, plt)
    result["machine"] = m.machine()
    fig.tight_layout()
    m.write_study(os.path.join(m.ROOT, "docs", "validation", f"holzapfel_ogden_{args.study}"), result, fig)


if __name__ == "__main__":
    main()
