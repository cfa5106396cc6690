#!/usr/bin/env python3
"""Copper Taylor bar of seed 001 section 4.3.2 (configs/taylor_bar_seed001_3d.json):
L0 = 32.4 mm, R0 = 3.2 mm, 227 m/s onto a rigid frictionless wall, J2 with
linear hardening (sigma_y0 = 400 MPa, H = 100 MPa), 100 us.

Seed 001 plots the radial expansion against the axial shortening of the bar
(Fig. 38) for its multiplicative return with the Mandel stress (model
j2_mandel here) against Chen et al. and Montans et al., without numbers. This
study records that curve per resolution R/dp: axial shortening 1 - L(t)/L0
from the top of the bar (the probe at the top's centre) and radial expansion
R(t)/R0 - 1 from the foot (the probe at the bottom edge, plus dp/2 for the
particle's half spacing), both relative to their values at t = 0, and the same curve with seed 000's return (model
j2), which differs in the consistency condition and in the measure of
equivalent plastic strain (kernels/materials/j2_return_mapping.hpp).

Writes docs/validation/taylor_bar_seed001.json and .png.
Usage: scripts/validation/taylor_bar_seed001.py [--res 4 8] [--threads N] [--reuse]
"""
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402

DOCS = os.path.join(m.ROOT, "docs", "validation")
OUT = os.path.join(m.ROOT, "out", "validation")
CONFIG = "configs/taylor_bar_seed001_3d.json"
L0, R0 = 0.0324, 0.0032


def run_case(n, model, threads, reuse):
    dp = R0 / n
    outdir = os.path.join(OUT, f"taylor_seed001_R{n}_{model}")
    p, e, timing = m.run_and_read(CONFIG, {"constants.R_over_dp": n, "bodies.bar.material.model": model}, outdir,
                                  threads, reuse)
    # The top probe starts at z = L0 - dp/2 (the top particle layer): its
    # height + dp/2 is the length while the bar stands on the wall.
    length = [z + dp / 2 for z in p["top.position.z"]]
    radius = [x + dp / 2 for x in p["foot.position.x"]]
    r = {"R_over_dp": n, "dp": dp, "model": model, "particles": timing["particles"], "steps": timing["steps"],
         "wall_seconds": timing["wall_seconds"], "mfsd_commit_of_the_run": timing["mfsd_commit_of_the_run"],
         "final_length_mm": 1e3 * length[-1], "final_foot_radius_mm": 1e3 * radius[-1],
         "final_shortening": 1 - length[-1] / L0, "final_expansion": radius[-1] / R0 - 1,
         "foot_plastic_strain_final": p["foot.plastic_strain"][-1],
         "plastic_work_final": e["plastic"][-1], "kinetic_final": e["kinetic"][-1]}
    # Relative to the measured start (the lattice does not fit L0 exactly at every R/dp).
    curve = ([1 - v / length[0] for v in length], [v / radius[0] - 1 for v in radius])
    r["initial_length_mm"], r["initial_foot_radius_mm"] = 1e3 * length[0], 1e3 * radius[0]
    r["final_shortening"], r["final_expansion"] = curve[0][-1], curve[1][-1]
    return r, curve


def main():
    args = m.study_arguments(__doc__, "resolutions R/dp (default 4 8; seed 001: 16)")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    result = {"study": "taylor_bar_seed001", "command": "scripts/validation/taylor_bar_seed001.py",
              "machine": m.machine(), "runs": {}}
    fig, ax = plt.subplots(figsize=(6.5, 5))
    for n in args.res or [4, 8]:
        for model, style in (("j2_mandel", "-"), ("j2", "--")):
            r, (short, expand) = run_case(n, model, args.threads, args.reuse)
            result["runs"][f"R{n}_{model}"] = r
            print(f"R/dp = {n}, {model}: length {r['final_length_mm']:.3f} mm, foot radius "
                  f"{r['final_foot_radius_mm']:.3f} mm (shortening {r['final_shortening']:.4f}, expansion "
                  f"{r['final_expansion']:.4f}), {r['particles']} particles, {r['steps']} steps, "
                  f"{r['wall_seconds']:.0f} s")
            ax.plot(short, expand, style, label=f"R/dp = {n}, {model}")
    ax.set_xlabel("axial shortening 1 - L/L0")
    ax.set_ylabel("radial expansion of the foot R/R0 - 1")
    ax.legend(fontsize=8)
    ax.set_title("Copper Taylor bar, 227 m/s, 100 us (seed 001 Fig. 38)", fontsize=10)
    fig.tight_layout()
    m.write_study(os.path.join(DOCS, "taylor_bar_seed001"), result, fig)


if __name__ == "__main__":
    main()
