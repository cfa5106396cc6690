#!/usr/bin/env python3
"""ULSPH with GNOG (seed 002): the studies behind docs/validation.md.

  plate     oscillating plate 2-D (configs/oscillating_plate_ulsph_2d.json,
            nu = 0.3975, h = 1.3 dp): the period of the first two
            oscillations for v_f = 0.001, 0.01, 0.03, 0.05 at H/dp = --res
            (default 10 20) against seed 002 Table 1 (0.275 0.273 0.272 0.272)
            and theory (0.254); tip deflection plot.
  spinning  spinning plate (configs/spinning_plate_ulsph_2d.json): angular
            momentum L = sum m x ^ v and polar moment I = sum m |x|^2 over
            time for gnog and gnog_amc with single-criterion stepping, gnog_amc
            with dual stepping (pair data formed every step, and frozen over the
            advection step as in the seed), and the same plate in TLSPH
            (neo-Hookean, genog); the corner's distance from the centre.
  long      the oscillating plate over 30+ oscillations (v_f = 0.05,
            H/dp = 10, 8.5 s; seed 002 Fig. 5): the period and amplitude of
            every oscillation and the energy at the end.
  column    bending column 3-D (configs/bending_column_ulsph_3d.json,
            seed 002 section 5.2) at H/dp = --res (default 6 12) to 2 s,
            against the TLSPH column (configs/bending_column_3d.json, genog,
            as shipped) at the same resolutions: z(t) of the top centre S,
            its first minimum, and kinetic + stored energy.
  projectile  high-velocity impact 2-D (configs/projectile_impact_ulsph_2d.json,
            seed 002 section 5.8) at dp = 0.4, 0.2, 0.1 mm: the particles at
            8 us (upper half, as the seed's Fig. 29), the projectile's
            residual velocity, the debris cloud's front, the hole in the plate,
            momentum and the energy split.
  pin       striker pin fuse 3-D (configs/striker_pin_ulsph_3d.json, seed 002
            section 5.9) at dp = 0.4 mm with v0 = 200 and 400 m/s and at
            dp = 0.2 mm with 400 m/s: the pairs of plate particles within 2h
            across the two groove lines (0: the centre piece is cut out),
            the failed particles, the mid-plane particles at the end.
  punch     the punched block (tests/regression/scenes/punched_block_2d.json)
            in TLSPH and ULSPH: the punch force at the end for the shipped
            indentation, half the spacing, and two smaller indentations
            (constants.vp 0.035, 0.03); the ULSPH / TLSPH ratio.
  rings     colliding rubber rings 2-D (configs/colliding_rings_ulsph_2d.json)
            at dp = 2, 1, 0.5 mm and hollow balls 3-D
            (configs/colliding_balls_ulsph_3d.json) at dp = 3, 2 mm: kinetic,
            stored and total energy over time, the momentum error, the rebound
            (left body's momentum after / before) against seed 002 (2-D:
            65.88 -> 56.74 per ring, 3-D: 8.27 -> 8.16).

Writes docs/validation/ulsph_<study>.json and .png.
Usage: scripts/validation/ulsph.py plate|spinning|rings|long|column|projectile|pin|punch [--res 10 20] [--threads N] [--reuse]
"""
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402

DOCS = os.path.join(m.ROOT, "docs", "validation")
OUT = os.path.join(m.ROOT, "out", "validation", "ulsph")
TABLE1 = {0.001: 0.275, 0.01: 0.273, 0.03: 0.272, 0.05: 0.272}  # seed 002 Table 1, SPH-GNOG
THEORY = 0.254


def plate(args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    res = args.res or [10, 20]
    result = {"config": "configs/oscillating_plate_ulsph_2d.json", "machine": m.machine(), "cases": []}
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5))
    for r in res:
        for vf, seed in TABLE1.items():
            out = os.path.join(OUT, f"plate_vf{vf}_H{r}")
            p = m.plate_run("configs/oscillating_plate_ulsph_2d.json",
                            {"constants.vf": vf, "constants.H_over_dp": r, "solver.end_time": 0.62,
                             "output.vtu": "false"}, out, args.threads, args.reuse)
            t, y, T = p["t"], p["y"], p["period"]
            case = {"H_over_dp": r, "vf": vf, "period": T, "seed": seed, "error_vs_seed": T / seed - 1,
                    "error_vs_theory": T / THEORY - 1, "energy_range": p["energy_range"],
                    "particle_steps_per_second": p["timing"].get("particle_steps_per_second")}
            result["cases"].append(case)
            print(f"H/dp={r} vf={vf}: T={T:.4f} (seed {seed}, {100 * case['error_vs_seed']:+.2f} %)")
            if vf == 0.05:
                ax[0].plot(t, [v / vf for v in y], label=f"H/dp = {r}, v_f = {vf}")
        ax[1].plot(list(TABLE1), [c["period"] for c in result["cases"] if c["H_over_dp"] == r], "o-",
                   label=f"mfsd H/dp = {r}")
    ax[1].plot(list(TABLE1), list(TABLE1.values()), "ks--", label="seed 002 Table 1")
    ax[1].axhline(THEORY, color="gray", lw=0.8, label="theory 0.254")
    ax[0].set_xlabel("t [s]")
    ax[0].set_ylabel("tip y / v_f")
    ax[0].legend()
    ax[1].set_xscale("log")
    ax[1].set_xlabel("v_f")
    ax[1].set_ylabel("period [s]")
    ax[1].legend()
    fig.suptitle("ULSPH oscillating plate (nu = 0.3975, h = 1.3 dp)")
    fig.tight_layout()
    m.write_study(os.path.join(DOCS, "ulsph_plate"), result, fig)


def spin_history(outdir):
    import numpy as np
    import vtu
    rows = []
    for t, path in vtu.snapshots(outdir):
        s = vtu.read_vtu(path)
        x, v = s["points"][:, :2], s["velocity"][:, :2]
        L = float(np.sum(x[:, 0] * v[:, 1] - x[:, 1] * v[:, 0]))
        I = float(np.sum(x[:, 0] ** 2 + x[:, 1] ** 2))
        rows.append((t, L, I))
    return rows


OMEGA = 105.0  # rad/s, configs/spinning_plate_ulsph_2d.json


def corner_against_rotation(probes, times=(0.001, 0.002, 0.005, 0.01, 0.05, 0.2)):
    """The corner probe against the rigid rotation of the seed's Fig. 19:
    x = R(omega t) X0, v = omega e_z ^ x; errors relative to |X0| and omega |X0|
    at the probe rows nearest `times`."""
    import math
    t = probes["time"]
    X0 = (probes["corner.position.x"][0], probes["corner.position.y"][0])
    r0 = math.hypot(*X0)
    out = []
    for want in times:
        k = min(range(len(t)), key=lambda i: abs(t[i] - want))
        c, s = math.cos(OMEGA * t[k]), math.sin(OMEGA * t[k])
        x = (c * X0[0] - s * X0[1], s * X0[0] + c * X0[1])
        v = (-OMEGA * x[1], OMEGA * x[0])
        dx = math.hypot(probes["corner.position.x"][k] - x[0], probes["corner.position.y"][k] - x[1])
        dv = math.hypot(probes["corner.velocity.x"][k] - v[0], probes["corner.velocity.y"][k] - v[1])
        out.append({"t": t[k], "position_error": dx / r0, "velocity_error": dv / (OMEGA * r0)})
    return out


def spinning(args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cases = [("gnog_amc single", {"solver.hourglass": "gnog_amc"}),
             ("gnog single", {"solver.hourglass": "gnog"}),
             ("gnog_amc dual", {"solver.hourglass": "gnog_amc", "solver.ulsph.time_stepping": "dual"}),
             ("gnog_amc dual frozen pairs", {"solver.hourglass": "gnog_amc", "solver.ulsph.time_stepping": "dual",
                                             "solver.ulsph.refresh_pairs": "false"}),
             ("TLSPH genog", {"solver.method": "tlsph", "solver.hourglass": "genog", "solver.ulsph": "null",
                              "bodies.plate.material.model": "neo_hookean", "solver.cfl": 0.4})]
    result = {"config": "configs/spinning_plate_ulsph_2d.json", "machine": m.machine(), "cases": []}
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    for name, sets in cases:
        out = os.path.join(OUT, "spinning_" + name.replace(" ", "_"))
        probes, _, _ = m.run_and_read("configs/spinning_plate_ulsph_2d.json", sets, out, args.threads, args.reuse)
        h = spin_history(out)
        t = [r[0] for r in h]
        L0 = h[0][1]
        rigid = corner_against_rotation(probes)
        result["cases"].append({"case": name, "L_change": h[-1][1] / L0 - 1, "I_end": h[-1][2],
                                "omega_end": h[-1][1] / h[-1][2], "t_end": t[-1], "corner_vs_rigid_rotation": rigid})
        print(f"{name}: L {100 * (h[-1][1] / L0 - 1):+.2f} %, I = {h[-1][2]:.2f}, omega = {h[-1][1] / h[-1][2]:.2f}; "
              "corner against the rigid rotation (t [ms]: position, velocity error / |X0|, / omega |X0|): " +
              ", ".join(f"{1e3 * r['t']:g}: {r['position_error']:.1e} {r['velocity_error']:.1e}" for r in rigid))
        ax[0].plot(t, [r[1] / L0 for r in h], label=name)
        ax[1].plot(t, [r[2] for r in h], label=name)
        r = [(x * x + y * y) ** 0.5 for x, y in zip(probes["corner.position.x"], probes["corner.position.y"])]
        ax[2].plot(probes["time"], r, label=name)
    ax[0].set_ylabel("L / L(0)")
    ax[1].set_ylabel("I = sum |x|^2 (per unit mass)")
    ax[2].set_ylabel("corner distance from the centre [m]")
    for a in ax:
        a.set_xlabel("t [s]")
        a.legend()
    fig.suptitle("spinning plate, omega = 105 rad/s (seed 002 section 5.5)")
    fig.tight_layout()
    m.write_study(os.path.join(DOCS, "ulsph_spinning"), result, fig)


def long_plate(args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    res = (args.res or [10])[0]
    out = os.path.join(OUT, f"plate_long_H{res}")
    probes, energies, timing = m.run_and_read(
        "configs/oscillating_plate_ulsph_2d.json",
        {"constants.H_over_dp": res, "solver.end_time": 8.5, "output.interval": 0.5, "output.probe_interval": 5e-4},
        out, args.threads, args.reuse)
    t, y = probes["time"], probes["tip.position.y"]
    c = m.crossings(t, y)
    periods = [c[k + 2] - c[k] for k in range(0, len(c) - 2, 2)]
    amplitudes = []
    for k in range(0, len(c) - 2, 2):
        seg = [abs(yy - y[0]) for tt, yy in zip(t, y) if c[k] <= tt <= c[k + 2]]
        amplitudes.append(max(seg))
    e = [a + b for a, b in zip(energies["kinetic"], energies["strain"])]
    result = {"config": "configs/oscillating_plate_ulsph_2d.json", "machine": m.machine(), "H_over_dp": res,
              "oscillations": len(periods), "periods": periods, "amplitudes": amplitudes,
              "period_first": periods[0], "period_last": periods[-1], "amplitude_ratio_last_first":
              amplitudes[-1] / amplitudes[0], "energy_end": e[-1] / e[0],
              "wall_seconds": timing.get("wall_seconds"), "steps": timing.get("steps")}
    print(f"{len(periods)} oscillations: period {periods[0]:.4f} -> {periods[-1]:.4f}, amplitude x "
          f"{amplitudes[-1] / amplitudes[0]:.3f}, energy x {e[-1] / e[0]:.3f}")
    fig, ax = plt.subplots(1, 2, figsize=(13, 4.5))
    ax[0].plot(t, y, lw=0.6)
    ax[0].set_xlabel("t [s]")
    ax[0].set_ylabel("tip y [m]")
    ax[0].set_title(f"{len(periods)} oscillations, H/dp = {res}, v_f = 0.05")
    ax[1].plot(range(1, len(periods) + 1), periods, "o-", label="period [s]")
    ax[1].axhline(0.272, color="k", lw=0.8, label="seed 002 Table 1 (first period)")
    ax[1].set_xlabel("oscillation")
    ax[1].set_ylabel("period [s]")
    a2 = ax[1].twinx()
    a2.plot(range(1, len(amplitudes) + 1), amplitudes, "s--", color="C1", label="amplitude [m]")
    a2.set_ylabel("amplitude [m]")
    ax[1].legend(loc="lower left")
    a2.legend(loc="lower right")
    fig.tight_layout()
    m.write_study(os.path.join(DOCS, "ulsph_plate_long"), result, fig)


def particle_panel(a, h, v, colour, cmap, size, labels, title):
    """One panel of particles (mm) coloured by a field, equal axes."""
    a.scatter(1e3 * h, 1e3 * v, s=size, c=colour, cmap=cmap)
    a.set_aspect("equal")
    a.set_xlabel(labels[0])
    a.set_ylabel(labels[1])
    a.set_title(title, fontsize=9)


def first_minimum(t, z):
    for k in range(1, len(z) - 1):
        if z[k] < z[k - 1] and z[k] <= z[k + 1] and t[k] > 0.05:
            return t[k], z[k]
    return float("nan"), float("nan")


def column(args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    res = args.res or [6, 12]
    result = {"configs": ["configs/bending_column_ulsph_3d.json", "configs/bending_column_3d.json"],
              "machine": m.machine(), "cases": []}
    fig, ax = plt.subplots(1, 2, figsize=(13, 4.5))
    for r in res:
        for method, config in (("ULSPH gnog", "configs/bending_column_ulsph_3d.json"),
                               ("TLSPH genog", "configs/bending_column_3d.json")):
            out = os.path.join(OUT, f"column_{method.split()[0].lower()}_H{r}")
            probes, e, timing = m.run_and_read(config, {"constants.H_over_dp": r, "solver.end_time": 2.0,
                                                        "output.vtu": "false", "output.interval": 0.02},
                                               out, args.threads, args.reuse)
            t, z = probes["time"], probes["S.position.z"]
            tmin, zmin = first_minimum(t, z)
            total = [a + b for a, b in zip(e["kinetic"], e["strain"])]
            case = {"method": method, "H_over_dp": r, "particles": timing.get("particles"),
                    "steps": timing.get("steps"), "wall_seconds": timing.get("wall_seconds"),
                    "first_minimum_time": tmin, "first_minimum_z": zmin, "energy_end": total[-1] / total[0]}
            result["cases"].append(case)
            print(f"{method} H/dp={r}: first minimum of z(S) {zmin:.3f} m at {tmin:.3f} s; "
                  f"kinetic + stored at 2 s: {case['energy_end']:.3f} of the start")
            style = "-" if method.startswith("ULSPH") else "--"
            ax[0].plot(t, z, style, label=f"{method}, H/dp = {r}")
            ax[1].plot(e["time"], [x / total[0] for x in total], style, label=f"{method}, H/dp = {r}")
    ax[0].set_ylabel("z of S [m]")
    ax[1].set_ylabel("(kinetic + stored) / start")
    for a in ax:
        a.set_xlabel("t [s]")
        a.legend(fontsize=8)
    fig.suptitle("bending column 3-D, v0 = 10 m/s (seed 002 section 5.2 against TLSPH)")
    fig.tight_layout()
    m.write_study(os.path.join(DOCS, "ulsph_column"), result, fig)


def projectile_case(out, dp, e, timing):
    """The perforation figures of a finished projectile run (its last
    snapshot; the projectile is body 0, the 2 mm plate starts at x = 0):
    (case dict, the snapshot)."""
    import numpy as np
    import vtu
    t_end, path = vtu.snapshots(out)[-1]
    d = vtu.read_vtu(path)
    x, body, v = np.asarray(d["points"]), np.asarray(d["body"]), np.asarray(d["velocity"])
    proj = body == 0
    plate_now = x[~proj]
    # The hole: the smallest |y| of a plate particle still within the plate's thickness.
    in_plate = (plate_now[:, 0] > -dp) & (plate_now[:, 0] < 0.002 + dp)
    total0 = e["balance"][0]
    case = {"dp": dp, "particles": timing.get("particles"), "steps": timing.get("steps"),
            "wall_seconds": timing.get("wall_seconds"), "t": t_end,
            "projectile_residual_velocity": float(np.mean(v[proj, 0])),
            "debris_front_x": float(x[:, 0].max()),
            "hole_half_height": float(np.min(np.abs(plate_now[in_plate, 1]))),
            "momentum_error": max(abs(px - e["momentum.x"][0]) for px in e["momentum.x"]) / e["projectile.momentum.x"][0],
            "plastic_share": e["plastic"][-1] / total0, "numerical_share": e["damping"][-1] / total0,
            "balance_end": e["balance"][-1] / total0}
    return case, d


def projectile(args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    import vtu
    config = "configs/projectile_impact_ulsph_2d.json"
    result = {"config": config, "machine": m.machine(), "cases": []}
    spacings = (0.0004, 0.0002, 0.0001)
    fig, ax = plt.subplots(1, len(spacings), figsize=(5 * len(spacings), 4.5))
    for a, dp in zip(ax, spacings):
        out = os.path.join(OUT, f"projectile_dp{dp}")
        _, e, timing = m.run_and_read(config, {"constants.dp": dp}, out, args.threads, args.reuse)
        case, d = projectile_case(out, dp, e, timing)
        x, hole, drift, t_end = np.asarray(d["points"]), case["hole_half_height"], case["momentum_error"], case["t"]
        result["cases"].append(case)
        print(f"dp = {dp * 1e3:g} mm: residual velocity {case['projectile_residual_velocity']:.0f} m/s, debris front "
              f"{1e3 * case['debris_front_x']:.2f} mm, hole half-height {1e3 * hole:.2f} mm, plastic "
              f"{case['plastic_share']:.3f}, numerical {case['numerical_share']:.3f}, balance {case['balance_end']:.4f}, "
              f"momentum error {drift:.1e}")
        up = x[:, 1] >= 0
        particle_panel(a, x[up, 0], x[up, 1], np.asarray(d["von_mises"])[up], "jet", 0.2, ("x [mm]", "y [mm]"),
                       f"dp = {dp * 1e3:g} mm, t = {1e6 * t_end:.1f} us (von Mises)")
    fig.suptitle("aluminium disc at 3100 m/s through a 2 mm plate (seed 002 section 5.8), upper half")
    fig.tight_layout()
    m.write_study(os.path.join(DOCS, "ulsph_projectile"), result, fig)


def components(x, reach):
    """Labels of the connected components of the graph joining particles
    closer than `reach` (chunked brute-force distances, min-label propagation)."""
    import numpy as np
    n = len(x)
    ii, jj = [], []
    for k in range(0, n, 500):
        d2 = ((x[k:k + 500, None, :] - x[None, :, :]) ** 2).sum(axis=2)
        a, b = np.nonzero(d2 < reach * reach)
        ii.append(a + k)
        jj.append(b)
    i, j = np.concatenate(ii), np.concatenate(jj)
    label = np.arange(n)
    while True:
        new = label.copy()
        np.minimum.at(new, i, label[j])
        if np.array_equal(new, label):
            return label
        label = new


def centre_cut_out(x, X, reach):
    """Whether the plate's centre (|X| < 1 mm) is joined to its clamped ends
    (|X| > 8 mm) by no chain of particles closer than `reach`."""
    import numpy as np
    label = components(x, reach)
    return not (set(label[np.abs(X) < 0.001]) & set(label[np.abs(X) > 0.008]))


def pin(args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    import vtu
    config = "configs/striker_pin_ulsph_3d.json"
    cases = [(0.0004, 200), (0.0004, 400), (0.0002, 400)]
    result = {"config": config, "machine": m.machine(), "groove_x": 0.003, "cases": []}
    fig, ax = plt.subplots(1, len(cases), figsize=(5.5 * len(cases), 4))
    for a, (dp, v0) in zip(ax, cases):
        out = os.path.join(OUT, f"pin_dp{dp}_v{v0}")
        _, e, timing = m.run_and_read(config, {"constants.dp": dp, "constants.v0": v0}, out, args.threads, args.reuse)
        history = []
        for t, path in vtu.snapshots(out):
            d = vtu.read_vtu(path)
            plate = np.asarray(d["body"]) == 0
            x = np.asarray(d["points"])[plate]
            X = x - np.asarray(d["displacement"])[plate]
            history.append((t, centre_cut_out(x, X[:, 0], 2 * 1.3 * dp), int(np.asarray(d["failed"])[plate].sum())))
        cut = next((t for t, c, _ in history if c), None)
        case = {"dp": dp, "v0": v0, "particles": timing.get("particles"), "steps": timing.get("steps"),
                "wall_seconds": timing.get("wall_seconds"), "centre_cut_out": [[t, c] for t, c, _ in history],
                "failed_plate_particles": history[-1][2], "cut_out_by": cut}
        result["cases"].append(case)
        print(f"dp = {dp * 1e3:g} mm, v0 = {v0} m/s: failed {history[-1][2]}, "
              f"{'centre cut out by %.0f us' % (1e6 * cut) if cut is not None else 'centre not cut out'}")
        x = np.asarray(d["points"])  # d: the last snapshot, read in the loop above
        sel = np.abs(x[:, 1]) < dp
        particle_panel(a, x[sel, 0], x[sel, 2], np.asarray(d["failed"])[sel], "coolwarm", 1.5, ("x [mm]", "z [mm]"),
                       f"dp = {dp * 1e3:g} mm, v0 = {v0} m/s, t = {1e6 * history[-1][0]:.0f} us (red: failed)")
    fig.suptitle("striker pin fuse (seed 002 section 5.9), mid-plane particles")
    fig.tight_layout()
    m.write_study(os.path.join(DOCS, "ulsph_pin"), result, fig)


def punch(args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scene = "tests/regression/scenes/punched_block_2d.json"
    ulsph = {"solver.method": "ulsph", "solver.hourglass": "gnog", "bodies.block.material.model": "linear_elastic"}
    variants = [("shipped", {}), ("dp / 2", {"constants.dp": 0.00025}), ("vp 0.035", {"constants.vp": 0.035}),
                ("vp 0.03", {"constants.vp": 0.03})]
    result = {"scene": scene, "machine": m.machine(), "cases": []}
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for k, (name, sets) in enumerate(variants):
        force = {}
        for method, extra in (("tlsph", {}), ("ulsph", ulsph)):
            out = os.path.join(OUT, f"punch_{method}_{name.replace(' ', '').replace('/', 'over')}")
            m.run_and_read(scene, {**sets, **extra, "output.interval": 0.001}, out, args.threads, args.reuse)
            forces = m.read_csv(os.path.join(out, "boundary_forces.csv"))
            force[method] = forces["punch.y"][-1]
        case = {"case": name, "sets": sets, "tlsph": force["tlsph"], "ulsph": force["ulsph"],
                "ratio": force["ulsph"] / force["tlsph"]}
        result["cases"].append(case)
        print(f"{name}: punch force TLSPH {force['tlsph']:.1f} N/m, ULSPH {force['ulsph']:.1f} N/m, "
              f"ratio {case['ratio']:.3f}")
        ax.bar([2 * k, 2 * k + 0.8], [-force["tlsph"], -force["ulsph"]], color=["C0", "C1"])
    ax.set_xticks([2 * k + 0.4 for k in range(len(variants))])
    ax.set_xticklabels([v[0] for v in variants])
    ax.set_ylabel("punch force at 0.04 s [N/m] (TLSPH blue, ULSPH orange)")
    fig.tight_layout()
    m.write_study(os.path.join(DOCS, "ulsph_punch"), result, fig)


def rings(args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    # eta: the low-dissipation limiter of seed 002's ref. [38] (solver.ulsph.riemann_limiter; 0: none, as shipped).
    rings2, balls3 = ("rings 2-D", "configs/colliding_rings_ulsph_2d.json"), ("balls 3-D", "configs/colliding_balls_ulsph_3d.json")
    cases = [(*rings2, dp, (65.88, 56.74), 0) for dp in (0.002, 0.001, 0.0005)]
    cases += [(*balls3, dp, (8.27, 8.16), 0) for dp in (0.003, 0.002)]
    cases += [(*rings2, dp, (65.88, 56.74), 3) for dp in (0.002, 0.001, 0.0005)]
    cases += [(*balls3, dp, (8.27, 8.16), 3) for dp in (0.003, 0.002)]
    result = {"configs": sorted({c[1] for c in cases}), "machine": m.machine(), "cases": []}
    fig, ax = plt.subplots(1, 2, figsize=(13, 4.5))
    for (name, config, dp, seed, eta), a in [(c, ax[0] if c[0].startswith("rings") else ax[1]) for c in cases]:
        out = os.path.join(OUT, f"{name.split()[0]}_dp{dp}" + (f"_eta{eta}" if eta else ""))
        sets = {"constants.dp": dp, "output.vtu": "false", "output.interval": 2e-4}
        if eta:
            sets["solver.ulsph.riemann_limiter"] = eta
        _, e, timing = m.run_and_read(config, sets, out, args.threads, args.reuse)
        t, total = e["time"], e["total"]
        p0 = e["left.momentum.x"][0]
        drift = max(abs(px) + abs(py) for px, py in zip(e["momentum.x"], e["momentum.y"])) / p0
        case = {"case": name, "dp": dp, "riemann_limiter": eta, "particles": timing.get("particles"), "total_start": total[0],
                "total_end": total[-1], "loss": 1 - total[-1] / total[0], "seed_loss": 1 - seed[1] / seed[0],
                "least_total": min(total) / total[0], "momentum_error": drift,
                "rebound": -e["left.momentum.x"][-1] / p0, "wall_seconds": timing.get("wall_seconds")}
        result["cases"].append(case)
        print(f"{name} dp={dp} eta={eta}: total {total[0]:.3f} -> {total[-1]:.3f} ({-100 * case['loss']:+.1f} %, seed "
              f"{-100 * case['seed_loss']:+.1f} %), rebound {case['rebound']:.3f}, momentum error {drift:.1e}")
        label = f"total, dp = {dp * 1e3:g} mm" + (f", limiter eta = {eta}" if eta else "")
        line, = a.plot(t, [x / total[0] for x in total], label=label, lw=1.6 if eta else 1.0)
        if not eta:  # the limited runs: the total only, to keep the plot readable
            a.plot(t, [x / total[0] for x in e["kinetic"]], "--", color=line.get_color(), lw=0.8)
            a.plot(t, [x / total[0] for x in e["strain"]], ":", color=line.get_color(), lw=0.8)
    for a, (name, seed) in zip(ax, [("rings 2-D", (65.88, 56.74)), ("balls 3-D", (8.27, 8.16))]):
        a.axhline(seed[1] / seed[0], color="k", lw=0.8, label=f"seed 002 end of run ({seed[0]} -> {seed[1]})")
        a.set_title(f"{name}: total (solid), kinetic (dashed), stored (dotted)")
        a.set_xlabel("t [s]")
        a.set_ylabel("energy / initial total")
        a.legend(fontsize=8)
    fig.tight_layout()
    m.write_study(os.path.join(DOCS, "ulsph_rings"), result, fig)


if __name__ == "__main__":
    study = sys.argv.pop(1) if len(sys.argv) > 1 and not sys.argv[1].startswith("-") else ""
    args = m.study_arguments(__doc__, res_help="H/dp of the plate (default 10 20)")
    {"plate": plate, "spinning": spinning, "rings": rings, "long": long_plate, "column": column,
     "projectile": projectile, "pin": pin, "punch": punch}.get(study, lambda a: sys.exit(__doc__))(args)
