"""Dynamic crack branching (seed 001 section 4.2.1, Fig. 23-25) at several
particle spacings: crack initiation and branching times, branch angle, crack
surface (fracture) energy and strain energy at 80 us, and how they converge.

  python3 scripts/validation/crack_branching.py                   # dp = 0.5, 0.25, 0.125 mm
  python3 scripts/validation/crack_branching.py --dp 0.06125 --backend cuda --out docs/validation/crack_branching_seed

Definitions (measured on the snapshots and crack_plate.csv, reference positions):
  initiation: the crack (particles with s < 0.5) reaches 0.5 mm beyond the notch tip;
  branching:  the crack tip (crack_plate.csv) leaves the notch line for good, by more
              than b = 1 mm + 2 dp, and at the end broken particles lie on both sides;
  angle:      the angle between the two branches, from straight-line fits of the broken
              particles above and below the line beyond the branching point (at the end).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fracture_study as fs  # noqa: E402
import mfsd_runs as m  # noqa: E402
import numpy as np  # noqa: E402

SCENE = "configs/crack_branching_2d.json"
NOTCH_TIP, LINE = 0.05, 0.02  # m: the notch's tip (x) and line (y)


def analyse(outdir, dp):
    crack = m.read_csv(os.path.join(outdir, "crack_plate.csv"))
    energies = m.read_csv(os.path.join(outdir, "energies.csv"))
    t, tip_y = np.array(crack["time"]), np.array(crack["tip.y"])
    notch_length = NOTCH_TIP + dp  # the notch starts one spacing outside the plate
    b = 1e-3 + 2 * dp
    # The tip leaves the notch line for good when the crack has branched (or
    # kinked; the last snapshot tells which).
    off = (np.array(crack["broken"]) > 0) & (np.abs(tip_y - LINE) > b)
    stays = np.nonzero(off & np.flip(np.minimum.accumulate(np.flip(off))))[0]
    branching = float(t[stays[0]]) if len(stays) else None
    final = fs.last_snapshot(outdir)
    _, X, s = final
    sel = (s < 0.5) & (X[:, 0] > NOTCH_TIP)
    angles = [fs.angle_of_fit(X[sel & (side * (X[:, 1] - LINE) > b)]) for side in (1, -1)]
    two_branches = None not in angles
    init = fs.initiation(crack, notch_length)
    return {"dp_mm": dp * 1e3, "initiation_us": init and init * 1e6,
            "branching_us": branching and branching * 1e6, "two_branches": two_branches,
            "branch_angle_deg": abs(angles[0]) + abs(angles[1]) if two_branches else None,
            "tip_extension_at_end_mm": float((crack["length"][-1] - notch_length) * 1e3),
            "energies_at_end": fs.energy_summary(energies)}, crack, energies, final


def main():
    fs.study(__doc__, SCENE, "crack_branching", [0.5, 0.25, 0.125], analyse, lambda dp: NOTCH_TIP + dp,
             "strain and fracture energy (seed 001 Fig. 25)", "crack extension beyond the notch [mm]")


if __name__ == "__main__":
    main()
