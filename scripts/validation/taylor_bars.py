#!/usr/bin/env python3
"""Taylor bars of seed 000 section 5.5: J2 bars thrown at a rigid frictionless
wall (configs/taylor_bar_*.json, genog, damping factor 0.125).

  round   aluminium, L = 2.346 cm, R = 0.391 cm, perfectly plastic, 373 m/s:
          final length and radius against seed 000 Table 6 (R/dp = 8, 12, 16)
  square  copper, 6 x 6 x 30 mm, linear hardening, 227 m/s: final x of point S
          (middle of a bottom edge) against 6.953 mm (seed 000 Fig. 25, H/dp = 20)
  square_hard  the square bar at 350 m/s (Fig. 26), genog and none: stability,
          particle order (largest hourglass indicator over the run), S, von
          Mises strain at serial instants
  2d      copper, plane strain 6 x 30 mm, 227 m/s and 400 m/s (Fig. 19-21):
          stability, final shape, largest von Mises strain

Final shapes are measured on the last snapshot (80 us; 60 us in 2-D, as in
Fig. 19). The bars bounce off the wall (they move up at about 15 m/s by then),
so the length is the extent z_max - z_min + dp of the particles (each stands
for a cube of side dp; the initial value is L) and the radius r_max + dp/2;
the centre-to-centre values are recorded as well.

--method ulsph runs round and square in updated-Lagrangian SPH with GNOG
(seed 002 sections 5.6-5.7: hypo-elastic J2, radial return, h = 1.3 dp,
CFL 0.4, no damping) instead; the results go to taylor_bars_<case>_ulsph.

Writes docs/validation/taylor_bars_<case>.json and .png.
Usage: scripts/validation/taylor_bars.py round|square|square_hard|2d [--method tlsph|ulsph] [--res 8 12] [--threads N] [--reuse] [--out STEM]
"""
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402
import vtu  # noqa: E402

DOCS = os.path.join(m.ROOT, "docs", "validation")
OUT = os.path.join(m.ROOT, "out", "validation")
TABLE6 = {8: (1.4908, 0.9075), 12: (1.4631, 0.9323), 16: (1.4546, 0.9616)}  # cm, seed 000 Table 6
CHEN = (1.454, 1.051)  # Chen et al. (1996), quoted in Table 6
S_SEED = 6.953e-3  # m, seed 000 Fig. 25 at H/dp = 20


def final_shape(outdir, dim, dp):
    """Length and radius (particle extents, see above; *_centres without dp),
    half width (largest |x| + dp/2), largest plastic and von Mises strain, and
    the points, of the last snapshot."""
    import numpy as np
    f = vtu.snapshots(outdir)[-1][1]
    d = vtu.read_vtu(f)
    x = np.asarray(d["points"], dtype=float)
    up = x[:, dim - 1]
    r = np.hypot(x[:, 0], x[:, 1]) if dim == 3 else np.abs(x[:, 0])
    return {"length": float(up.max() - up.min() + dp), "radius": float(r.max() + dp / 2),
            "length_centres": float(up.max() - up.min()), "radius_centres": float(r.max()),
            "half_width": float(np.abs(x[:, 0]).max() + dp / 2), "lift_off": float(up.min() - dp / 2),
            "max_plastic_strain": float(np.max(d["plastic_strain"])),
            "max_von_mises_strain": float(np.max(d["von_mises_strain"])) if "von_mises_strain" in d else None,
            "hourglass_max": float(np.max(d["hourglass"])) if "hourglass" in d else None, "points": x,
            "reference": x - np.asarray(d["displacement"], dtype=float),
            "hourglass": np.asarray(d["hourglass"], dtype=float) if "hourglass" in d else None}


ARRAYS = ("points", "reference", "hourglass")  # final_shape's per-particle fields


# The same bar in ULSPH (seed 002): the TLSPH-only keys of the configs removed.
ULSPH = {"solver.method": "ulsph", "solver.hourglass": "gnog", "solver.h_over_dp": 1.3, "solver.cfl": 0.4,
         "solver.kernel_correction_in_force": "null", "solver.damping": "null"}
METHOD = "tlsph"


def run_case(config, tag, sets, dim, dp, threads, reuse):
    if METHOD == "ulsph":
        sets, tag = {**sets, **ULSPH}, tag + "_ulsph"
    outdir = os.path.join(OUT, tag)
    p, e, timing = m.run_and_read(config, sets, outdir, threads, reuse)
    s = final_shape(outdir, dim, dp)
    res = {"particles": timing["particles"], "steps": timing["steps"], "wall_seconds": timing["wall_seconds"],
           "particle_steps_per_second": timing["particle_steps_per_second"],
           "mfsd_commit_of_the_run": timing["mfsd_commit_of_the_run"],
           "energy_initial": e["balance"][0], "plastic_work_final": e["plastic"][-1],
           "kinetic_final": e["kinetic"][-1], "wall_work": e["boundary_work"][-1],
           "energy_balance_final": e["balance"][-1]}
    res.update({k: v for k, v in s.items() if k not in ARRAYS})
    return res, s, p, e


def plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as pyplot
    return pyplot


def round_bar(args):
    res = {"study": "taylor_bar_round", "command": "scripts/validation/taylor_bars.py round", "machine": m.machine(),
           "seed_table6_cm": {str(k): v for k, v in TABLE6.items()}, "chen_1996_cm": CHEN, "runs": {}}
    p_ = plt()
    fig, ax = p_.subplots(1, 2, figsize=(11, 4.5))
    for n in args.res or [4, 8]:
        dp = 0.391e-2 / n
        r, shape, probes, _ = run_case("configs/taylor_bar_3d_round.json", f"taylor_round_R{n}",
                                  {"constants.R_over_dp": n, "output.interval": 8e-6}, 3, dp, args.threads,
                                  args.reuse)
        r["dp"] = dp
        r["length_cm"], r["radius_cm"] = 100 * r["length"], 100 * r["radius"]
        if n in TABLE6:
            L6, R6 = TABLE6[n]
            r["length_error_vs_seed"] = r["length_cm"] / L6 - 1
            r["radius_error_vs_seed"] = r["radius_cm"] / R6 - 1
        res["runs"][str(n)] = r
        seed = f" (seed {TABLE6[n][0]:.4f} / {TABLE6[n][1]:.4f})" if n in TABLE6 else ""
        print(f"round R/dp = {n}: length {r['length_cm']:.4f} cm, radius {r['radius_cm']:.4f} cm{seed}; "
              f"centres {100 * r['length_centres']:.4f} / {100 * r['radius_centres']:.4f}; "
              f"lift-off {1e3 * r['lift_off']:.2f} mm")
        pts = shape["points"]
        rr = (pts[:, 0] ** 2 + pts[:, 1] ** 2) ** 0.5
        ax[0].scatter(100 * rr * (1 - 2 * (pts[:, 1] < 0)), 100 * (pts[:, 2] - pts[:, 2].min() + dp / 2), s=1,
                      label=f"R/dp = {n}")
        ax[1].plot([1e6 * t for t in probes["time"]], [100 * z for z in probes["top.position.z"]], label=f"R/dp = {n}")
    for n, (L6, R6) in TABLE6.items():
        ax[0].plot([-R6, R6], [L6, L6], ":", lw=1)
        ax[0].plot([R6, R6], [0, 0.2], ":", lw=1, label=f"seed 000 Table 6, R/dp = {n}")
    ax[0].set_aspect("equal")
    ax[0].set_xlabel("signed radius [cm]")
    ax[0].set_ylabel("z [cm]")
    ax[0].legend(fontsize=6, markerscale=5)
    ax[1].axhline(TABLE6[16][0], color="k", ls=":", lw=1, label="seed 000, R/dp = 16")
    ax[1].set_xlabel("t [us]")
    ax[1].set_ylabel("top of the bar [cm]")
    ax[1].legend(fontsize=7)
    fig.suptitle("Round aluminium Taylor bar, 373 m/s (seed 000 Table 6), final shape at 80 us")
    fig.tight_layout()
    return res, fig


def square_bar(args):
    res = {"study": "taylor_bar_square", "command": "scripts/validation/taylor_bars.py square", "machine": m.machine(),
           "seed_S_x": S_SEED, "runs": {}}
    p_ = plt()
    fig, ax = p_.subplots(1, 2, figsize=(11, 4.5))
    for n in args.res or [8, 12]:
        dp = 0.006 / n
        r, shape, probes, _ = run_case("configs/taylor_bar_3d_square.json", f"taylor_square_H{n}",
                                  {"constants.H_over_dp": n, "output.interval": 8e-6}, 3, dp, args.threads,
                                  args.reuse)
        r["dp"] = dp
        r["S_x"] = probes["S.position.x"][-1]
        r["S_x_plus_half_dp"] = r["S_x"] + dp / 2
        r["S_x_error_vs_seed"] = r["S_x"] / S_SEED - 1
        res["runs"][str(n)] = r
        print(f"square H/dp = {n}: S x = {1e3 * r['S_x']:.3f} mm (+dp/2: {1e3 * r['S_x_plus_half_dp']:.3f}); "
              f"seed 6.953 mm at H/dp = 20; length {1e3 * r['length']:.2f} mm")
        ax[0].plot([1e6 * t for t in probes["time"]], [1e3 * x for x in probes["S.position.x"]], label=f"H/dp = {n}")
        pts, sel = shape["points"], abs(shape["reference"][:, 1]) < dp  # the two layers next to the plane y = 0
        ax[1].scatter(1e3 * pts[sel, 0], 1e3 * pts[sel, 2], s=1, label=f"H/dp = {n}")
    ax[0].axhline(1e3 * S_SEED, color="k", ls=":", lw=1, label="seed 000 Fig. 25, H/dp = 20")
    ax[0].set_xlabel("t [us]")
    ax[0].set_ylabel("x of point S [mm]")
    ax[0].legend(fontsize=7)
    ax[1].set_aspect("equal")
    ax[1].set_xlabel("x [mm]")
    ax[1].set_ylabel("z [mm]")
    ax[1].set_title("particles of the mid-plane layers (|Y| < dp) at 80 us", fontsize=9)
    ax[1].legend(fontsize=7, markerscale=5)
    fig.suptitle("Square copper Taylor bar, 227 m/s (seed 000 Fig. 22-25)")
    fig.tight_layout()
    return res, fig


def square_hard(args):
    """Seed 000 Fig. 26: the square copper bar at 350 m/s. The seed shows
    orderly particles and a smooth field with genog at H/dp = 20; the largest
    hourglass indicator over the run measures the order, `none` is the contrast."""
    import numpy as np
    res = {"study": "taylor_bar_square_hard", "command": "scripts/validation/taylor_bars.py square_hard",
           "machine": m.machine(), "v0": 350.0, "runs": {}}
    p_ = plt()
    resolutions = args.res or [8, 12]
    fig = p_.figure(figsize=(13, 8))
    grid = fig.add_gridspec(3, 6, width_ratios=[1, 1, 1, 1, 0.25, 1.9], height_ratios=[1, 1, 0.05])
    fig.subplots_adjust(left=0.05, right=0.98, top=0.92, bottom=0.07, wspace=0.3, hspace=0.35)
    history = [fig.add_subplot(grid[0, 5]), fig.add_subplot(grid[1:, 5])]
    interval = 2e-6  # snapshots and energies.csv rows: the hourglass history at 40 instants
    times = [2e-5, 4e-5, 6e-5, 8e-5]
    image = None
    for hourglass, style in (("genog", "-"), ("none", "--")):
        for n in resolutions:
            dp = 0.006 / n
            tag = f"taylor_square_H{n}_v350_{hourglass}"
            r, shape, probes, e = run_case("configs/taylor_bar_3d_square.json", tag,
                                       {"constants.H_over_dp": n, "constants.v0": 350.0,
                                        "solver.hourglass": hourglass, "output.interval": interval}, 3, dp,
                                       args.threads, args.reuse)
            r["dp"] = dp
            r["S_x"] = probes["S.position.x"][-1]
            r["hourglass_max_over_run"] = max(e["hourglass_max"])
            # where the disorder sits at the end: the two reference layers next to the wall
            # (crushed into one layer at the axis) against the rest of the bar
            h = shape["hourglass"]
            foot = shape["reference"][:, 2] < 2 * dp
            r["hourglass_median_final"] = float(np.median(h))
            r["hourglass_p99_final"] = float(np.percentile(h, 99))
            r["hourglass_max_final_two_wall_layers"] = float(h[foot].max())
            r["hourglass_max_final_above"] = float(h[~foot].max())
            res["runs"][f"H{n}_{hourglass}"] = r
            print(f"square 350 m/s H/dp = {n}, {hourglass}: S x = {1e3 * r['S_x']:.3f} mm, length "
                  f"{1e3 * r['length']:.2f} mm, hourglass max over the run {r['hourglass_max_over_run']:.3f} "
                  f"(end: median "
                  f"{r['hourglass_median_final']:.3f}, p99 {r['hourglass_p99_final']:.3f}, wall layers "
                  f"{r['hourglass_max_final_two_wall_layers']:.3f}, above {r['hourglass_max_final_above']:.3f}), "
                  f"max von Mises strain {r['max_von_mises_strain']:.2f}, max plastic strain "
                  f"{r['max_plastic_strain']:.2f}")
            label = f"H/dp = {n}, {hourglass}"
            history[0].plot([1e6 * t for t in e["time"]], e["hourglass_max"], style, label=label)
            history[1].plot([1e6 * t for t in probes["time"]], [1e3 * x for x in probes["S.position.x"]], style,
                            label=label)
            if n != max(resolutions):
                continue
            # the mid-plane layers (reference y = +-dp/2) at serial instants, as Fig. 26
            row = 0 if hourglass == "genog" else 1
            snaps = vtu.snapshots(os.path.join(OUT, tag))
            for col, t in enumerate(times):
                d = vtu.read_vtu(vtu.nearest_snapshot(snaps, t)[1])
                x = np.asarray(d["points"], dtype=float)
                sel = vtu.mid_plane(d, dp)
                a = fig.add_subplot(grid[row, col])
                image = a.scatter(1e3 * x[sel, 0], 1e3 * x[sel, 2], c=np.asarray(d["von_mises_strain"])[sel],
                                  s=max(0.3, 40.0 / n ** 1.5), cmap="jet", vmin=0, vmax=3, linewidths=0)
                a.set_aspect("equal")
                a.set_xlim(-12, 12)
                a.set_ylim(-0.5, 25)
                a.set_title(f"{hourglass}, {1e6 * t:.0f} us", fontsize=9)
                a.tick_params(labelsize=7)
                if col == 0:
                    a.set_ylabel(f"z [mm] (H/dp = {n})", fontsize=8)
    fig.colorbar(image, cax=fig.add_subplot(grid[2, :4]), orientation="horizontal", label="von Mises strain")
    history[0].set_ylabel("largest hourglass indicator")
    history[0].set_yscale("log")
    history[1].set_ylabel("x of point S [mm]")
    history[1].set_xlabel("t [us]")
    for a in history:
        a.legend(fontsize=7)
    fig.suptitle("Square copper Taylor bar, 350 m/s (seed 000 Fig. 26): mid-plane layers coloured by the von "
                 "Mises strain")
    return res, fig


def bar_2d(args):
    res = {"study": "taylor_bar_2d", "command": "scripts/validation/taylor_bars.py 2d", "machine": m.machine(),
           "runs": {}}
    p_ = plt()
    cases = [(n, v) for n in (args.res or [10, 20, 40]) for v in (227.0, 400.0)]
    fig, ax = p_.subplots(1, 2, figsize=(11, 5))
    for n, v0 in cases:
        r, shape, probes, _ = run_case("configs/taylor_bar_2d.json", f"taylor_2d_H{n}_v{int(v0)}",
                                  {"constants.H_over_dp": n, "constants.v0": v0, "output.interval": 6e-6}, 2,
                                  0.006 / n, args.threads, args.reuse)
        res["runs"][f"H{n}_v{int(v0)}"] = r
        print(f"2d H/dp = {n}, v0 = {v0:g}: length {1e3 * r['length']:.2f} mm, half width "
              f"{1e3 * r['half_width']:.2f} mm, max plastic strain {r['max_plastic_strain']:.2f}, max von Mises "
              f"strain {r['max_von_mises_strain']:.1f}, hourglass max {r['hourglass_max']:.3f}")
        a = ax[0] if v0 == 227.0 else ax[1]
        a.scatter(1e3 * shape["points"][:, 0], 1e3 * shape["points"][:, 1], s=0.5, label=f"H/dp = {n}")
    for a, v0 in zip(ax, (227, 400)):
        a.set_aspect("equal")
        a.set_xlabel("x [mm]")
        a.set_ylabel("y [mm]")
        a.set_title(f"{v0} m/s, t = 60 us", fontsize=9)
        a.legend(fontsize=7, markerscale=8)
    fig.suptitle("2-D copper Taylor bar (seed 000 Fig. 19-21), genog")
    fig.tight_layout()
    return res, fig


def main():
    args = m.study_arguments(
        __doc__, "resolutions (R/dp, H/dp)",
        "stem of the result files in docs/validation (default taylor_bars_<case>; "
        "e.g. a bench resolution on its own: --res 16 --out taylor_bars_round_R16)",
        lambda ap: (ap.add_argument("case", choices=["round", "square", "square_hard", "2d"]),
                    ap.add_argument("--method", choices=["tlsph", "ulsph"], default="tlsph")))
    global METHOD
    METHOD = args.method
    if METHOD == "ulsph" and args.case not in ("round", "square"):
        sys.exit("--method ulsph: round or square")
    res, fig = {"round": round_bar, "square": square_bar, "square_hard": square_hard, "2d": bar_2d}[args.case](args)
    if METHOD == "ulsph":
        res["method"] = "ulsph (seed 002): " + ", ".join(f"{k}={v}" for k, v in ULSPH.items())
        fig.suptitle(fig._suptitle.get_text() + " -- ULSPH with GNOG")
    suffix = "_ulsph" if METHOD == "ulsph" else ""
    m.write_study(os.path.join(DOCS, args.out or f"taylor_bars_{args.case}{suffix}"), res, fig)


if __name__ == "__main__":
    main()
