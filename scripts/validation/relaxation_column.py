#!/usr/bin/env python3
"""How strongly the dynamic relaxation (solver.relaxation; seed 003 ref. [68])
damps a body's slowest mode, and whether it settles on the right static
state: the hanging column of tests/regression/scenes/hanging_column_2d.json
(1 m x 0.1 m, W/dp = 5, rho0 1000, E 10 MPa, nu 0.3, held at its top, its
weight applied from rest), whose tip swings about its static stretch with a
period of about 40 ms.

For relaxation factors f (eta = f p rho0 c0 h / CFL) at random ratios p = 1
and 0.2 the study fits the damping ratio zeta of the swing over 10 periods
(log of the half-amplitude per period against time) and compares it with the
continuum value of the viscous term, zeta = eta k / (2 rho0 c) for the
fixed-free mode k = pi / (2 L), c = sqrt(E / ((1 - nu^2) rho0)). Runs with
factors 1 and 8 (p = 1) go on to 2 s to show where they settle against the
middle of the undamped swing.

Writes docs/validation/relaxation_column.json and .png.
Usage: scripts/validation/relaxation_column.py [--threads N] [--reuse]
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402

DOCS = os.path.join(m.ROOT, "docs", "validation")
OUT = os.path.join(m.ROOT, "out", "validation")
CONFIG = "tests/regression/scenes/hanging_column_2d.json"
RHO, E, NU, L, G = 1000.0, 1.0e7, 0.3, 1.0, 9.81
PERIOD_WINDOW = 0.04


def run_case(key, sets, threads, reuse):
    outdir = os.path.join(OUT, "relaxation_column_" + key)
    sets = dict(sets)
    sets["output.probe_interval"] = 0.0005
    p, e, timing = m.run_and_read(CONFIG, sets, outdir, threads, reuse)
    return p["time"], p["tip.displacement.y"], e, timing


def damping_ratio(t, u, periods=10):
    """zeta from the half-amplitudes of successive 40 ms windows."""
    amps, mids = [], []
    for k in range(periods):
        w = [u[i] for i in range(len(t)) if k * PERIOD_WINDOW <= t[i] < (k + 1) * PERIOD_WINDOW]
        amps.append(0.5 * (max(w) - min(w)))
        mids.append((k + 0.5) * PERIOD_WINDOW)
    ys = [math.log(a) for a in amps]
    n = len(ys)
    mt, my = sum(mids) / n, sum(ys) / n
    slope = sum((x - mt) * (y - my) for x, y in zip(mids, ys)) / sum((x - mt) ** 2 for x in mids)
    return -slope * PERIOD_WINDOW / (2 * math.pi), amps  # decay per radian of the ~40 ms period


def main():
    args = m.study_arguments(__doc__)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    res = {"study": "relaxation_column", "command": "scripts/validation/relaxation_column.py",
           "machine": m.machine(), "runs": {}}
    c_bar = math.sqrt(E / ((1 - NU ** 2) * RHO))
    k_mode = math.pi / (2 * L)
    t0, u0, _, _ = run_case("undamped", {"solver.relaxation.enabled": "false", "solver.end_time": 0.4},
                            args.threads, args.reuse)
    middle = 0.5 * (min(u0) + max(u0))
    res["undamped"] = {"tip_min": min(u0), "tip_max": max(u0), "static_stretch_middle_of_swing": middle,
                       "analytic_uniaxial_plane_strain": -RHO * G * (0.99 - 0.99 ** 2 / 2) * (1 - NU ** 2) / E}
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.6))
    ax[1].plot(t0, [1e3 * v for v in u0], color="0.6", lw=0.8, label="undamped")
    for p in (1.0, 0.2):
        zs, fs = [], []
        for f in (0.1, 0.3, 1, 3, 10):
            key = f"p{p:g}_factor{f:g}"
            t, u, e, timing = run_case(key, {"solver.relaxation.factor": f, "solver.relaxation.random_ratio": p,
                                             "solver.end_time": 0.4}, args.threads, args.reuse)
            zeta, amps = damping_ratio(t, u)
            h = 1.15 * 0.02
            c0 = math.sqrt(E / (3 * (1 - 2 * NU)) / RHO)
            eta = f * p * RHO * c0 * h / 0.6
            r = {"random_ratio": p, "factor": f, "viscosity_Pa_s": eta, "zeta_measured": zeta,
                 "zeta_continuum": eta * k_mode / (2 * RHO * c_bar), "half_amplitudes_per_40ms": amps,
                 "relaxation_J_per_m": e["relaxation"][-1], "steps": timing["steps"]}
            res["runs"][key] = r
            print(f"{key}: eta {eta:.4g} Pa s, zeta {zeta:.4f} (continuum {r['zeta_continuum']:.4f})")
            zs.append(zeta)
            fs.append(f)
        ax[0].loglog(fs, zs, "o-", label=f"measured, random ratio {p:g}")
    fc = [0.1, 10]
    c0 = math.sqrt(E / (3 * (1 - 2 * NU)) / RHO)
    for p in (1.0, 0.2):
        ax[0].loglog(fc, [f * p * RHO * c0 * 0.023 / 0.6 * k_mode / (2 * RHO * c_bar) for f in fc], ":",
                     label=f"continuum viscosity, random ratio {p:g}")
    for f in (1, 10):
        key = f"p1_factor{f:g}_long"
        t, u, e, _ = run_case(key, {"solver.relaxation.factor": f, "solver.relaxation.random_ratio": 1,
                                    "solver.end_time": 2.0}, args.threads, args.reuse)
        last = [u[i] for i in range(len(t)) if t[i] >= 2.0 - PERIOD_WINDOW]
        res["runs"][key] = {"factor": f, "tip_final": u[-1], "last_period_spread": max(last) - min(last),
                            "relative_to_middle_of_undamped_swing": u[-1] / middle - 1,
                            "relaxation_J_per_m": e["relaxation"][-1]}
        print(f"{key}: tip {u[-1]:.5e} m ({100 * (u[-1] / middle - 1):+.2f} % of the undamped swing's middle), "
              f"relaxation removed {e['relaxation'][-1]:.3g} J/m")
        ax[1].plot(t, [1e3 * v for v in u], label=f"relaxation factor {f:g}, random ratio 1")
    ax[1].axhline(1e3 * middle, color="k", lw=0.6, ls="--", label="middle of the undamped swing")
    ax[0].set_xlabel("relaxation factor f (eta = f p rho0 c0 h / CFL)")
    ax[0].set_ylabel("damping ratio of the slowest mode")
    ax[1].set_xlabel("t [s]")
    ax[1].set_ylabel("tip displacement [mm]")
    ax[1].set_xlim(0, 2.0)
    for a in ax:
        a.legend(fontsize=7)
    fig.suptitle("Dynamic relaxation on a hanging column (W/dp = 5, L/h = 43)")
    fig.tight_layout()
    m.write_study(os.path.join(DOCS, "relaxation_column"), res, fig)


if __name__ == "__main__":
    main()
