"""Dynamic four-point bending with a tilted slit (seed 001 section 4.2.3,
Fig. 29-31) for slit angles 90, 60 and 45 degrees: crack initiation time at
the slit, how far the crack has run by the end, and pictures of the crack
paths (broken particles, s < 0.5, in the reference configuration).

  python3 scripts/validation/four_point_bending.py                       # dp = 0.5 mm, 90/60/45
  python3 scripts/validation/four_point_bending.py --dp 0.5 --backend cuda --out docs/validation/four_point_bending_gpu

Definitions: initiation = a broken particle reaches 0.5 mm above the slit's top
(z0 >= 6.5 mm; crack_beam.csv measures the reach from the notch's centre,
z = 2.3 mm, along +z); crack height at the end = the highest broken particle.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fracture_study as fs  # noqa: E402
import mfsd_runs as m  # noqa: E402
import numpy as np  # noqa: E402
import vtu  # noqa: E402

SCENE = "configs/four_point_bending_3d.json"
ANGLES = (90, 60, 45)


def main():
    args = fs.arguments(__doc__, [0.5], "four_point_bending")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    dp_mm = args.dp[-1]
    rows, finals = [], []
    for theta in ANGLES:
        outdir = fs.run(SCENE, f"four_point_bending_{theta}", dp_mm, args, {"constants.theta": theta})
        crack = m.read_csv(os.path.join(outdir, "crack_beam.csv"))
        energies = m.read_csv(os.path.join(outdir, "energies.csv"))
        init = fs.initiation(crack, 0.0, growth=(6.5 - 2.3) * 1e-3)
        time, path = vtu.snapshots(outdir)[-1]
        d = vtu.read_vtu(path)
        X = np.asarray(d["points"], float) - np.asarray(d["displacement"], float)
        s = np.asarray(d["phase_field"], float)
        broken = X[s < 0.5]
        row = {"theta_deg": theta, "dp_mm": dp_mm, "initiation_us": init and init * 1e6,
               "crack_top_at_end_mm": float(broken[:, 2].max() * 1e3) if len(broken) else None,
               "broken_particles": int(len(broken)), "energies_at_end": fs.energy_summary(energies)}
        row.update(fs.run_record(outdir, args))
        rows.append(row)
        finals.append((theta, time, broken))
        print(row, flush=True)
    fig, ax = plt.subplots(2, len(ANGLES), figsize=(5 * len(ANGLES), 8))
    for k, (theta, time, broken) in enumerate(finals):
        for r, (i, j, name) in enumerate(((0, 2, "side (x-z)"), (0, 1, "bottom (x-y)"))):
            a = ax[r, k]
            if len(broken):
                sc = a.scatter(broken[:, i] * 1e3, broken[:, j] * 1e3, c=broken[:, 1 if j == 2 else 2] * 1e3, s=1,
                               cmap="viridis")
                fig.colorbar(sc, ax=a, shrink=0.7, label="y [mm]" if j == 2 else "z [mm]")
            a.set(xlim=(20, 60), ylim=(0, 20 if j == 2 else 10), aspect="equal", xlabel="x [mm]",
                  ylabel="z [mm]" if j == 2 else "y [mm]",
                  title=f"slit at {theta} deg: s < 0.5 at {time * 1e6:.0f} us, {name}")
    fig.tight_layout()
    m.write_study(args.stem, {"scene": SCENE, "machine": m.machine(), "definitions": __doc__.split("Definitions")[1],
                              "runs": rows}, fig)


if __name__ == "__main__":
    main()
