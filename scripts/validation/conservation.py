#!/usr/bin/env python3
"""Energy conservation of a free elastic block without damping
(tests/regression/scenes/free_block_{2d,3d}.json, initial shear and bending
velocity): the largest relative change of kinetic + strain energy, for each
hourglass variant at CFL 0.6, 0.3 and 0.15, and a body at rest with the
papers' Laplacian form (B0 in the remaining-stress sum).

Writes docs/validation/conservation.json.
Usage: scripts/validation/conservation.py
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402

OUT = os.path.join(m.ROOT, "out", "validation", "conservation")


def main():
    rows = []
    for scene in ("free_block_2d", "free_block_3d"):
        for hourglass in ("none", "laplacian", "genog"):
            row = {"scene": scene, "hourglass": hourglass, "cfl": [], "energy_error": []}
            for cfl in (0.6, 0.3, 0.15):
                out = os.path.join(OUT, f"{scene}_{hourglass}_{cfl}")
                m.run(f"tests/regression/scenes/{scene}.json",
                      {"solver.hourglass": hourglass, "constants.amp": 2, "solver.cfl": cfl,
                       "output.interval": 0.0005}, out, ["--threads", "1"])
                e = m.read_csv(os.path.join(out, "energies.csv"))
                e0 = e["total"][0]
                row["cfl"].append(cfl)
                row["energy_error"].append(max(abs(x - e0) for x in e["total"]) / e0)
            row["max_strain_over_initial"] = max(e["strain"]) / e0
            rows.append(row)
            print(scene, hourglass, ["%.2e" % x for x in row["energy_error"]], flush=True)
    out = os.path.join(OUT, "rest_laplacian_B0_in_force")
    m.run("tests/regression/scenes/free_block_2d.json",
          {"solver.hourglass": "laplacian", "solver.kernel_correction_in_force": "true",
           "bodies.block.initial_velocity": "{}", "solver.end_time": 1, "output.interval": 1e-4},
          out, ["--threads", "1", "--max-steps", "200"])
    e = m.read_csv(os.path.join(out, "energies.csv"))
    rest = {"steps": 200, "strain_energy": e["strain"][-1], "kinetic_energy": e["kinetic"][-1]}
    print("laplacian with B0 in force sums, at rest after 200 steps:", rest)
    path = os.path.join(m.ROOT, "docs", "validation", "conservation.json")
    with open(path, "w") as f:
        json.dump({"command": "scripts/validation/conservation.py", "machine": m.machine(), "energy": rows,
                   "rest_laplacian_B0_in_force": rest}, f, indent=1)
    print("wrote", os.path.relpath(path, m.ROOT))


if __name__ == "__main__":
    main()
