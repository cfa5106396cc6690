#!/usr/bin/env python3
"""The centre of the impact face of the square copper Taylor bar at 350 m/s
(seed 000 Fig. 26; docs/validation.md, "The hard case: 350 m/s"): why the
run breaks down at H/dp = 20 and not at 8 or 12.

For each resolution it reads (or makes) the run that `taylor_bars.py
square_hard` makes (genog, snapshots and energies every 2 us; a run that
stops with exit code 3, a particle leaving the scene, is analysed up to where
it stopped) and measures on the particles nearest the bar's axis:

  gap stretch   (z of the 2nd reference layer - z of the 1st) / dp, the
                axial stretch of the first layers at the axis, at every snapshot
  principal stretches of F of the first-layer axis particle at 20 and 40 us
                (F from the kernel-corrected SPH gradient of the snapshot's
                positions over the reference neighbours, as the solver does),
                and the mean |e_hat| of its pairs (seed 000 eq. 31)
  fastest particle  largest speed in the bar and the reference layer it
                belongs to, at every snapshot
  second layer  distance from the axis (in dp) and radial velocity of the
                axis particles of the second reference layer
  balance       kinetic + stored + plastic + damping - wall work, against
                the impact energy

--set key=value and --tag run a variant (e.g. --set solver.h_over_dp=1.3
--tag h13); the variant's runs are taylor_square_H<n>_v350_<hourglass>_<tag>.
Writes docs/validation/taylor_axis[_<hourglass>][_<tag>].json and .png
(<hourglass> when it is not genog).
Usage: scripts/validation/taylor_axis.py [--res 8 12 20] [--set k=v ...] [--tag T] [--threads N] [--reuse]
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import mfsd_runs as m  # noqa: E402
import vtu  # noqa: E402

DOCS = os.path.join(m.ROOT, "docs", "validation")
OUT = os.path.join(m.ROOT, "out", "validation")
H = 0.006  # bar width [m]
V0 = 350.0
INTERVAL = 2e-6  # snapshots and energies, as taylor_bars.py square_hard


def wendland_dw(r, h):
    """dW/dr of the 3-D Wendland C2 kernel (kernels/sph/wendland_c2.hpp)."""
    import numpy as np
    q = r / h
    a = 21.0 / (16.0 * np.pi * h ** 3)
    return np.where(q < 2, -5.0 * a / h * q * (1 - q / 2) ** 3, 0.0)


def deformation(X, x, i, dp, h):
    """F_i = [sum_j V0 (x_j - x_i) (x) g_ij] B0_i, B0_i = [sum_j V0 (X_j - X_i) (x) g_ij]^-1,
    g_ij = grad0 W_ij, and the reference neighbours j."""
    import numpy as np
    dX = X - X[i]
    r = np.linalg.norm(dX, axis=1)
    nb = np.where((r > 0) & (r < 2 * h))[0]
    g = (wendland_dw(r[nb], h) / r[nb])[:, None] * dX[nb] * dp ** 3
    return (x[nb] - x[i]).T @ g @ np.linalg.inv(dX[nb].T @ g), nb


def axis_state(d, dp, h):
    """Measures of one snapshot (see the module text)."""
    import numpy as np
    x = np.asarray(d["points"], dtype=float)
    X = x - np.asarray(d["displacement"], dtype=float)
    r0 = np.hypot(X[:, 0], X[:, 1])
    axis = r0 < r0.min() + 0.01 * dp
    layer = [axis & (np.abs(X[:, 2] - (k + 0.5) * dp) < 0.01 * dp) for k in range(2)]
    v = np.asarray(d["velocity"], dtype=float)
    speed = np.linalg.norm(v, axis=1)
    fast = int(np.argmax(speed))
    second = np.where(layer[1])[0]  # the axis particles of the 2nd reference layer
    radius = np.hypot(x[second, 0], x[second, 1])
    out = {"gap_stretch": float((x[layer[1], 2].mean() - x[layer[0], 2].mean()) / dp),
           "max_speed": float(speed[fast]), "fastest_reference_layer": int(round(X[fast, 2] / dp - 0.5)),
           "fastest_reference_radius_over_dp": float(r0[fast] / dp),
           "axis_plastic_strain": float(np.max(np.asarray(d["plastic_strain"])[layer[0] | layer[1]])),
           "axis_reference_radius": float(r0.min()),
           "second_layer_radius_over_dp": [float(a) for a in radius / dp],
           "second_layer_radial_velocity": [float(a) for a in (v[second, 0] * x[second, 0] + v[second, 1] *
                                                                 x[second, 1]) / np.maximum(radius, 1e-300)]}
    return out, X, x, np.where(layer[0])[0][0]


def principal(X, x, i, dp, h):
    """Principal stretches of F_i and the mean |e_hat_ij| over its pairs."""
    import numpy as np
    Fi, nb = deformation(X, x, i, dp, h)
    Fi_inv = np.linalg.inv(Fi)
    e = []
    for j in nb:
        Fj, _ = deformation(X, x, j, dp, h)
        r0 = np.linalg.norm(X[j] - X[i])
        e.append(np.linalg.norm(0.5 * (Fi_inv + np.linalg.inv(Fj)) @ ((x[j] - x[i]) / r0) - (X[j] - X[i]) / r0))
    s = np.linalg.svd(Fi, compute_uv=False)
    return {"stretch_min": float(s.min()), "stretch_max": float(s.max()), "J": float(np.prod(s)),
            "e_hat_mean": float(np.mean(e))}


def run_or_reuse(n, sets, tag, threads, reuse):
    """The run's folder and how it ended: 0 (ran to 80 us) or 3 (stopped)."""
    outdir = os.path.join(OUT, tag)
    status = os.path.join(outdir, "run.json")
    if reuse and os.path.exists(status):
        return outdir, 3 if m.read_json(status).get("status") == "failed" else 0
    rc = m.run("configs/taylor_bar_3d_square.json",
               {"constants.H_over_dp": n, "constants.v0": V0, "solver.hourglass": "genog",
                "output.interval": INTERVAL, **sets}, outdir, ["--threads", str(threads)] if threads else [])
    if rc not in (0, 3):
        sys.exit(f"[mfsd] run {outdir} failed with exit code {rc}")
    return outdir, rc


def parse_sets(items):
    """--set key=value items as {key: value text} (passed to mfsd as given)."""
    sets = {}
    for item in items or []:
        k, _, v = item.partition("=")
        sets[k] = v
    return sets


def main():
    def extra(ap):
        ap.add_argument("--set", action="append", help="a scene override of the variant, key=value")
        ap.add_argument("--tag", help="the variant's name (run folders and result files)")
    args = m.study_arguments(__doc__, res_help="H/dp values (default 8 12 20)", extra=extra)
    import numpy as np
    sets = parse_sets(args.set)
    if sets and not args.tag:
        sys.exit("[mfsd] a variant (--set) needs a --tag")
    suffix = f"_{args.tag}" if args.tag else ""
    hourglass = sets.get("solver.hourglass", "genog")
    res = {"study": "taylor_axis", "command": "scripts/validation/taylor_axis.py " + " ".join(sys.argv[1:]),
           "machine": m.machine(), "v0": V0, "variant": sets, "runs": {}}
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 4, figsize=(17, 4.2))
    for n in args.res or [8, 12, 20]:
        dp = H / n
        h_over_dp = float(sets.get("solver.h_over_dp", 1.15))
        h = h_over_dp * dp
        tag = f"taylor_square_H{n}_v350_{hourglass}{suffix}"
        outdir, rc = run_or_reuse(n, sets, tag, args.threads, args.reuse)
        e = m.read_csv(os.path.join(outdir, "energies.csv"))
        snaps = vtu.snapshots(outdir)
        hist = {"time": [], "gap_stretch": [], "max_speed": [], "fastest_reference_layer": [],
                "axis_plastic_strain": [], "second_layer_radius_over_dp": [], "second_layer_radial_velocity": []}
        at = {}
        for t, path in snaps:
            d = vtu.read_vtu(path)
            s, X, x, i = axis_state(d, dp, h)
            hist["time"].append(t)
            for k in hist:
                if k != "time":
                    hist[k].append(s[k])
            for target in (2e-5, 4e-5):
                if abs(t - target) < 0.5 * INTERVAL:
                    at[f"{1e6 * target:.0f}us"] = principal(X, x, i, dp, h)
            r_axis = s["axis_reference_radius"]
        E0 = e["balance"][0]
        r = {"dp": dp, "h_over_dp": h_over_dp, "exit_code": rc, "end_time": snaps[-1][0],
             "steps": m.read_json(os.path.join(outdir, "run.json")).get("steps"),
             "axis_reference_radius": r_axis, "history": hist, "axis_particle": at,
             "balance_over_impact_energy": {f"{1e6 * t:.0f}us": b / E0 for t, b in zip(e["time"], e["balance"])
                                            if abs(t / 1e-5 - round(t / 1e-5)) < 0.1}}
        if rc == 3:
            fast = [k for k, v in enumerate(hist["max_speed"]) if v > 2 * V0]
            r["speed_above_2v0_from"] = hist["time"][fast[0]] if fast else None
        res["runs"][f"H{n}"] = r
        a40 = at.get("40us", {})
        print(f"H/dp = {n} ({hourglass}{suffix}): exit {rc} at {1e6 * snaps[-1][0]:.0f} us; gap stretch at the axis "
              + ", ".join(f"{1e6 * t:.0f} us {g:.4f}" for t, g in zip(hist["time"], hist["gap_stretch"])
                          if abs(t / 1e-5 - round(t / 1e-5)) < 0.1)
              + (f"; at 40 us: principal stretches {a40['stretch_min']:.4f} / {a40['stretch_max']:.2f}, "
                 f"mean |e_hat| {a40['e_hat_mean']:.3f}" if a40 else "")
              + f"; largest speed at the end {hist['max_speed'][-1]:.0f} m/s (reference layer "
                f"{hist['fastest_reference_layer'][-1]})")
        label = f"H/dp = {n}" + (" (stopped)" if rc == 3 else "")
        tu = [1e6 * t for t in hist["time"]]
        ax[0].semilogy(tu, hist["gap_stretch"], label=label)
        ax[2].semilogy(tu, hist["max_speed"], label=label)
        ax[3].plot([1e6 * t for t in e["time"]], [b / E0 for b in e["balance"]], label=label)
        if a40:
            ax[1].loglog([1e3 * r_axis], [a40["stretch_min"]], "o", label=label)
    pts = [(r["axis_reference_radius"], r["axis_particle"]["40us"]["stretch_min"]) for r in res["runs"].values()
           if "40us" in r["axis_particle"]]
    if len(pts) >= 2:  # stretch ~ r0^p: the face centre's singularity
        lr, ls = np.log([p[0] for p in pts]), np.log([p[1] for p in pts])
        slope, icpt = np.polyfit(lr, ls, 1)
        res["stretch_vs_axis_radius_exponent_40us"] = float(slope)
        rr = np.exp(np.linspace(lr.min(), lr.max(), 10))
        ax[1].loglog(1e3 * rr, np.exp(icpt) * rr ** slope, "k--", lw=0.8, label=f"r0^{slope:.2f}")
        print(f"smallest principal stretch at 40 us ~ r0^{slope:.2f}")
    ax[0].set_xlabel("t [us]")
    ax[0].set_ylabel("axial stretch of the first layers at the axis")
    ax[1].set_xlabel("reference radius of the axis particles [mm]")
    ax[1].set_ylabel("smallest principal stretch at 40 us")
    ax[2].set_xlabel("t [us]")
    ax[2].set_ylabel("largest particle speed [m/s]")
    ax[3].set_xlabel("t [us]")
    ax[3].set_ylabel("energy balance / impact energy")
    ax[3].set_ylim(0.95, 1.25)
    for a in ax:
        a.legend(fontsize=7)
        a.grid(alpha=0.3, which="both")
    fig.suptitle(f"Square copper Taylor bar at 350 m/s: the centre of the impact face ({hourglass})"
                 + (f", variant {args.tag}: {sets}" if sets else ""))
    fig.tight_layout()
    os.makedirs(DOCS, exist_ok=True)
    stem = os.path.join(DOCS, "taylor_axis" + ("" if hourglass == "genog" else "_" + hourglass) + suffix)
    with open(stem + ".json", "w") as f:
        json.dump(res, f, indent=1)
    fig.savefig(stem + ".png", dpi=110)
    print(f"wrote {stem}.json, {stem}.png")


if __name__ == "__main__":
    main()
