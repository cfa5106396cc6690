#!/usr/bin/env python3
"""Flyer plate impact of seed 001 section 4.3.1 (configs/flyer_plate_2d.json):
two 1 x 1 m steel plates (J2, linear hardening) meet head-on at +-200 m/s in
plane strain; deformable-deformable contact with contcoeff (contact.stiffness)
5 and restitution 0.95. Seed 001 shows the equivalent plastic strain fields
(Fig. 35) and no numbers; this study records, per resolution L/dp:

  - the momentum of each plate and the total (zero to round-off: the contact
    forces are exactly opposite, the TLSPH forces conserve momentum),
  - the energies (kinetic, stored, plastic work, contact work, the
    Kelvin-Voigt damping's work) and the balance. The scene's formulation
    (genog, damping 0.125, B0 left out of the force sums, as the Taylor bars)
    does not keep it: the force without B0 is not the gradient of the stored
    energy. At the coarsest resolution a conservative run (hourglass none, B0
    in the force sums, no damping) and the scene with B0 in the force sums
    show that the balance with plastic, contact and damping work closes,
  - the closest approach of the two plates' particle centres (interpenetration),
  - the largest equivalent plastic strain and the lateral spreading,
  - the plastic strain field at four instants (the figure, as Fig. 35).

Writes docs/validation/flyer_plate.json and .png.
Usage: scripts/validation/flyer_plate.py [--res 50 100] [--threads N] [--reuse]
"""
import glob
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402
import vtu  # noqa: E402

DOCS = os.path.join(m.ROOT, "docs", "validation")
OUT = os.path.join(m.ROOT, "out", "validation")
CONFIG = "configs/flyer_plate_2d.json"
V0, RHO, L = 200.0, 7870.0, 1.0


def closest_approach(d, dp):
    """Smallest distance between a particle of the lower plate (body 0) and one
    of the upper plate (body 1), among those within 3 dp of the interface."""
    import numpy as np
    x = np.asarray(d["points"], dtype=float)[:, :2]
    body = np.asarray(d["body"])
    near = np.abs(x[:, 1]) < 3 * dp + 0.1 * np.abs(x[:, 1]).min()
    a, b = x[near & (body == 0)], x[near & (body == 1)]
    if len(a) == 0 or len(b) == 0:
        return float("inf")
    best = float("inf")
    for k in range(0, len(a), 256):
        diff = a[k:k + 256, None, :] - b[None, :, :]
        best = min(best, float(np.sqrt((diff ** 2).sum(-1)).min()))
    return best


def run_case(n, sets, tag, threads, reuse):
    import numpy as np
    dp = L / n
    outdir = os.path.join(OUT, tag)
    probes, e, timing = m.run_and_read(CONFIG, {"constants.L_over_dp": n, "output.interval": 5e-5, **sets}, outdir,
                                       threads, reuse)
    p_lower0 = e["lower.momentum.y"][0]
    snaps = sorted(glob.glob(os.path.join(outdir, "snapshots", "*.vtu")))
    fields = [vtu.read_vtu(f) for f in snaps]
    approach = min(closest_approach(d, dp) for d in fields)
    last = fields[-1]
    x = np.asarray(last["points"], dtype=float)
    r = {"L_over_dp": n, "dp": dp, "particles": timing["particles"], "steps": timing["steps"],
         "wall_seconds": timing["wall_seconds"], "particle_steps_per_second": timing["particle_steps_per_second"],
         "mfsd_commit_of_the_run": timing["mfsd_commit_of_the_run"],
         "momentum_lower_initial": p_lower0,
         "momentum_lower_final": e["lower.momentum.y"][-1], "momentum_upper_final": e["upper.momentum.y"][-1],
         "total_momentum_largest_over_plate_momentum": max(abs(p) for p in e["momentum.y"]) / abs(p_lower0),
         "energy_initial": e["balance"][0], "kinetic_final": e["kinetic"][-1], "stored_final": e["strain"][-1],
         "plastic_work_final": e["plastic"][-1], "contact_work_final": e["contact_work"][-1],
         "damping_final": e["damping"][-1],
         "balance_final_over_initial": e["balance"][-1] / e["balance"][0],
         "closest_approach_over_dp": approach / dp,
         "max_plastic_strain": float(np.max(last["plastic_strain"])),
         "half_width_final": float(np.abs(x[:, 0]).max() + dp / 2)}
    return r, e, fields


def plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as pyplot
    return pyplot


def main():
    args = m.study_arguments(__doc__, "resolutions L/dp (default 50 100; seed 001: 100)")
    import numpy as np
    res_list = args.res or [50, 100]
    result = {"study": "flyer_plate", "command": "scripts/validation/flyer_plate.py", "machine": m.machine(),
              "runs": {}}
    p_ = plt()
    fig = p_.figure(figsize=(13, 8))
    grid = fig.add_gridspec(2, 4)
    finest = None
    for n in res_list:
        r, e, fields = run_case(n, {}, f"flyer_plate_L{n}", args.threads, args.reuse)
        result["runs"][str(n)] = r
        finest = (n, e, fields)
        print(f"L/dp = {n}: momentum |sum p|/p_plate {r['total_momentum_largest_over_plate_momentum']:.2e}, "
              f"plate momentum {r['momentum_lower_initial']:.4g} -> {r['momentum_lower_final']:.4g}, "
              f"balance {r['balance_final_over_initial']:.4f} of E0, plastic work {r['plastic_work_final']:.4g} J/m, "
              f"contact work {r['contact_work_final']:.4g} J/m, closest approach {r['closest_approach_over_dp']:.3f} dp, "
              f"max plastic strain {r['max_plastic_strain']:.3f}")
    n0 = min(res_list)
    conservative = {"solver.damping.factor": 0, "solver.hourglass": "none", "solver.kernel_correction_in_force": "true"}
    r, e_und, _ = run_case(n0, conservative, f"flyer_plate_L{n0}_conservative", args.threads, args.reuse)
    r["settings"] = conservative
    result["conservative"] = r
    print(f"L/dp = {n0}, conservative formulation: balance {r['balance_final_over_initial']:.4f} of E0, contact work "
          f"{r['contact_work_final']:.4g} J/m, closest approach {r['closest_approach_over_dp']:.3f} dp")
    # The scene with B0 in the force sums (its damping and genog kept): what
    # the scene's force form (B0 only in dF/dt) does to the balance.
    with_b0 = {"solver.kernel_correction_in_force": "true"}
    r, _, _ = run_case(n0, with_b0, f"flyer_plate_L{n0}_b0_in_force", args.threads, args.reuse)
    r["settings"] = with_b0
    result["scene_with_b0_in_force"] = r
    print(f"L/dp = {n0}, the scene with B0 in the force sums: balance {r['balance_final_over_initial']:.4f} of E0, "
          f"damping {r['damping_final'] / r['energy_initial']:.4f} of E0")

    n, e, fields = finest
    times = [1e3 * t for t in e["time"]]
    picks = [k for k in (5, 8, 12, 20) if k < len(fields)]
    vmax = max(float(np.max(fields[k]["plastic_strain"])) for k in picks)
    for col, k in enumerate(picks):
        ax = fig.add_subplot(grid[0, col])
        x = np.asarray(fields[k]["points"], dtype=float)
        sc = ax.scatter(x[:, 0], x[:, 1], c=fields[k]["plastic_strain"], s=0.3, cmap="viridis", vmin=0, vmax=vmax)
        ax.set_aspect("equal")
        ax.set_xlim(-0.8, 0.8)
        ax.set_ylim(-1.1, 1.1)
        ax.set_title(f"t = {times[k]:.2f} ms", fontsize=9)
        ax.tick_params(labelsize=7)
    fig.colorbar(sc, ax=fig.axes[:len(picks)], shrink=0.8, label="equivalent plastic strain")
    ax = fig.add_subplot(grid[1, 0:2])
    E0 = e["balance"][0]
    for key, label in (("kinetic", "kinetic"), ("strain", "stored elastic"), ("plastic", "plastic work")):
        ax.plot(times, [v / E0 for v in e[key]], label=label)
    ax.plot(times, [-v / E0 for v in e["contact_work"]], label="- contact work")
    ax.plot(times, [v / E0 for v in e["balance"]], "k", label="balance (scene: genog, damping 0.125)")
    ax.plot([1e3 * t for t in e_und["time"]], [v / e_und["balance"][0] for v in e_und["balance"]], "k--",
            label=f"balance, conservative run (L/dp = {n0})")
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("energy / initial kinetic energy")
    ax.legend(fontsize=7)
    ax = fig.add_subplot(grid[1, 2:4])
    p0 = e["lower.momentum.y"][0]
    ax.plot(times, [v / p0 for v in e["lower.momentum.y"]], label="lower plate")
    ax.plot(times, [v / p0 for v in e["upper.momentum.y"]], label="upper plate")
    ax.plot(times, [v / p0 for v in e["momentum.y"]], "k", label="total")
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("y-momentum / initial plate momentum")
    ax.legend(fontsize=7)
    fig.suptitle(f"Flyer plate impact, +-200 m/s, L/dp = {n} (seed 001 section 4.3.1, Fig. 35)")
    m.write_study(os.path.join(DOCS, "flyer_plate"), result, fig)


if __name__ == "__main__":
    main()
