#!/usr/bin/env python3
"""Holzapfel-Ogden and active muscle (seed 000 sections 3.3-3.4, 5.2-5.4; issue 21).

  muscle     configs/muscle_contraction_3d.json at dp = 0.1, 0.05, 0.025 (--res
             10 20 40: cells per unit length): u_x(t) of the top-face centre
             (mean of the particles within dp of (1 - dp/2, 1/2, 1/2)), its
             value at t = 1.2 s against seed 000 Table 5, its maximum, and the
             energy balance with the active stress's work; with --long also
             to t = 4 s (the static answer the ramped activation tends to).
  muscle-damping
             the same cube at dp = 0.1, 0.05, 0.025 to 1.2 s with the
             Kelvin-Voigt damping factor 0.25, 0.5, 1, 2, 4 (isotropic form)
             and 0.125 (split form, the authors' GENOG setting): u_x at 1.2 s
             and its maximum over time, against seed 000 Table 5.
  bending    configs/bending_column_ho_3d.json, a_f/a = 0 (isotropic), 0.1,
             0.5, 1.0 at H/dp = 6 (--res) to 3 s: z(t) of S (seed 000 Fig. 7, 9)
             and its first minimum.
  twisting   configs/twisting_column_ho_3d.json, Omega0 = 330 and 480 rad/s,
             genog and none, H/dp = 6 (--res) to 0.5 s, and 330 rad/s genog
             at CFL 0.3 and 0.15: the mean hourglass indicator and the
             energy balance over time (seed 000 Fig. 14-16); a run that
             fails is reported with the time it reached.

Writes docs/validation/holzapfel_ogden_<study>.json and .png.
Usage: scripts/validation/holzapfel_ogden.py muscle|muscle-damping|bending|twisting [--res N ...] [--threads N] [--reuse] [--long]
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


DAMPINGS = [(0.25, "isotropic"), (0.5, "isotropic"), (1.0, "isotropic"), (2.0, "isotropic"), (4.0, "isotropic"),
            (0.125, "split")]


def muscle_damping(args, plt):
    res = args.res or [10, 20, 40]
    runs = []
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True)
    for factor, form in DAMPINGS:
        at_end, peak = [], []
        for n in res:
            out = os.path.join(OUT, f"muscle_damping_{n}_{form}_{factor:g}")
            p, e, t = m.run_and_read("configs/muscle_contraction_3d.json",
                                     {"constants.dp": 1.0 / n, "solver.damping.factor": factor,
                                      "solver.damping.form": form, "output.vtu": "false"}, out, args.threads, args.reuse)
            u = p["top.displacement.x"]
            runs.append({"res": n, "dp": 1.0 / n, "damping_factor": factor, "damping_form": form, "u_1_2": u[-1],
                         "u_max": max(u), "t_of_max": p["time"][u.index(max(u))], "seed_table5": SEED_TABLE5.get(n),
                         "balance_over_active_work": e["balance"][-1] / e["active_work"][-1]})
            at_end.append(u[-1])
            peak.append(max(u))
        label = f"{form} x {factor:g}"
        axes[0].plot(res, at_end, "o-", label=label)
        axes[1].plot(res, peak, "o-", label=label)
    for ax, title in zip(axes, ["u_x at t = 1.2 s", "maximum of u_x over t <= 1.2 s"]):
        ax.plot(res, [SEED_TABLE5.get(n) for n in res], "k*--", ms=10, label="seed 000 Table 5")
        ax.set_xlabel("cells per unit length (1/dp)")
        ax.set_title(title)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("u_x of the top-face centre")
    axes[1].legend(fontsize=8, title="Kelvin-Voigt damping")
    fig.suptitle("Muscle contraction: the top displacement against the damping")
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
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.5))
    cases = [(330, "genog", 0.6), (330, "none", 0.6), (480, "genog", 0.6), (480, "none", 0.6),
             (330, "genog", 0.3), (330, "genog", 0.15)]  # the last two: does the balance error shrink with dt?
    for omega, hg, cfl in cases:
        out = os.path.join(OUT, f"twisting_{res}_{omega}_{hg}" + ("" if cfl == 0.6 else f"_cfl{cfl:g}"))
        sets = {"constants.H_over_dp": res, "constants.Omega0": omega, "solver.hourglass": hg, "solver.cfl": cfl}
        p, e, t = m.run_and_read("configs/twisting_column_ho_3d.json", sets, out, args.threads, args.reuse,
                                 allow_failure=True)
        total0 = e["total"][0]
        runs.append({"Omega0": omega, "hourglass": hg, "cfl": cfl, "H_over_dp": res, "steps": t.get("steps"),
                     "failed_with_exit_code": t.get("failed_with_exit_code"), "last_output_time": e["time"][-1],
                     "hourglass_mean_peak": max(e["hourglass_mean"]),
                     "hourglass_mean_final": e["hourglass_mean"][-1], "balance_final": e["balance"][-1],
                     "total_initial": total0,
                     "balance_drift_max_over_initial": max(abs(b - e["balance"][0]) for b in e["balance"]) / total0,
                     "balance_drift_final_over_initial": (e["balance"][-1] - e["balance"][0]) / total0,
                     "damping_final": e["damping"][-1]})
        label = f"{omega} rad/s, {hg}" + ("" if cfl == 0.6 else f", CFL {cfl:g}")
        if cfl == 0.6:
            ax.plot(e["time"], e["hourglass_mean"], label=label)
        bx.plot(e["time"], [(b - e["balance"][0]) / total0 for b in e["balance"]], label=label)
    ax.set_yscale("log")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("mean hourglass indicator")
    ax.set_title(f"Holzapfel-Ogden twisting column, H/dp = {res}")
    bx.set_xlabel("t [s]")
    bx.set_ylabel("(balance - its initial value) / initial kinetic energy")
    bx.set_title("Energy balance drift (0 = conserved)")
    for a in (ax, bx):
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    return {"runs": runs}, fig


def main():
    def extra(ap):
        ap.add_argument("study", choices=["muscle", "muscle-damping", "bending", "twisting"])
        ap.add_argument("--long", action="store_true", help="muscle: also run to 4 s")
    args = m.study_arguments(__doc__, res_help="resolutions (see above)", extra=extra)
    m.ensure_python_packages()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    result, fig = {"muscle": muscle, "muscle-damping": muscle_damping, "bending": bending, "twisting": twisting}[args.study](args, plt)
    result["machine"] = m.machine()
    fig.tight_layout()
    m.write_study(os.path.join(m.ROOT, "docs", "validation", "holzapfel_ogden_" + args.study.replace("-", "_")), result, fig)


if __name__ == "__main__":
    main()
