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

Writes docs/validation/taylor_bar_seed001.json and .png (another stem with
--out, e.g. the seed's resolution as a bench run of the seed's model only:
--res 4 8 16 --models j2_mandel --out taylor_bar_seed001_R16).
Usage: scripts/validation/taylor_bar_seed001.py [--res 4 8] [--models j2_mandel j2] [--out STEM]
       [--threads N] [--reuse]
"""
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402
import vtu  # noqa: E402

DOCS = os.path.join(m.ROOT, "docs", "validation")
OUT = os.path.join(m.ROOT, "out", "validation")
CONFIG = "configs/taylor_bar_seed001_3d.json"
L0, R0 = 0.0324, 0.0032
MODELS = {"j2_mandel": "-", "j2": "--"}  # return mapping -> line style


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
         "plastic_work_final": e["plastic"][-1], "kinetic_final": e["kinetic"][-1],
         "energy_balance_initial": e["balance"][0], "energy_balance_final": e["balance"][-1],
         "hourglass_max_final": e["hourglass_max"][-1],
         "particle_steps_per_second": timing["particle_steps_per_second"], "outdir": outdir}
    # Relative to the measured start (the lattice does not fit L0 exactly at every R/dp).
    curve = ([1 - v / length[0] for v in length], [v / radius[0] - 1 for v in radius])
    r["initial_length_mm"], r["initial_foot_radius_mm"] = 1e3 * length[0], 1e3 * radius[0]
    r["final_shortening"], r["final_expansion"] = curve[0][-1], curve[1][-1]
    return r, curve


def draw_sections(axes, outdir, dp, times):
    """The particle row nearest the x-z mid-plane (in the reference state) at the
    snapshots nearest to `times`, coloured by the equivalent plastic strain
    (seed 001 Fig. 39 shows the same at 20 us intervals). Returns the largest
    plastic strain of the last snapshot drawn and the colour mappable."""
    import numpy as np
    snaps = vtu.snapshots(outdir)
    largest, image = 0.0, None
    for a, t in zip(axes, times):
        time, path = vtu.nearest_snapshot(snaps, t)
        d = vtu.read_vtu(path)
        x = np.asarray(d["points"], dtype=float)
        strain = np.asarray(d["plastic_strain"], dtype=float)
        cut = vtu.mid_plane(d, dp)
        image = a.scatter(1e3 * x[cut, 0], 1e3 * x[cut, 2], c=strain[cut], s=2.5 * (dp / 2e-4) ** 2, cmap="jet",
                          vmin=0, vmax=2.0, linewidths=0)
        largest = float(strain.max())
        a.set_aspect("equal")
        a.set_xlim(-8, 8)
        a.set_ylim(-0.5, 33)
        a.set_facecolor("0.92")
        a.set_title(f"{1e6 * time:.0f} us", fontsize=9)
        a.set_xlabel("x [mm]", fontsize=8)
        a.tick_params(labelsize=7)
    axes[0].set_ylabel("z [mm]", fontsize=8)
    return largest, image


def main():
    args = m.study_arguments(
        __doc__, "resolutions R/dp (default 4 8; seed 001: 16)",
        "stem of the result files in docs/validation (default taylor_bar_seed001)",
        lambda ap: ap.add_argument("--models", nargs="*", choices=MODELS, help="return mappings (default: both)"))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    result = {"study": "taylor_bar_seed001", "command": " ".join(["scripts/validation/taylor_bar_seed001.py"] + sys.argv[1:]),
              "machine": m.machine(), "runs": {}}
    fig = plt.figure(figsize=(11, 10))
    grid = fig.add_gridspec(2, 5, height_ratios=[1, 1.25])
    fig.subplots_adjust(left=0.06, right=0.98, top=0.95, bottom=0.09, hspace=0.3)
    ax = fig.add_subplot(grid[0, 1:4])
    resolutions = args.res or [4, 8]
    for n in resolutions:
        for model in args.models or MODELS:
            style = MODELS[model]
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
    finest = result["runs"][f"R{max(resolutions)}_{(args.models or list(MODELS))[0]}"]
    sections = [fig.add_subplot(grid[1, i]) for i in range(5)]
    finest["largest_plastic_strain_final"], image = draw_sections(sections, finest["outdir"], finest["dp"],
                                                                  [2e-5, 4e-5, 6e-5, 8e-5, 1e-4])
    fig.colorbar(image, ax=sections, shrink=0.8, label="equivalent plastic strain")
    fig.text(0.45, 0.03, f"mid-section (the particle row nearest y = 0) at R/dp = {finest['R_over_dp']}, "
             f"{finest['model']} (seed 001 Fig. 39)", ha="center", fontsize=9)
    for r in result["runs"].values():
        r["outdir"] = os.path.relpath(r["outdir"], m.ROOT)
    m.write_study(os.path.join(DOCS, args.out or "taylor_bar_seed001"), result, fig)


if __name__ == "__main__":
    main()
