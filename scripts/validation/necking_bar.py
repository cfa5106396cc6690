#!/usr/bin/env python3
"""Necking bar of seed 000 section 5.6 (configs/necking_bar_2d.json):
plane-strain steel bar 53.334 x 12.826 mm, height reduced linearly to 0.982 H
at the centre (a stress-free reference map of the particle lattice), pulled
4 mm at each end (8 mm in total) through 4 constrained layers; neo-Hookean
with saturation hardening (Table 7). The seed plots the necking displacement
(how far the top of the centre section moves in) and the reaction force
against the imposed elongation (Fig. 31-34, against Elguedj and Hughes),
without numbers; this study records both curves for genog and none at
H/dp = 20 and 40.

The pull follows u(t) = U (t/T - sin(2 pi t/T)/(2 pi)) at each end (zero
velocity at the start and the end, T = 4 ms, about 170 wave transits of the
bar) without damping; then the ends hold still for T/4 while the dynamic
relaxation of seed 003 (ref. [68]; solver.relaxation, factor 1) brings the bar
to rest: the final state is the static one at 8 mm. Besides
the scene (genog and none at each resolution), the study runs at the lowest
resolution (genog): pull times T/2 and 2T, and two damped pulls, the
Kelvin-Voigt damping factor 0.125 (the scene before the relaxation existed)
and the relaxation switched on during the pull (eta = 1e4 Pa s), to measure
how much damping during the pull holds the neck back.

Writes docs/validation/necking_bar.json and .png.
Usage: scripts/validation/necking_bar.py [--res 20 40] [--threads N] [--reuse]
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402

DOCS = os.path.join(m.ROOT, "docs", "validation")
OUT = os.path.join(m.ROOT, "out", "validation")
CONFIG = "configs/necking_bar_2d.json"
U = 0.004
T0 = 4e-3  # the scene's pull time

# Damping variants: overrides of the scene.
VARIANTS = {
    "scene": {},
    "kelvin_voigt_0.125": {"solver.damping.factor": 0.125},
    "relaxation_in_pull_eta1e4": {"solver.relaxation": {"viscosity": 1.0e4}},
}


def case_key(n, hourglass, T, variant):
    return f"H{n}_{hourglass}" + ("" if T == T0 else f"_T{T * 1e3:g}ms") + ("" if variant == "scene" else "_" + variant)


def elongation_mm(t, T):
    t = min(t, T)  # the ends hold still after the pull
    return 2e3 * U * (t / T - math.sin(2 * math.pi * t / T) / (2 * math.pi))


def run_case(n, hourglass, T, variant, threads, reuse):
    outdir = os.path.join(OUT, "necking_" + case_key(n, hourglass, T, variant))
    sets = {"constants.H_over_dp": n, "solver.hourglass": hourglass, "constants.T": T}
    sets.update(VARIANTS[variant])
    p, e, timing = m.run_and_read(CONFIG, sets, outdir, threads, reuse)
    f = m.read_csv(os.path.join(outdir, "boundary_forces.csv"))
    elong = [elongation_mm(t, T) for t in p["time"]]
    neck = [1e3 * (p["top.position.y"][0] - y) for y in p["top.position.y"]]
    f_elong = [elongation_mm(t, T) for t in f["time"]]
    force = [1e-6 * v for v in f["right.x"]]
    k = max(range(len(force)), key=lambda i: force[i])
    end_of_pull = min(range(len(p["time"])), key=lambda i: abs(p["time"][i] - T))
    e_end_of_pull = min(range(len(e["time"])), key=lambda i: abs(e["time"][i] - T))
    r = {"H_over_dp": n, "hourglass": hourglass, "pull_time": T, "variant": variant, "overrides": VARIANTS[variant],
         "particles": timing["particles"],
         "steps": timing["steps"], "wall_seconds": timing["wall_seconds"],
         "mfsd_commit_of_the_run": timing["mfsd_commit_of_the_run"],
         "neck_displacement_mm_at_8mm": neck[-1], "force_MN_per_m_at_8mm": force[-1],
         "neck_displacement_mm_at_end_of_pull": neck[end_of_pull],
         "kinetic_J_per_m_at_end_of_pull": e["kinetic"][e_end_of_pull], "kinetic_J_per_m_final": e["kinetic"][-1],
         "plastic_work_J_per_m": e["plastic"][-1],
         "peak_force_MN_per_m": force[k], "elongation_mm_at_peak_force": f_elong[k],
         "von_mises_strain_top_final": p["top.von_mises_strain"][-1],
         "hourglass_max": max(e["hourglass_max"])}
    return r, (elong, neck), (f_elong, force)


def main():
    args = m.study_arguments(__doc__, "resolutions H/dp (default 20 40)")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    res = {"study": "necking_bar", "command": "scripts/validation/necking_bar.py", "machine": m.machine(), "runs": {}}
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.8))
    cases = [(n, hg, T0, "scene") for n in (args.res or [20, 40]) for hg in ("genog", "none")]
    n0 = min(args.res or [20])
    cases += [(n0, "genog", T0 / 2, "scene"), (n0, "genog", 2 * T0, "scene"),
              (n0, "genog", T0, "kelvin_voigt_0.125"), (n0, "genog", T0, "relaxation_in_pull_eta1e4")]
    for n, hg, T, variant in cases:
        r, (el, neck), (fe, force) = run_case(n, hg, T, variant, args.threads, args.reuse)
        key = case_key(n, hg, T, variant)
        res["runs"][key] = r
        print(f"{key}: neck {r['neck_displacement_mm_at_8mm']:.3f} mm, force {r['force_MN_per_m_at_8mm']:.3f} MN/m at "
              f"8 mm; peak {r['peak_force_MN_per_m']:.3f} MN/m at {r['elongation_mm_at_peak_force']:.2f} mm; "
              f"end of pull {r['neck_displacement_mm_at_end_of_pull']:.3f} mm, kinetic {r['kinetic_J_per_m_at_end_of_pull']:.2g} "
              f"-> {r['kinetic_J_per_m_final']:.2g} J/m; hourglass max {r['hourglass_max']:.3f}; {r['particles']} particles, {r['steps']} steps, "
              f"{r['wall_seconds']:.0f} s")
        style = ("-" if hg == "genog" else "--") if (T == T0 and variant == "scene") else ":"
        label = (f"H/dp = {n}, {hg}" + ("" if T == T0 else f", pull {T * 1e3:g} ms") +
                 ("" if variant == "scene" else ", " + variant.replace("_", " ")))
        ax[0].plot(el, neck, style, label=label)
        ax[1].plot(fe, force, style, label=label)
    ax[0].set_xlabel("imposed elongation [mm]")
    ax[0].set_ylabel("necking displacement [mm]")
    ax[1].set_xlabel("imposed elongation [mm]")
    ax[1].set_ylabel("reaction force [MN per m of depth]")
    for a in ax:
        a.legend(fontsize=7)
    fig.suptitle("Necking bar (seed 000 section 5.6, Fig. 31-34)")
    fig.tight_layout()
    m.write_study(os.path.join(DOCS, "necking_bar"), res, fig)


if __name__ == "__main__":
    main()
