#!/usr/bin/env python3
"""Scenes of both methods (bodies[].method; host/solver/coupled/): the study
behind docs/validation.md, "Mixed methods".

  rings       the colliding rubber rings 2-D (seed 002 section 5.3) at
              dp = 2 and 1 mm with both rings TLSPH (neo-Hookean, genog),
              both ULSPH (configs/colliding_rings_ulsph_2d.json) and one of
              each (configs/colliding_rings_mixed_2d.json, left TLSPH): total
              energy over time, the loss at the end, each ring's rebound
              (momentum after / before), the momentum error, the largest
              drift of the energy balance.
  projectile  the high-velocity impact 2-D (seed 002 section 5.8) at
              dp = 0.4 and 0.2 mm, all ULSPH
              (configs/projectile_impact_ulsph_2d.json) against the TLSPH
              projectile in the ULSPH plate
              (configs/projectile_impact_mixed_2d.json): residual velocity,
              debris front, hole, momentum error, balance, wall time.

Writes docs/validation/mixed_methods.json and .png.
Usage: scripts/validation/mixed_methods.py [--threads N] [--reuse]
"""
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402

DOCS = os.path.join(m.ROOT, "docs", "validation")
OUT = os.path.join(m.ROOT, "out", "validation", "mixed")
MIXED_RINGS = "configs/colliding_rings_mixed_2d.json"
# The rings' variants: (label, config, overrides).
RINGS = [("TLSPH + TLSPH", MIXED_RINGS, {"bodies.right.method": "tlsph", "bodies.right.material.model": "neo_hookean",
                                         "solver.ulsph": "null"}),
         ("ULSPH + ULSPH", "configs/colliding_rings_ulsph_2d.json", {}),
         ("TLSPH + ULSPH", MIXED_RINGS, {})]
PROJECTILE = [("ULSPH + ULSPH", "configs/projectile_impact_ulsph_2d.json"),
              ("TLSPH + ULSPH", "configs/projectile_impact_mixed_2d.json")]


def rings(args, a):
    cases = []
    for dp, style in ((0.002, "--"), (0.001, "-")):
        for label, config, sets in RINGS:
            out = os.path.join(OUT, f"rings_{label.replace(' + ', '_')}_dp{dp}")
            sets = dict(sets, **{"constants.dp": dp, "output.vtu": "false", "output.interval": 1e-4})
            _, e, timing = m.run_and_read(config, sets, out, args.threads, args.reuse)
            total, balance = e["total"], e["balance"]
            p_left, p_right = e["left.momentum.x"][0], e["right.momentum.x"][0]
            case = {"case": label, "dp": dp, "particles": timing.get("particles"), "steps": timing.get("steps"),
                    "wall_seconds": timing.get("wall_seconds"), "loss": 1 - total[-1] / total[0],
                    "rebound_left": -e["left.momentum.x"][-1] / p_left,
                    "rebound_right": -e["right.momentum.x"][-1] / p_right,
                    "momentum_error": max(abs(px) for px in e["momentum.x"]) / p_left,
                    "balance_drift": max(abs(b / balance[0] - 1) for b in balance)}
            cases.append(case)
            print(f"rings {label} dp = {dp * 1e3:g} mm: loss {100 * case['loss']:.1f} %, rebound "
                  f"{case['rebound_left']:.3f} / {case['rebound_right']:.3f}, momentum error "
                  f"{case['momentum_error']:.1e}, balance drift {100 * case['balance_drift']:.2f} %")
            a.plot(e["time"], [x / total[0] for x in total], style, label=f"{label}, dp = {dp * 1e3:g} mm")
    a.set_xlabel("t [s]")
    a.set_ylabel("(kinetic + stored) / initial")
    a.set_title("colliding rings (seed 002 5.3): total energy", fontsize=9)
    a.legend(fontsize=7)
    return cases


def projectile(args, ax):
    import numpy as np
    import ulsph
    cases = []
    for dp in (0.0004, 0.0002):
        for label, config in PROJECTILE:
            out = os.path.join(OUT, f"projectile_{label.replace(' + ', '_')}_dp{dp}")
            _, e, timing = m.run_and_read(config, {"constants.dp": dp}, out, args.threads, args.reuse)
            case, d = ulsph.projectile_case(out, dp, e, timing)
            case = dict({"case": label}, **case)
            t_end = case["t"]
            x, proj = np.asarray(d["points"]), np.asarray(d["body"]) == 0
            cases.append(case)
            print(f"projectile {label} dp = {dp * 1e3:g} mm: residual velocity "
                  f"{case['projectile_residual_velocity']:.0f} m/s, debris front {1e3 * case['debris_front_x']:.2f} mm, "
                  f"hole half-height {1e3 * case['hole_half_height']:.2f} mm, momentum error "
                  f"{case['momentum_error']:.1e}, balance {case['balance_end']:.4f}, {case['wall_seconds']:.1f} s")
            if dp == 0.0002:
                a = ax[0] if label.startswith("ULSPH") else ax[1]
                up = x[:, 1] >= 0
                a.scatter(1e3 * x[up, 0], 1e3 * x[up, 1], s=0.2, c=np.where(proj[up], 0.2, 0.8), cmap="coolwarm",
                          vmin=0, vmax=1)
                a.set_aspect("equal")
                a.set_xlabel("x [mm]")
                a.set_ylabel("y [mm]")
                a.set_title(f"{label} (projectile blue), dp = 0.2 mm, t = {1e6 * t_end:.0f} us", fontsize=9)
    return cases


def main():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    args = m.study_arguments(__doc__)
    fig, ax = plt.subplots(1, 3, figsize=(16, 4.5))
    result = {"configs": sorted({c for _, c, _ in RINGS} | {c for _, c in PROJECTILE}), "machine": m.machine(),
              "rings": rings(args, ax[0]), "projectile": projectile(args, ax[1:])}
    fig.tight_layout()
    m.write_study(os.path.join(DOCS, "mixed_methods"), result, fig)


if __name__ == "__main__":
    main()
