"""Kalthoff-Winkler impact (seed 001 section 4.2.2, Fig. 26-28) at several
particle spacings: crack initiation time, crack angle to the notch, crack
surface (fracture) energy and strain energy at 80 us.

  python3 scripts/validation/kalthoff_winkler.py                  # dp = 0.5, 0.25 mm
  python3 scripts/validation/kalthoff_winkler.py --dp 0.125 --backend cuda --out docs/validation/kalthoff_winkler_seed

Definitions (crack_plate.csv and the last snapshot, reference positions):
  initiation: the crack (particles with s < 0.5) reaches 0.5 mm beyond the notch tip
              along the scene's crack_direction (70 degrees to the notch);
  angle:      of the straight-line fit through the broken particles more than 2 mm
              from the notch tip (above the notch line), to the notch's direction (+x).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fracture_study as fs  # noqa: E402
import mfsd_runs as m  # noqa: E402
import numpy as np  # noqa: E402

SCENE = "configs/kalthoff_winkler_2d.json"
TIP = np.array([0.05, 0.0256])  # m: the notch's tip


def analyse(outdir, dp):
    crack = m.read_csv(os.path.join(outdir, "crack_plate.csv"))
    energies = m.read_csv(os.path.join(outdir, "energies.csv"))
    init = fs.initiation(crack, 0.05 + dp)  # the notch starts one spacing outside the plate
    final = fs.last_snapshot(outdir)
    _, X, s = final
    far = (s < 0.5) & (X[:, 1] > TIP[1]) & (np.hypot(X[:, 0] - TIP[0], X[:, 1] - TIP[1]) > 2e-3)
    angle = fs.angle_of_fit(X[far])
    if angle is not None and angle < 0:
        angle += 180
    return {"dp_mm": dp * 1e3, "initiation_us": init and init * 1e6, "crack_angle_deg": angle,
            "crack_length_at_end_mm": float(crack["length"][-1] * 1e3),
            "energies_at_end": fs.energy_summary(energies)}, crack, energies, final


def main():
    fs.study(__doc__, SCENE, "kalthoff_winkler", [0.5, 0.25], analyse, lambda dp: 0.05 + dp,
             "strain and fracture energy (seed 001 Fig. 28)", "crack reach along 70 degrees [mm]")


if __name__ == "__main__":
    main()
