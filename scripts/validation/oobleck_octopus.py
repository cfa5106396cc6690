#!/usr/bin/env python3
"""Viscoplastic showcase in the spirit of seed 000 section 5.7
(configs/oobleck_octopus_2d.json): a plane-strain 'octopus' of shear-thickening
oobleck (Herschel-Bulkley, seed 000 Table 8) on a rigid floor under gravity,
punched by a rigid half-disc that stops after 0.3 s; self-contact of the legs,
friction on the floor. No reference numbers: the study records the run
(particles, steps, wall time, largest von Mises strain, hourglass indicator,
the punch and floor forces) and draws the body at six instants with the
punch and the floor markers.

Writes docs/validation/oobleck_octopus.json and .png.
Usage: scripts/validation/oobleck_octopus.py [--threads N] [--reuse]
"""
import glob
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402
import vtu  # noqa: E402

DOCS = os.path.join(m.ROOT, "docs", "validation")
OUT = os.path.join(m.ROOT, "out", "validation")


def main():
    args = m.study_arguments(__doc__)
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    outdir = os.path.join(OUT, "oobleck_octopus")
    probes, e, timing = m.run_and_read("configs/oobleck_octopus_2d.json", {}, outdir, args.threads, args.reuse)
    forces = m.read_csv(os.path.join(outdir, "boundary_forces.csv"))
    snaps = [f for f in sorted(glob.glob(os.path.join(outdir, "snapshots", "*.vtu"))) if "_rigid_" not in f]
    rigid = sorted(glob.glob(os.path.join(outdir, "snapshots", "*_rigid_*.vtu")))
    fields = [vtu.read_vtu(f) for f in snaps]
    res = {"study": "oobleck_octopus", "command": "scripts/validation/oobleck_octopus.py", "machine": m.machine(),
           "particles": timing["particles"], "steps": timing["steps"], "wall_seconds": timing["wall_seconds"],
           "particle_steps_per_second": timing["particle_steps_per_second"],
           "mfsd_commit_of_the_run": timing["mfsd_commit_of_the_run"],
           "largest_von_mises_strain": max(float(np.max(d["von_mises_strain"])) for d in fields),
           "largest_hourglass_indicator": max(e["hourglass_max"]),
           "largest_punch_force": max(abs(v) for v in forces["punch.y"]),
           "floor_force_final": forces["floor.y"][-1], "weight": None,
           "plastic_work_final": e["plastic"][-1], "contact_work_final": e["contact_work"][-1],
           "gravity_work_final": e["gravity_work"][-1], "balance_final": e["balance"][-1],
           "lowest_particle_over_dp": min(float(np.min(np.asarray(d["points"])[:, 1])) for d in fields) / 0.005}
    res["weight"] = 1000 * 9.81 * timing["particles"] * 0.005 ** 2
    print(f"{res['particles']} particles, {res['steps']} steps, {res['wall_seconds']:.0f} s; largest von Mises "
          f"strain {res['largest_von_mises_strain']:.2f}; hourglass max {res['largest_hourglass_indicator']:.3f}; "
          f"punch force peak {res['largest_punch_force']:.1f} N/m; floor force at the end {res['floor_force_final']:.1f}"
          f" N/m (weight {res['weight']:.1f} N/m); lowest particle centre {res['lowest_particle_over_dp']:.2f} dp")
    picks = [k for k in (0, 5, 10, 15, 25, 50) if k < len(fields)]
    fig = plt.figure(figsize=(16, 7))
    grid = fig.add_gridspec(2, len(picks))
    for col, k in enumerate(picks):
        ax = fig.add_subplot(grid[0, col])
        x = np.asarray(fields[k]["points"])
        sc = ax.scatter(x[:, 0], x[:, 1], c=np.asarray(fields[k]["von_mises_strain"]), s=0.6, cmap="viridis",
                        vmin=0, vmax=2)
        if k < len(rigid):
            xr = np.asarray(vtu.read_vtu(rigid[k])["points"])
            ax.scatter(xr[:, 0], xr[:, 1], c="k", s=0.3)
        ax.set_aspect("equal")
        ax.set_xlim(-0.45, 0.45)
        ax.set_ylim(-0.03, 0.6)
        ax.set_title(f"t = {e['time'][k]:.2f} s", fontsize=9)
        ax.tick_params(labelsize=7)
    fig.colorbar(sc, ax=fig.axes[:len(picks)], shrink=0.7, label="von Mises strain")
    ax = fig.add_subplot(grid[1, : len(picks) // 2])
    ax.plot(forces["time"], [-v for v in forces["punch.y"]], label="punch on the octopus (down)")
    ax.plot(forces["time"], forces["floor.y"], label="floor on the octopus (up)")
    ax.axhline(res["weight"], color="k", ls=":", lw=1, label="weight")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("force [N per m of depth]")
    ax.legend(fontsize=7)
    ax = fig.add_subplot(grid[1, len(picks) // 2:])
    ax.plot(e["time"], e["kinetic"], label="kinetic")
    ax.plot(e["time"], e["strain"], label="stored elastic")
    ax.plot(e["time"], e["plastic"], label="viscoplastic work")
    ax.plot(e["time"], [-v for v in e["contact_work"]], label="- contact work")
    ax.plot(e["time"], e["gravity_work"], label="gravity's work")
    ax.plot(e["time"], e["balance"], "k", label="balance")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("J per m of depth")
    ax.legend(fontsize=7)
    fig.suptitle("Oobleck octopus (Herschel-Bulkley, seed 000 Table 8): gravity, rigid punch until 0.3 s, "
                 "self-contact, floor friction 0.3")
    m.write_study(os.path.join(DOCS, "oobleck_octopus"), res, fig)


if __name__ == "__main__":
    main()
