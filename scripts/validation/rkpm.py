#!/usr/bin/env python3
"""Semi-Lagrangian RKPM (seed 004, ../shared/reference/rkpm.md 7): the studies
behind docs/validation.md "RKPM".

  plate     oscillating plate 2-D (configs/oscillating_plate_rkpm_2d.json in
            the shared slot holder and configs/oscillating_plate_clamped_rkpm_2d.json
            clamped by singular-kernel nodes, v_f = 0.01, SNNI + VC + NSNI, a~ = 2) at H/dp = --res (default
            10 20 40) to two periods: the period against the thin-beam
            T = 0.264 s (rkpm.md 7.5: within 3 % at H/dp = 20 and 40), the
            total-energy drift; and the TLSPH plate (configs/oscillating_plate_2d.json,
            genog, the same v_f) at the same resolutions.
  taylor    copper Taylor bar 3-D (configs/taylor_bar_rkpm_3d.json) at
            R0/dp = --res (default 4; 8 is unstable): final length, mushroom radius and the
            largest plastic strain at 80 us against the published FE band
            (L_f 21.4-21.7 mm, R_f 7.0-7.2 mm, peak plastic strain 2.9-3.3),
            and the TLSPH bar of seed 001 (configs/taylor_bar_seed001_3d.json)
            at the same resolution.
  spinning  spinning plate 2-D (configs/spinning_plate_rkpm_2d.json): angular
            momentum and polar moment over 0.2 s, with and without NSNI.
  shear     Dienes' simple shear through the whole code
            (configs/simple_shear_rkpm_2d.json) to gamma = 2 pi with about
            --res (default 100 400) steps: the middle node's von Mises stress
            against the Jaumann-rate solution 2 sqrt(3) mu |sin(gamma/2)|
            (rkpm.md 7.1; Hughes-Winget integrates the Jaumann rate, so it
            oscillates) and the Green-Naghdi-rate solution (Dienes 1979;
            monotonic). A drift-kick-drift step evaluates the stress in the
            mid-step configuration: a row at time t holds gamma(t - dt/2).

Writes docs/validation/rkpm_<study>.json and .png.
Usage: scripts/validation/rkpm.py plate|taylor|spinning|shear [--res ...] [--threads N] [--reuse]
"""
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402

DOCS = os.path.join(m.ROOT, "docs", "validation")
OUT = os.path.join(m.ROOT, "out", "validation", "rkpm")
T_BEAM = 0.264  # rkpm.md 7.5: omega^2 = E H^2 k^4 / (12 rho (1 - nu^2)), kL = 1.875
FE_BAND = {"length_mm": (21.4, 21.7), "radius_mm": (7.0, 7.2), "peak_plastic_strain": (2.9, 3.3)}


def plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as pyplot
    return pyplot


def plate(args):
    res = args.res or [10, 20, 40]
    result = {"config": "configs/oscillating_plate_rkpm_2d.json", "machine": m.machine(), "T_beam": T_BEAM,
              "cases": []}
    fig, ax = plt().subplots(1, 2, figsize=(12, 4.5))
    for method, config, sets in (("rkpm", "configs/oscillating_plate_rkpm_2d.json", {}),
                                 ("rkpm_clamped", "configs/oscillating_plate_clamped_rkpm_2d.json", {}),
                                 ("tlsph genog", "configs/oscillating_plate_2d.json", {"constants.vf": 0.01})):
        periods = []
        for r in res:
            out = os.path.join(OUT, f"plate_{method.split()[0]}_H{r}")  # rkpm, rkpm_clamped, tlsph
            p = m.plate_run(config, {"constants.H_over_dp": r, "solver.end_time": 0.56, "output.vtu": "false", **sets},
                            out, args.threads, args.reuse)
            t, y, T, timing = p["t"], p["y"], p["period"], p["timing"]
            case = {"method": method, "H_over_dp": r, "period": T, "error_vs_beam": T / T_BEAM - 1,
                    "energy_range": p["energy_range"],
                    "particles": timing.get("particles"), "steps": timing.get("steps"),
                    "particle_steps_per_second": timing.get("particle_steps_per_second"),
                    "wall_seconds": timing.get("wall_seconds")}
            result["cases"].append(case)
            periods.append(T)
            print(f"{method} H/dp={r}: T={T:.4f} ({100 * case['error_vs_beam']:+.2f} % vs thin beam), energy "
                  f"{100 * case['energy_range'][0]:+.3f} .. {100 * case['energy_range'][1]:+.3f} %")
            if method == "rkpm":
                ax[0].plot(t, y, label=f"RKPM H/dp = {r}")
        ax[1].plot(res, periods, "o-", label=method)
    ax[1].axhline(T_BEAM, color="gray", lw=0.8, label="thin beam 0.264 s")
    ax[0].set_xlabel("t [s]")
    ax[0].set_ylabel("tip y [m]")
    ax[0].legend()
    ax[1].set_xscale("log")
    ax[1].set_xlabel("H/dp")
    ax[1].set_ylabel("period [s]")
    ax[1].legend()
    fig.suptitle("Oscillating plate: RKPM (SNNI + VC + NSNI) and TLSPH, v_f = 0.01")
    fig.tight_layout()
    m.write_study(os.path.join(DOCS, "rkpm_plate"), result, fig)


def bar_shape(outdir, dp):
    """Final length, mushroom radius (node centres + dp/2) and the largest plastic strain."""
    import numpy as np
    import vtu
    snaps = vtu.snapshots(outdir)
    s = vtu.read_vtu(snaps[-1][1])
    x = s["points"]
    r = np.hypot(x[:, 0], x[:, 1])
    return {"time": snaps[-1][0], "length_mm": 1e3 * (float(x[:, 2].max()) + dp / 2),
            "radius_mm": 1e3 * (float(r.max()) + dp / 2),
            "peak_plastic_strain": float(np.max(s["plastic_strain"])) if "plastic_strain" in s else float("nan")}


def taylor(args):
    res = args.res or [4]  # R0/dp = 8 is unstable in RKPM (docs/validation.md)
    result = {"config": "configs/taylor_bar_rkpm_3d.json", "machine": m.machine(), "fe_band": FE_BAND, "cases": []}
    fig, ax = plt().subplots(1, 2, figsize=(12, 4.5))
    for method, config in (("rkpm", "configs/taylor_bar_rkpm_3d.json"),
                           ("tlsph j2_mandel", "configs/taylor_bar_seed001_3d.json")):
        for r in res:
            out = os.path.join(OUT, f"taylor_{method.split()[0]}_R{r}")
            probes, energies, timing = m.run_and_read(
                config, {"constants.R_over_dp": r, "solver.end_time": 8e-5, "output.interval": 8e-5}, out,
                args.threads, args.reuse)
            shape = bar_shape(out, 0.0032 / r)
            e = energies["balance"]
            case = {"method": method, "R_over_dp": r, **shape, "energy_balance_change": e[-1] / e[0] - 1,
                    "particles": timing.get("particles"), "steps": timing.get("steps"),
                    "wall_seconds": timing.get("wall_seconds")}
            result["cases"].append(case)
            print(f"{method} R0/dp={r}: L_f = {shape['length_mm']:.2f} mm, R_f = {shape['radius_mm']:.2f} mm, "
                  f"peak eps_p = {shape['peak_plastic_strain']:.2f}, energy balance {100 * case['energy_balance_change']:+.2f} %")
            ax[0].plot(probes["time"], [1e3 * z for z in probes["top.position.z"]], label=f"{method} R0/dp = {r}")
    ax[0].axhspan(*FE_BAND["length_mm"], color="gray", alpha=0.3, label="FE band (final)")
    ax[0].set_xlabel("t [s]")
    ax[0].set_ylabel("top z [mm]")
    ax[0].legend()
    for c in result["cases"]:
        ax[1].plot(c["radius_mm"], c["length_mm"], "o" if c["method"] == "rkpm" else "s",
                   label=f"{c['method']} R0/dp = {c['R_over_dp']}")
    ax[1].add_patch(plt().Rectangle((7.0, 21.4), 0.2, 0.3, color="gray", alpha=0.4, label="FE band"))
    ax[1].set_xlabel("mushroom radius [mm]")
    ax[1].set_ylabel("final length [mm]")
    ax[1].legend(fontsize=8)
    fig.suptitle("Copper Taylor bar, 227 m/s, 80 us")
    fig.tight_layout()
    m.write_study(os.path.join(DOCS, "rkpm_taylor"), result, fig)


def spinning(args):
    import numpy as np
    import vtu
    result = {"config": "configs/spinning_plate_rkpm_2d.json", "machine": m.machine(), "cases": []}
    fig, ax = plt().subplots(1, 2, figsize=(12, 4.5))
    for integration in ("nsni", "snni"):
        out = os.path.join(OUT, f"spinning_{integration}")
        _, energies, timing = m.run_and_read("configs/spinning_plate_rkpm_2d.json",
                                             {"solver.rkpm.integration": integration}, out, args.threads, args.reuse)
        rows = []
        for t, path in vtu.snapshots(out):
            s = vtu.read_vtu(path)
            x, v = s["points"][:, :2], s["velocity"][:, :2]
            rows.append((t, float(np.sum(x[:, 0] * v[:, 1] - x[:, 1] * v[:, 0])), float(np.sum(x[:, 0] ** 2 + x[:, 1] ** 2))))
        t, L, I = zip(*rows)
        e = energies["balance"]
        case = {"integration": integration, "angular_momentum_change": L[-1] / L[0] - 1,
                "polar_moment_change": max(I) / I[0] - 1, "energy_balance_change": e[-1] / e[0] - 1}
        result["cases"].append(case)
        print(f"{integration}: L change {case['angular_momentum_change']:+.2e}, I max {100 * case['polar_moment_change']:+.2f} %, "
              f"energy {100 * case['energy_balance_change']:+.2f} %")
        ax[0].plot(t, [x / L[0] for x in L], label=integration)
        ax[1].plot(t, [x / I[0] for x in I], label=integration)
    ax[0].set_ylabel("L / L(0)")
    ax[1].set_ylabel("I / I(0)")
    for a in ax:
        a.set_xlabel("t [s]")
        a.legend()
    fig.suptitle("RKPM spinning plate, 105 rad/s")
    fig.tight_layout()
    m.write_study(os.path.join(DOCS, "rkpm_spinning"), result, fig)


def green_naghdi_von_mises(gamma, mu):
    """Simple shear under the Green-Naghdi rate (Dienes 1979): tan b = gamma/2,
    s11 = -s22 = 4 mu (cos 2b ln cos b + b sin 2b - sin^2 b),
    s12 = 2 mu cos 2b (2b - 2 tan 2b ln cos b - tan b); q = sqrt(3 (s11^2 + s12^2))."""
    import math
    b = math.atan(gamma / 2)
    s11 = 4 * mu * (math.cos(2 * b) * math.log(math.cos(b)) + b * math.sin(2 * b) - math.sin(b) ** 2)
    s12 = 2 * mu * math.cos(2 * b) * (2 * b - 2 * math.tan(2 * b) * math.log(math.cos(b)) - math.tan(b))
    return math.sqrt(3 * (s11 ** 2 + s12 ** 2))


def shear(args):
    import math
    config = "configs/simple_shear_rkpm_2d.json"
    result = {"config": config, "machine": m.machine(), "reference": "rkpm.md 7.1; Dienes, Acta Mech. 32 (1979)",
              "cases": []}
    fig, ax = plt().subplots(figsize=(7, 4.5))
    g_ref = [2 * math.pi * k / 400 for k in range(401)]
    for steps in args.res or [100, 400]:
        out = os.path.join(OUT, f"shear_{steps}")
        # dt = CFL h / c: the scene's 0.14 s takes 103 steps; scale t_end for about `steps`.
        sets = {"constants.t_end": 0.14 * steps / 103, "output.probe_interval": "t_end / 10000"}  # a row every step
        probes, _, timing = m.run_and_read(config, sets, out, args.threads,
                                           args.reuse)
        const = m.read_json(os.path.join(out, "run.json"))["scene"]["constants"]
        mu = const["E"] / (2 * (1 + const["nu"]))
        t, q = probes["time"], probes["centre.von_mises"]
        gam = [const["rate"] * 0.5 * (a + b) for a, b in zip(t, t[1:])]  # mid-step configuration
        qs = [x / mu for x in q[1:]]
        err = max(abs(x - 2 * math.sqrt(3) * abs(math.sin(g / 2))) for g, x in zip(gam, qs))
        case = {"steps": timing.get("steps"), "max_error_over_mu": err, "last_q_over_mu": qs[-1],
                "last_gamma": gam[-1],
                "largest_q_over_mu": max(qs), "gamma_of_largest_q": gam[qs.index(max(qs))]}
        result["cases"].append(case)
        print(f"{case['steps']} steps: von Mises against the Jaumann solution, largest error {err:.2e} mu; "
              f"peak {case['largest_q_over_mu']:.4f} mu at gamma {case['gamma_of_largest_q']:.3f}; "
              f"last row {case['last_q_over_mu']:.2e} mu at gamma {case['last_gamma']:.4f} (2 pi = 6.2832)")
        ax.plot(gam, qs, "o" if steps == (args.res or [100])[0] else "-", ms=3,
                label=f"mfsd RKPM, Hughes-Winget, {case['steps']} steps")
    ax.plot(g_ref, [2 * math.sqrt(3) * abs(math.sin(g / 2)) for g in g_ref], "k--", lw=1,
            label="Jaumann rate (exact): $2\\sqrt{3}\\,|\\sin(\\gamma/2)|$")
    ax.plot(g_ref, [green_naghdi_von_mises(g, 1.0) for g in g_ref], "k:", lw=1.5, label="Green-Naghdi rate (exact)")
    ax.set_xlabel("shear $\\gamma$")
    ax.set_ylabel("von Mises stress / $\\mu$")
    ax.set_title("Simple shear of a hypo-elastic block (Dienes 1979)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    m.write_study(os.path.join(DOCS, "rkpm_shear"), result, fig)


if __name__ == "__main__":
    study = sys.argv.pop(1) if len(sys.argv) > 1 and not sys.argv[1].startswith("-") else None
    args = m.study_arguments(__doc__, res_help="resolutions (H/dp or R0/dp)")
    {"plate": plate, "taylor": taylor, "spinning": spinning, "shear": shear}.get(study, lambda a: sys.exit(__doc__))(args)
