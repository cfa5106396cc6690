"""Shared pieces of the fracture studies (crack_branching.py,
kalthoff_winkler.py): running a scene at a spacing on a backend, the crack
initiation time from crack_<body>.csv, the broken particles of the last
snapshot, the energy summary, and the common plot panels."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mfsd_runs as m  # noqa: E402  (installs numpy/matplotlib when missing)
import numpy as np  # noqa: E402
import vtu  # noqa: E402


def arguments(doc, default_dp, default_out):
    def extra(ap):
        ap.add_argument("--dp", type=float, nargs="*", default=default_dp, help="particle spacings [mm]")
        ap.add_argument("--backend", default="cpu", choices=["cpu", "cuda"])
        ap.add_argument("--snapshot-interval", type=float, default=10.0, help="[us]")
    args = m.study_arguments(doc, out_help=f"stem of the result files (default docs/validation/{default_out})",
                             extra=extra)
    args.stem = args.out or os.path.join(m.ROOT, "docs", "validation", default_out)
    return args


def run(scene, name, dp_mm, args, sets=None):
    """Runs scene at spacing dp_mm (unless --reuse finds it); returns its folder."""
    outdir = os.path.join(m.ROOT, "out", name, f"dp_{dp_mm:g}mm_{args.backend}")
    all_sets = {"constants.dp": dp_mm * 1e-3, "output.interval": args.snapshot_interval * 1e-6,
                "output.probe_interval": 0.2e-6, **(sets or {})}
    extra = ["--backend", args.backend] + (["--threads", str(args.threads)] if args.threads else [])
    if not (args.reuse and os.path.exists(os.path.join(outdir, "timing.json"))):
        if m.run(scene, all_sets, outdir, extra) != 0:
            sys.exit(f"[mfsd] run {outdir} failed")
    return outdir


def initiation(crack, notch_length, growth=0.5e-3):
    """First time the crack reaches `growth` beyond the notch's tip, or None."""
    t, length = np.array(crack["time"]), np.array(crack["length"])
    grown = np.nonzero(length - notch_length >= growth)[0]
    return float(t[grown[0]]) if len(grown) else None


def last_snapshot(outdir):
    """(time, reference positions X (n, 2), phase field s) of the last snapshot."""
    time, path = vtu.snapshots(outdir)[-1]
    d = vtu.read_vtu(path)
    X = np.asarray(d["points"], float)[:, :2] - np.asarray(d["displacement"], float)[:, :2]
    return time, X, np.asarray(d["phase_field"], float)


def energy_summary(energies):
    e = {k: energies[k][-1] for k in ("time", "strain", "kinetic", "crack_surface", "fracture")}
    work = energies["external_work"][-1] + energies["boundary_work"][-1]
    e["work"] = work
    e["balance_drift_over_work"] = abs(energies["balance"][-1] - energies["balance"][0]) / max(abs(work), 1e-30)
    e["momentum"] = [energies["momentum.x"][-1], energies["momentum.y"][-1]]
    return e


def run_record(outdir, args):
    timing = m.read_json(os.path.join(outdir, "timing.json"))
    return {"particles": timing["particles"], "steps": timing["steps"], "wall_seconds": timing["wall_seconds"],
            "particle_steps_per_second": timing["particle_steps_per_second"], "backend": args.backend,
            "commit": m.read_json(os.path.join(outdir, "run.json")).get("git_commit")}


def plot_energies(ax, energies, label):
    t = np.array(energies["time"]) * 1e6
    line, = ax.plot(t, energies["strain"], label=f"strain, {label}")
    ax.plot(t, energies["crack_surface"], "--", color=line.get_color(), label=f"crack surface, {label}")
    ax.set(xlabel="t [us]", ylabel="energy [J/m]")


def plot_phase_field(fig, ax, final, title):
    time, X, s = final
    step = max(1, len(s) // 200000)  # at most 200,000 points drawn
    sc = ax.scatter(X[::step, 0] * 1e3, X[::step, 1] * 1e3, c=s[::step], s=0.3, cmap="inferno", vmin=0, vmax=1,
                    linewidths=0)
    ax.set(aspect="equal", xlabel="X [mm]", ylabel="Y [mm]", title=f"s at {time * 1e6:.0f} us, {title}")
    fig.colorbar(sc, ax=ax, shrink=0.7)


def angle_of_fit(points):
    """Angle [deg] of the least-squares line through points (n, 2), from +x, in (-90, 90]."""
    if len(points) < 3:
        return None
    x, y = points[:, 0] - points[:, 0].mean(), points[:, 1] - points[:, 1].mean()
    return math.degrees(0.5 * math.atan2(2 * (x * y).sum(), (x * x).sum() - (y * y).sum()))


def study(doc, scene, name, default_dp, analyse, notch_length, energy_title, tip_label):
    """The whole study of a 2-D notched scene: runs it at each --dp, analyse(outdir, dp) ->
    (row, crack, energies, final), and writes the result file and the figure (energies,
    the crack's growth beyond the notch (notch_length(dp) [m]), the phase field of the
    two finest runs)."""
    args = arguments(doc, default_dp, name)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows, curves = [], []
    for dp_mm in args.dp:
        outdir = run(scene, name, dp_mm, args)
        row, crack, energies, final = analyse(outdir, dp_mm * 1e-3)
        row.update(run_record(outdir, args))
        rows.append(row)
        curves.append((dp_mm, crack, energies, final))
        print(row, flush=True)
    fig, ax = plt.subplots(2, 2, figsize=(12, 9))
    for dp_mm, crack, energies, _ in curves:
        plot_energies(ax[0, 0], energies, f"dp = {dp_mm:g} mm")
        on = np.array(crack["broken"]) > 0
        ax[0, 1].plot(np.array(crack["time"])[on] * 1e6,
                      (np.array(crack["length"])[on] - notch_length(dp_mm * 1e-3)) * 1e3, label=f"dp = {dp_mm:g} mm")
    ax[0, 0].set(title=energy_title)
    ax[0, 0].legend(fontsize=7)
    ax[0, 1].set(xlabel="t [us]", ylabel=tip_label, title="crack tip")
    ax[0, 1].legend(fontsize=7)
    for k, (dp_mm, _, _, final) in enumerate(curves[-2:]):
        plot_phase_field(fig, ax[1, k], final, f"dp = {dp_mm:g} mm")
    fig.tight_layout()
    m.write_study(args.stem, {"scene": scene, "machine": m.machine(), "definitions": doc.split("Definitions")[1],
                              "runs": rows}, fig)
