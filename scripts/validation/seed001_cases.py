#!/usr/bin/env python3
"""Seed 001 elastodynamic scenes written with the scene features (velocity
conditions with the seed's expressions, measure planes):

  plate     cantilever plate 3D (section 4.1.2) at dx = 2 mm (the seed's
            0.5 mm, 2 million particles, is a bench scene): tip deflection
            u_z(t) against Euler-Bernoulli (eq. 71-74 with the plate's E and
            W0 = 0.06), period and amplitude; energies.
  twisting  twisting column (section 4.1.4, Fig. 21) at the seed's dx = 1/30 m:
            twist angle of the top face over time (the seed: about half a
            torsional cycle by t = 180 ms) and the energy balance.

Writes docs/validation/seed001_<case>.json and .png.
Usage: scripts/validation/seed001_cases.py plate|twisting [--threads N] [--dp DP] [--reuse]
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402

DOCS = os.path.join(m.ROOT, "docs", "validation")
OUT = os.path.join(m.ROOT, "out", "validation")


REUSE = False  # --reuse: analyse the finished run in out/validation again


def run(config, name, sets, threads):
    return m.run_and_read(config, {"output.vtu": "false", **sets}, os.path.join(OUT, name), threads, REUSE)


def energy_panel(ax, e):
    """Kinetic, strain and their sum from energies.csv."""
    for key in ("kinetic", "strain", "total"):
        ax.plot(e["time"], e[key], label=key)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("energy [J]")
    ax.legend(fontsize=7)


def plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as p
    return p


def plate(args):
    dp = args.dp or 2e-3
    p, e, timing = run("configs/cantilever_plate_3d.json", "seed001_plate", {"constants.dp": dp,
                       "solver.end_time": 0.6, "output.interval": 0.005}, args.threads)
    mu, kappa, rho, L0, H0, W0, kw, cb = 0.715e6, 3.25e6, 1000.0, 0.2, 0.02, 0.06, 9.375, 57.0
    E = 9 * kappa * mu / (3 * kappa + mu)
    omega = kw * kw * math.sqrt(E * W0 * H0 ** 3 / 12 / (rho * H0 * W0))
    ref = {"E": E, "period": 2 * math.pi / omega, "amplitude": 0.01 * cb / omega}
    t, uz = p["time"], p["tip.displacement.z"]
    k = max(range(len(t)), key=lambda i: uz[i] if t[i] < 0.75 * ref["period"] else -1e9)
    res = {"study": "seed001_plate", "command": "scripts/validation/seed001_cases.py plate", "machine": m.machine(),
           "dx": dp, "particles": timing["particles"], "steps": timing["steps"],
           "mfsd_commit_of_the_run": timing["mfsd_commit_of_the_run"],
           "wall_seconds": timing["wall_seconds"], "particle_steps_per_second": timing["particle_steps_per_second"],
           "euler_bernoulli": ref, "period": m.period(t, uz), "amplitude": uz[k],
           "energy_balance_largest_deviation": max(abs(b - e["balance"][0]) for b in e["balance"]) / e["balance"][0]}
    res["period_error"] = res["period"] / ref["period"] - 1
    res["amplitude_error"] = res["amplitude"] / ref["amplitude"] - 1
    print(f"plate dx = {dp * 1e3:g} mm: period {res['period']:.4f} s ({100 * res['period_error']:+.1f} % vs "
          f"{ref['period']:.4f}), amplitude {1e3 * res['amplitude']:.2f} mm ({100 * res['amplitude_error']:+.1f} % vs "
          f"{1e3 * ref['amplitude']:.2f})")
    p_ = plt()
    fig, ax = p_.subplots(1, 2, figsize=(11, 4))
    ax[0].plot(t, [1e3 * u for u in uz], label=f"mfsd dx = {dp * 1e3:g} mm")
    ax[0].plot(t, [1e3 * ref["amplitude"] * math.sin(omega * tk) for tk in t], "k--", lw=1, label="Euler-Bernoulli")
    ax[0].set_xlabel("t [s]")
    ax[0].set_ylabel("tip deflection u_z [mm]")
    ax[0].legend(fontsize=7)
    energy_panel(ax[1], e)
    fig.suptitle("Cantilever plate 3D (seed 001 4.1.2), SVK, genog")
    fig.tight_layout()
    return res, fig


def twisting(args):
    dp = args.dp or 1.0 / 30
    p, e, timing = run("configs/twisting_column_seed001_3d.json", "seed001_twisting", {"constants.dp": dp},
                       args.threads)
    t = p["time"]
    # Twist of the top face: the angle of the edge probe about the column axis.
    raw = [math.atan2(y - 0.5, x - 0.5) for x, y in zip(p["edge.position.x"], p["edge.position.y"])]
    ang = [0.0]
    for a, b in zip(raw[:-1], raw[1:]):  # unwrapped: the top turns by more than pi
        ang.append(ang[-1] + (b - a + math.pi) % (2 * math.pi) - math.pi)
    k_max = max(range(len(t)), key=lambda i: ang[i])
    back = next((t[i - 1] + (t[i] - t[i - 1]) * ang[i - 1] / (ang[i - 1] - ang[i])
                 for i in range(k_max + 1, len(t)) if ang[i] <= 0 < ang[i - 1]), float("nan"))
    res = {"study": "seed001_twisting", "command": "scripts/validation/seed001_cases.py twisting",
           "machine": m.machine(), "dx": dp, "particles": timing["particles"], "steps": timing["steps"],
           "mfsd_commit_of_the_run": timing["mfsd_commit_of_the_run"],
           "wall_seconds": timing["wall_seconds"], "particle_steps_per_second": timing["particle_steps_per_second"],
           "largest_twist_rad": ang[k_max], "largest_twist_time": t[k_max], "twist_back_to_zero_time": back,
           "hourglass_mean_peak": max(e["hourglass_mean"]),
           "energy_initial": e["total"][0], "energy_final": e["total"][-1]}
    print(f"twisting dx = {dp:.4f} m: largest twist {res['largest_twist_rad']:.3f} rad at {t[k_max]:.3f} s, back to "
          f"zero at {back:.3f} s (seed: about half a cycle by 0.18 s)")
    p_ = plt()
    fig, ax = p_.subplots(1, 2, figsize=(11, 4))
    ax[0].plot(t, ang)
    ax[0].axvline(0.18, color="k", ls=":", lw=1, label="seed 001: half a cycle at about 180 ms")
    ax[0].set_xlabel("t [s]")
    ax[0].set_ylabel("twist of the top face [rad]")
    ax[0].legend(fontsize=7)
    energy_panel(ax[1], e)
    fig.suptitle(f"Twisting column (seed 001 4.1.4, Fig. 21 expressions), dx = {dp:.4f} m, genog")
    fig.tight_layout()
    return res, fig


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case", choices=["plate", "twisting"])
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--dp", type=float, default=0.0, help="particle spacing (default: see above)")
    ap.add_argument("--reuse", action="store_true", help="analyse the finished run again")
    args = ap.parse_args()
    global REUSE
    REUSE = args.reuse
    res, fig = (plate if args.case == "plate" else twisting)(args)
    m.write_study(os.path.join(DOCS, f"seed001_{args.case}"), res, fig)


if __name__ == "__main__":
    main()
