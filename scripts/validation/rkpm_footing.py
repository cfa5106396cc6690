#!/usr/bin/env python3
"""Drucker-Prager strip footing of rkpm.md 7.7 (configs/footing_dp_rkpm_2d.json),
semi-Lagrangian RKPM: a rigid rough footing of width B pushed into a
weightless cohesive soil 10B x 5B (plane strain, phi = 0: DP = von Mises with
the plane-strain match k = c), E/c = 1000, nu = 0.3, settlement to 0.1B under
mass-proportional damping alpha_d = 2 omega_1. Target: the plateau of the
footing pressure q = -(sum of the footing nodes' vertical reactions)/B within
5 % of the Prandtl limit (2 + pi) c = 5.14 c, with the kinetic energy below
1 % of the plastic work.

q comes from boundary_forces.csv (column footing.y, one step's reaction, every
probe_interval); the settlement s is the integral of the prescribed velocity
V min(t/t_ramp, 1) (exact at the singular-kernel footing nodes). The plateau
is the mean of q/c over s/B in [0.07, 0.10]. Besides the kinetic/plastic
ratio the study measures what the damping adds to q: the rate of the damping
work over the plateau, d(damping)/ds / B (the force alpha_d M v on the moving
soil, which the footing must also overcome), and the footing's own work rate
d(boundary_work)/ds / B as a check of the reactions.

The reaction of a prescribed dof is m (v_prescribed - v_computed)/dt on the
velocity the force stage computed with the damping on the step's start
velocity: f_int - f_ext + alpha_d M v exactly (rkpm.md 6; an implicit damping
update had scaled it by 1/(1 + alpha_d dt/2), 3.9 % at B/dp = 4).

Each resolution runs with the scene's integration (NSNI, the default of
solver.rkpm) and with SNNI alone (--integration picks). Option --phi20: one
more run per integration at the coarsest resolution with phi = 20 deg,
associative, plane-strain match: target N_c = 14.83 (Prandtl-Reissner,
weightless soil) within 10 %. --speed F runs every case at F times the
footing speed (same settlement; the damping term scales with V).

From the last snapshot each run reports the largest equivalent plastic
strain and a roughness of the displacement field: |u_I - mean of its 4
lattice neighbours| over the nodes within |x| < 2B, y > -2B, over the final
settlement (node-to-node oscillation: SNNI's spurious modes show as values
near 1, a smooth field as a few %).

Writes docs/validation/rkpm_footing.json and .png (or --out STEM).
Usage: scripts/validation/rkpm_footing.py [--res 4 8] [--integration nsni snni]
       [--phi20] [--speed 1] [--threads N] [--reuse]
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402

DOCS = os.path.join(m.ROOT, "docs", "validation")
OUT = os.path.join(m.ROOT, "out", "validation")
CONFIG = "configs/footing_dp_rkpm_2d.json"
PRANDTL = 2 + math.pi                   # N_c, phi = 0
N_C_20 = 14.83                          # N_c, phi = 20 deg (Prandtl-Reissner)
PLATEAU = (0.07, 0.10)                  # s/B window of the plateau
EARLY = (0.03, 0.05)                    # s/B window of an earlier plateau (reported besides)
ENERGY_FROM = 0.02                      # s/B from which kinetic/plastic is checked (plastic work ~ 0 before)


def settlement(t, V, t_ramp):
    """Integral of V min(t/t_ramp, 1)."""
    return V * t * t / (2 * t_ramp) if t < t_ramp else V * (t - t_ramp / 2)


def case_key(n, phi, speed, integration):
    return (f"B{n}_{integration.replace('-', '_')}" + ("" if phi == 0 else f"_phi{phi:g}") +
            ("" if speed == 1 else f"_V{speed:g}x"))


def rate(x, y, lo, hi):
    """Least-squares slope dy/dx over lo <= x <= hi."""
    pts = [(a, b) for a, b in zip(x, y) if lo <= a <= hi]
    if len(pts) < 2:
        return float("nan")
    n = len(pts)
    sx = sum(a for a, _ in pts)
    sy = sum(b for _, b in pts)
    sxx = sum(a * a for a, _ in pts)
    sxy = sum(a * b for a, b in pts)
    return (n * sxy - sx * sy) / (n * sxx - sx * sx)


def final_field(outdir, dp, s_end):
    """Largest plastic strain and the roughness (module doc) of the last snapshot."""
    import numpy as np
    import vtu
    snaps = vtu.snapshots(outdir)
    if not snaps:
        return None, None
    d = vtu.read_vtu(snaps[-1][1])
    x = np.asarray(d["points"], float)[:, :2]
    u = np.asarray(d["displacement"], float)[:, :2]
    X = x - u
    lo = X.min(axis=0) - dp / 2
    i = np.rint((X[:, 0] - lo[0]) / dp - 0.5).astype(int)
    j = np.rint((X[:, 1] - lo[1]) / dp - 0.5).astype(int)
    U = np.full((i.max() + 1, j.max() + 1, 2), np.nan)
    U[i, j] = u
    mean4 = 0.25 * (U[2:, 1:-1] + U[:-2, 1:-1] + U[1:-1, 2:] + U[1:-1, :-2])
    xc = lo[0] + (np.arange(1, U.shape[0] - 1) + 0.5) * dp
    yc = lo[1] + (np.arange(1, U.shape[1] - 1) + 0.5) * dp
    top = lo[1] + (U.shape[1]) * dp
    near = (np.abs(xc)[:, None] < 2 * s_end / 0.1) & (yc[None, :] > top - 2 * s_end / 0.1)
    r = np.linalg.norm(U[1:-1, 1:-1] - mean4, axis=2)[near]
    return float(np.max(d["plastic_strain"])), float(np.nanmax(r) / s_end)


def run_case(n, phi, speed, integration, threads, reuse):
    outdir = os.path.join(OUT, "rkpm_footing_" + case_key(n, phi, speed, integration))
    sets = {"constants.B_over_dp": n, "solver.rkpm.integration": integration.split("-")[0]}
    if "-" in integration:  # nsni-tangent, nsni-consistent: solver.rkpm.nsni_moduli
        sets["solver.rkpm.nsni_moduli"] = integration.split("-")[1]
    if phi:
        sets["bodies.soil.material.friction_angle"] = phi  # dilation_angle defaults to it: associative
    if speed != 1:
        sets["constants.V"] = 0.01 * speed
    _, e, timing = m.run_and_read(CONFIG, sets, outdir, threads, reuse)
    const = m.read_json(os.path.join(outdir, "run.json"))["scene"]["constants"]
    B, c, V, t_ramp = const["B"], const["c"], const["V"], const["t_ramp"]
    f = m.read_csv(os.path.join(outdir, "boundary_forces.csv"))
    s = [settlement(t, V, t_ramp) / B for t in f["time"]]
    q = [-fy / (B * c) for fy in f["footing.y"]]
    # boundary_forces.csv repeats its last row at the end: drop duplicate times.
    keep = [i for i in range(len(s)) if i == 0 or f["time"][i] > f["time"][i - 1]]
    s, q = [s[i] for i in keep], [q[i] for i in keep]
    window = [qi for si, qi in zip(s, q) if PLATEAU[0] <= si <= PLATEAU[1]]
    plateau = sum(window) / len(window)
    early = [qi for si, qi in zip(s, q) if EARLY[0] <= si <= EARLY[1]]
    target = PRANDTL if phi == 0 else N_C_20
    es = [settlement(t, V, t_ramp) / B for t in e["time"]]
    ratios = [k / p for si, k, p in zip(es, e["kinetic"], e["plastic"]) if si >= ENERGY_FROM and p > 0]
    # Energy rates over the plateau, as pressures (per B and c): dW/ds / (B c).
    def q_rate(col):
        return rate([si * B for si in es], e[col], PLATEAU[0] * B, PLATEAU[1] * B) / (B * c)

    r = {"B_over_dp": n, "integration": integration, "friction_angle_deg": phi, "footing_speed_m_per_s": V,
         "overrides": sets,
         "particles": timing.get("particles"), "steps": timing.get("steps"),
         "wall_seconds": timing.get("wall_seconds"), "threads": timing.get("threads"),
         "mfsd_commit_of_the_run": timing.get("mfsd_commit_of_the_run"),
         "alpha_d_per_s": const["alpha_d"], "target_q_over_c": target,
         "plateau_q_over_c": plateau, "plateau_error": plateau / target - 1,
         "plateau_spread_q_over_c": [min(window), max(window)],
         # A plateau is flat: the rise of q/c across the window (least-squares slope x width).
         "plateau_rise_q_over_c": rate(s, q, *PLATEAU) * (PLATEAU[1] - PLATEAU[0]),
         "early_plateau_q_over_c": sum(early) / len(early), "early_window_s_over_B": list(EARLY),
         "q_over_c_at_s_0.01B": next((qi for si, qi in zip(s, q) if si >= 0.01), None),
         "q_over_c_at_s_0.05B": next((qi for si, qi in zip(s, q) if si >= 0.05), None),
         "max_kinetic_over_plastic_from_s_0.02B": max(ratios) if ratios else float("nan"),
         "kinetic_over_plastic_final": e["kinetic"][-1] / e["plastic"][-1] if e["plastic"][-1] > 0 else None,
         "plateau_rates_q_over_c": {"boundary_work": q_rate("boundary_work"), "plastic": q_rate("plastic"),
                                    "strain": q_rate("strain"), "damping": q_rate("damping"),
                                    "kinetic": q_rate("kinetic")},
         "energies_final_J_per_m": {k: e[k][-1] for k in ("kinetic", "strain", "plastic", "damping",
                                                          "boundary_work", "balance")}}
    r["max_plastic_strain_final"], r["roughness_final"] = final_field(outdir, B / n, const["s_end"])
    return r, (s, q), (es, e)


def main():
    def extra(ap):
        ap.add_argument("--phi20", action="store_true", help="also run phi = 20 deg at the coarsest resolution")
        ap.add_argument("--speed", type=float, default=1.0, help="footing speed factor (1: the scene's V)")
        ap.add_argument("--integration", nargs="*", default=["nsni", "snni"], choices=["nsni", "snni", "nsni-elastic", "nsni-tangent", "nsni-consistent"],
                        help="solver.rkpm.integration of the runs (default nsni and snni; nsni-M sets nsni_moduli M)")
    args = m.study_arguments(__doc__, "resolutions B/dp (default 4 8)", "result stem (default docs/validation/rkpm_footing)",
                             extra)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    res = {"study": "rkpm_footing", "command": "scripts/validation/" + os.path.basename(__file__) + " " +
           " ".join(sys.argv[1:]), "machine": m.machine(), "reference": "rkpm.md 7.7; Prandtl (2 + pi) c",
           "plateau_window_s_over_B": list(PLATEAU), "runs": {}}
    levels = sorted(args.res or [4, 8])
    cases = [(n, 0, i) for i in args.integration for n in levels]
    cases += [(levels[0], 20, i) for i in args.integration] if args.phi20 else []
    fig, ax = plt.subplots(1, 2 if args.phi20 else 1, figsize=(12 if args.phi20 else 6.5, 4.8), squeeze=False)
    ax = ax[0]
    for n, phi, integration in cases:
        r, (s, q), _ = run_case(n, phi, args.speed, integration, args.threads, args.reuse)
        key = case_key(n, phi, args.speed, integration)
        res["runs"][key] = r
        rt = r["plateau_rates_q_over_c"]
        print(f"{key}: plateau q_u/c = {r['plateau_q_over_c']:.3f} (target {r['target_q_over_c']:.2f}, "
              f"error {100 * r['plateau_error']:+.1f} %; "
              f"s/B in {EARLY}: {r['early_plateau_q_over_c']:.3f}; rise over the window "
              f"{r['plateau_rise_q_over_c']:+.3f}), max kinetic/plastic (s >= {ENERGY_FROM}B) "
              f"{r['max_kinetic_over_plastic_from_s_0.02B']:.2e}; plateau rates /(B c): footing work "
              f"{rt['boundary_work']:.3f}, plastic {rt['plastic']:.3f}, damping {rt['damping']:.3f}, "
              f"strain {rt['strain']:.3f}; final max eps_p {r['max_plastic_strain_final']:.3f}, roughness "
              f"{r['roughness_final']:.3f}; {r['particles']} nodes, {r['steps']} steps, "
              f"{r['wall_seconds']:.0f} s on {r['threads']} threads")
        a = ax[0] if phi == 0 else ax[1]
        a.plot(s, q, "-" if integration.startswith("nsni") else "--",
               label=f"{integration.upper()}, B/dp = {n}: plateau {r['plateau_q_over_c']:.2f}")
    ax[0].axhline(PRANDTL, color="k", ls="--", lw=1, label="Prandtl (2 + $\\pi$) = 5.14")
    ax[0].axhspan(0.95 * PRANDTL, 1.05 * PRANDTL, color="0.9", zorder=0, label="$\\pm$5 %")
    ax[0].set_title("$\\phi$ = 0 (von Mises, k = c)")
    if args.phi20:
        ax[1].axhline(N_C_20, color="k", ls="--", lw=1, label="Prandtl-Reissner N$_c$ = 14.83")
        ax[1].axhspan(0.9 * N_C_20, 1.1 * N_C_20, color="0.9", zorder=0, label="$\\pm$10 %")
        ax[1].set_title("$\\phi$ = 20$^\\circ$, associative, plane-strain match")
    for a in ax:
        a.axvspan(*PLATEAU, color="C9", alpha=0.1, lw=0)
        a.set_xlabel("settlement / B")
        a.set_ylabel("q / c")
        a.set_xlim(0, 0.1)
        a.set_ylim(bottom=0)
        a.legend(fontsize=7, loc="lower right")
    fig.suptitle("RKPM strip footing on Drucker-Prager soil (rkpm.md 7.7)")
    fig.tight_layout()
    m.write_study(args.out or os.path.join(DOCS, "rkpm_footing"), res, fig)


if __name__ == "__main__":
    main()
