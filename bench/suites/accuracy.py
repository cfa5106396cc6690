"""Suite `accuracy`: speed against error. For each hourglass variant,
resolution and precision (double, float, and on the CPU a double run with
float reference pair data, --pair-precision float):
  - oscillating plate 2D (nu = 0.3, v_f = 0.05, two periods): error of the
    period against seed 000 Table 1 (0.28201 s at H/dp = 40) and against the
    thin-plate theory (0.26412 s, seed 000 eq. 42);
  - bending column 3D (v0 = 10 m/s, 1 s): RMS distance of the trajectory of
    point S from the finest run (genog, double, H/dp = 12), relative to the
    largest displacement of S in that run;
against wall time per simulated second (the time-loop wall time over the
simulated time). A Pareto plot and a table."""
import os

import bench_lib as b

T_SEED, T_THEORY = 0.28201, 0.26412
VARIANTS = ["genog", "laplacian", "none"]
# (label, --precision, extra options): double, float, and a double run with
# its reference pairs' data in float (issue 24 item 4; CPU half-pair loop).
PRECISIONS = [("double", "double", ()), ("float", "float", ()),
              ("double, float pairs", "double", ("--pair-precision", "float"))]


def variants(args):
    """The hourglass variants to run (bench/run.py --only filters them)."""
    return [hg for hg in VARIANTS if not args.only or args.only in hg]


def precisions(args):
    return [p for p in PRECISIONS if args.backend == "cpu" or not p[2]]


def plate(args, threads):
    rows = []
    for res in ((10, 20) if args.quick else (10, 20, 40)):
        for hg in variants(args):
            for precision, run_precision, extra in precisions(args):
                out = os.path.join(b.OUT, "accuracy", f"plate_{hg}_{res}_{precision.replace(', ', '_').replace(' ', '_')}")
                sets = {"constants.H_over_dp": res, "solver.hourglass": hg, "solver.end_time": 0.62,
                        "output.vtu": "false", "output.interval": 1.0}
                timing, _, _ = b.run(b.PLATE, sets, out, threads=threads, precision=run_precision,
                                     backend=args.backend, extra=extra)
                p = b.m.read_csv(os.path.join(out, "probes.csv"))
                T = b.m.period(p["time"], p["tip.position.y"])
                rows.append({"case": "oscillating plate", "hourglass": hg, "H_over_dp": res, "precision": precision,
                             "particles": timing["particles"], "period": T,
                             "error_vs_seed": abs(T - T_SEED) / T_SEED, "error_vs_theory": abs(T - T_THEORY) / T_THEORY,
                             "wall_seconds_per_simulated_second": timing["step_seconds"] / timing["simulated_time"]})
    return rows


def trajectory(out):
    p = b.m.read_csv(os.path.join(out, "probes.csv"))
    return p["time"], [p[f"S.position.{c}"] for c in "xyz"]


def bending(args, threads):
    import numpy as np
    base = {"solver.end_time": 1.0, "output.vtu": "false", "output.interval": 1.0, "output.probe_interval": 0.005}
    ref_out = os.path.join(b.OUT, "accuracy", "bending_reference")
    b.run(b.BENDING, {**base, "constants.H_over_dp": 12, "solver.hourglass": "genog"}, ref_out, threads=threads,
          precision="double", backend=args.backend)
    tr, xr = trajectory(ref_out)
    xr = np.array(xr)
    scale = np.max(np.linalg.norm(xr - xr[:, :1], axis=0))
    rows = []
    for res in ((4, 6) if args.quick else (4, 6, 8)):
        for hg in variants(args):
            for precision, run_precision, extra in precisions(args):
                out = os.path.join(b.OUT, "accuracy",
                                   f"bending_{hg}_{res}_{precision.replace(', ', '_').replace(' ', '_')}")
                timing, _, _ = b.run(b.BENDING, {**base, "constants.H_over_dp": res, "solver.hourglass": hg}, out,
                                     threads=threads, precision=run_precision, backend=args.backend, extra=extra)
                t, x = trajectory(out)
                x_ref = np.array([np.interp(t, tr, xr[c]) for c in range(3)])
                err = float(np.sqrt(np.mean(np.sum((np.array(x) - x_ref) ** 2, axis=0))) / scale)
                rows.append({"case": "bending column", "hourglass": hg, "H_over_dp": res, "precision": precision,
                             "particles": timing["particles"], "trajectory_error": err,
                             "wall_seconds_per_simulated_second": timing["step_seconds"] / timing["simulated_time"]})
    return rows, float(scale)


def main(args):
    threads = os.cpu_count() or 1
    prow = plate(args, threads)
    brow, scale = bending(args, threads)
    md = ["Oscillating plate 2D (nu = 0.3, v_f = 0.05, to 0.62 s):", "",
          "| hourglass | H/dp | precision | particles | T [s] | error vs seed 000 | error vs theory | "
          "wall s per simulated s |", "|" + "---|" * 8]
    md += [f"| {r['hourglass']} | {r['H_over_dp']} | {r['precision']} | {r['particles']} | {r['period']:.5f} | "
           f"{100 * r['error_vs_seed']:.2f} % | {100 * r['error_vs_theory']:.2f} % | "
           f"{r['wall_seconds_per_simulated_second']:.1f} |" for r in prow]
    md += ["", f"Bending column 3D (v0 = 10 m/s, to 1 s), trajectory of S against genog/double/H/dp = 12 "
           f"(largest displacement {scale:.3f} m):", "",
           "| hourglass | H/dp | precision | particles | RMS trajectory error | wall s per simulated s |",
           "|" + "---|" * 6]
    md += [f"| {r['hourglass']} | {r['H_over_dp']} | {r['precision']} | {r['particles']} | "
           f"{100 * r['trajectory_error']:.2f} % | {r['wall_seconds_per_simulated_second']:.1f} |" for r in brow]
    stem = b.result_stem("accuracy")
    plot(prow, brow, stem + ".png")
    md += ["", f"![accuracy]({os.path.basename(stem)}.png)", ""]
    b.write_results("accuracy", {"machine": args.machine, "threads": threads, "plate": prow, "bending": brow,
                                 "bending_reference_scale_m": scale}, "\n".join(md) + "\n", args.command)


def pareto(points):
    """Indices of points (cost, error) not dominated by any other."""
    keep = []
    for i, (c, e) in enumerate(points):
        if not any((c2 <= c and e2 <= e) and (c2, e2) != (c, e) for c2, e2 in points):
            keep.append(i)
    return sorted(keep, key=lambda i: points[i][0])


def plot(prow, brow, path):
    plt = b.plt()
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    markers = {"genog": "o", "laplacian": "s", "none": "^"}
    for ax, rows, key, title in ((axes[0], prow, "error_vs_seed", "oscillating plate: period error vs seed 000"),
                                 (axes[1], brow, "trajectory_error", "bending column: trajectory error vs finest")):
        for hg in VARIANTS:
            for precision, fill in (("double", "full"), ("float", "none"), ("double, float pairs", "left")):
                rs = [r for r in rows if r["hourglass"] == hg and r["precision"] == precision]
                ax.loglog([r["wall_seconds_per_simulated_second"] for r in rs], [100 * max(r[key], 1e-6) for r in rs],
                          markers[hg], fillstyle=fill, color={"genog": "C0", "laplacian": "C1", "none": "C2"}[hg],
                          label=f"{hg}, {precision}")
                for r in rs:
                    ax.annotate(str(r["H_over_dp"]), (r["wall_seconds_per_simulated_second"], 100 * max(r[key], 1e-6)),
                                fontsize=6, xytext=(3, 3), textcoords="offset points")
        pts = [(r["wall_seconds_per_simulated_second"], max(r[key], 1e-6)) for r in rows]
        front = pareto(pts)
        ax.loglog([pts[i][0] for i in front], [100 * pts[i][1] for i in front], "k--", lw=0.8, label="Pareto front")
        ax.set_xlabel("wall seconds per simulated second")
        ax.set_ylabel("error [%]")
        ax.set_title(title, fontsize=9)
        ax.grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
