"""Suite `throughput`: particle-steps/s, time per step, per-stage share and
peak memory per particle of the TLSPH step (genog, neo-Hookean) for the
bending column 3D (about 10k, 80k, 650k particles) and the oscillating plate
2D (three sizes), and of the ULSPH acoustic step (gnog, dual-criteria
stepping: the neighbour search once per advection step) for the oscillating
plate of seed 002 (three sizes), and the twisting column at about 51k
particles and 154 neighbours (issue 24's side-by-side case; ns per
pair-step), on 1 and all threads, in float and double; then issue 24's
targets, met or not, from the rows of the same run.
A fixed number of steps after a warm-up; the median of several repeats."""
import os

import bench_lib as b

# Issue 24's side-by-side case: about 51k particles and 154 neighbours.
TWIST_SETS = {"solver.h_over_dp": 1.66}
CASES = [  # (label, scene, H/dp)
    ("bending column 3D", b.BENDING, 12),
    ("bending column 3D", b.BENDING, 24),
    ("bending column 3D", b.BENDING, 48),
    ("twisting column 3D, h = 1.66 dp", b.TWISTING, 20),
    ("oscillating plate 2D", b.PLATE, 20),
    ("oscillating plate 2D", b.PLATE, 40),
    ("oscillating plate 2D", b.PLATE, 80),
    ("ULSPH oscillating plate 2D", b.PLATE_ULSPH, 10),
    ("ULSPH oscillating plate 2D", b.PLATE_ULSPH, 20),
    ("ULSPH oscillating plate 2D", b.PLATE_ULSPH, 40),
    ("RKPM oscillating plate 2D", b.PLATE_RKPM, 10),
    ("RKPM oscillating plate 2D", b.PLATE_RKPM, 20),
    ("RKPM oscillating plate 2D", b.PLATE_RKPM, 40),
]
QUICK = [c for c in CASES if c[2] in (12, 24, 20, 40) or c[0].startswith(("ULSPH", "RKPM"))]
# The stages whose shares the table shows, per method.
SHARES = {"tlsph": ("force", "deformation_rate", "stress"), "ulsph": ("force", "neighbors", "half_step", "stress"),
          "rkpm": ("operators", "stress", "force", "neighbors")}


def method(scene):
    return "ulsph" if scene == b.PLATE_ULSPH else "rkpm" if scene == b.PLATE_RKPM else "tlsph"


def timed_steps(particles):
    return int(min(300, max(20, 2e7 / particles)))


def main(args):
    threads = sorted({1, os.cpu_count() or 1}) if args.backend == "cpu" else [0]
    repeats = args.repeats or (1 if args.quick else 3)
    rows = []
    for label, scene, res in (QUICK if args.quick else CASES):
        if args.only and args.only not in label:
            continue
        for precision in ("double", "float"):
            for t in threads:
                # RKPM has no hourglass control (and refuses the key).
                hourglass = {"ulsph": {"solver.hourglass": "gnog"}, "rkpm": {}}.get(method(scene),
                                                                                  {"solver.hourglass": "genog"})
                sets = {"constants.H_over_dp": res, **hourglass, **b.QUIET_OUTPUT,
                        **(TWIST_SETS if scene == b.TWISTING else {})}
                out = os.path.join(b.OUT, "throughput", f"{os.path.basename(scene)[:-5]}_{res}_{precision}_{t}")
                # Size the run from a one-step probe of the particle count.
                probe, _, _ = b.run(scene, sets, out, threads=t, precision=precision, backend=args.backend,
                                    max_steps=1)
                steps = timed_steps(probe["particles"])
                (timing, info, rss), rates = b.median_run(repeats, scene, sets, out, threads=t, precision=precision,
                                                          backend=args.backend, max_steps=steps + 5, warmup=5)
                rows.append({
                    "case": label, "scene": scene, "H_over_dp": res, "precision": precision, "threads": t,
                    "particles": timing["particles"], "neighbors_per_particle": info["neighbors"]["mean"],
                    "timed_steps": timing["timed_steps"], "repeats": repeats,
                    "particle_steps_per_second": timing["particle_steps_per_second"], "all_rates": rates,
                    "microseconds_per_step": timing["microseconds_per_step"],
                    "step_microseconds": timing.get("step_microseconds"),
                    "stages": b.stage_table(timing),
                    "peak_memory_bytes_per_particle": rss / timing["particles"],
                    "model_bytes_per_particle": timing["bytes_per_particle"],
                    "setup_seconds": timing["setup_seconds"],
                    "mean_dt": timing["simulated_time"] / max(timing["steps"], 1),
                })
    md = ["| case | H/dp | particles | nbrs | precision | threads | M particle-steps/s | ns per pair-step | ms/step | "
          "stage shares | peak memory [B/particle] |", "|" + "---|" * 11]
    for r in rows:
        s = r["stages"]
        keys = SHARES[method(r["scene"])]
        share = ", ".join(f"{k} {100 * s[k]['share']:.0f} %" for k in keys if k in s)
        md.append(f"| {r['case']} | {r['H_over_dp']} | {r['particles']} | {r['neighbors_per_particle']:.1f} | "
                  f"{r['precision']} | {r['threads'] or 'gpu'} | {b.mega(r['particle_steps_per_second']):.2f} | "
                  f"{pair_ns(r):.2f} | "
                  f"{r['microseconds_per_step'] / 1e3:.2f} | {share} | {r['peak_memory_bytes_per_particle']:.0f} |")
    md += targets(rows, threads[-1])
    md += methods(rows, threads[-1])
    speedups = []
    if len(threads) > 1:
        md += ["", f"Speed-up from 1 to {threads[-1]} threads:", "",
               "| case | H/dp | precision | speed-up |", "|---|---|---|---|"]
        for r in rows:
            if r["threads"] != threads[-1]:
                continue
            one = next(x for x in rows if x["threads"] == 1 and x["scene"] == r["scene"]
                       and x["H_over_dp"] == r["H_over_dp"] and x["precision"] == r["precision"])
            sp = r["particle_steps_per_second"] / one["particle_steps_per_second"]
            speedups.append({"case": r["case"], "H_over_dp": r["H_over_dp"], "precision": r["precision"],
                             "speedup": sp})
            md.append(f"| {r['case']} | {r['H_over_dp']} | {r['precision']} | {sp:.2f} |")
    md.append("")
    stem = b.result_stem("throughput")
    plot(rows, threads, stem + ".png")
    md.append(f"![throughput]({os.path.basename(stem)}.png)\n")
    b.write_results("throughput", {"machine": args.machine, "rows": rows, "speedups": speedups},
                    "\n".join(md) + "\n", args.command)


def methods(rows, threads):
    """The three methods on the same case (the oscillating plate, issue 23
    item 7): cost per node-step, time step and wall time per simulated
    second, and RKPM's shape-function rebuild (the `operators` stage)."""
    out = ["", f"The methods on the oscillating plate 2D, double, {threads} threads (TLSPH genog, ULSPH gnog, "
           "RKPM SNNI + VC + NSNI; each scene's own resolution of dp, CFL and h):", "",
           "| method | H/dp | particles | nbrs | M node-steps/s | ns/node-step | mean dt [us] | "
           "wall s per simulated s | RKPM shape-function rebuild |", "|" + "---|" * 9]
    for res in (10, 20, 40):
        for r in rows:
            if "oscillating plate" not in r["case"] or r["H_over_dp"] != res or r["precision"] != "double" \
                    or r["threads"] != threads:
                continue
            share = r["stages"].get("operators", {}).get("share")
            dt = r.get("mean_dt", 0)
            wall = r["microseconds_per_step"] * 1e-6 / dt if dt else float("nan")
            out.append(f"| {method(r['scene'])} | {res} | {r['particles']} | {r['neighbors_per_particle']:.1f} | "
                       f"{b.mega(r['particle_steps_per_second']):.2f} | {1e9 / r['particle_steps_per_second']:.0f} | "
                       f"{1e6 * dt:.2f} | {wall:.1f} | {'' if share is None else f'{100 * share:.0f} %'} |")
    return out


def pair_ns(r):
    return 1e9 / r["particle_steps_per_second"] / r["neighbors_per_particle"]


# Issue 24's targets (benchmarks, not tests), checked on the rows of this run.
TARGETS = [  # (what, case label, H/dp, precision, value, bound, "min" | "max")
    ("bending column 84,672 particles, genog, double, M particle-steps/s", "bending column 3D", 24, "double",
     lambda r: b.mega(r["particle_steps_per_second"]), 4.0, "min"),
    ("bending column 84,672 particles, genog, float, M particle-steps/s", "bending column 3D", 24, "float",
     lambda r: b.mega(r["particle_steps_per_second"]), 6.0, "min"),
    ("twisting column about 51k particles, about 154 neighbours, double, ns per pair-step",
     "twisting column 3D, h = 1.66 dp", 20, "double", pair_ns, 3.5, "max"),
]


def targets(rows, threads):
    out = ["", f"Targets (issue 24), at {threads} threads:", "", "| target | measured | bound | met |",
           "|---|---|---|---|"]
    for what, label, res, precision, value, bound, kind in TARGETS:
        r = next((x for x in rows if x["case"] == label and x["H_over_dp"] == res and x["precision"] == precision
                  and x["threads"] == threads), None)
        if r is None:
            continue
        v = value(r)
        met = v >= bound if kind == "min" else v <= bound
        out.append(f"| {what} | {v:.2f} | {'>=' if kind == 'min' else '<='} {bound} | {'yes' if met else 'no'} |")
    return out


def plot(rows, threads, path):
    plt = b.plt()
    fig, axes = plt.subplots(1, 4, figsize=(21, 4))
    for ax, label in zip(axes, ("bending column 3D", "oscillating plate 2D", "ULSPH oscillating plate 2D",
                                "RKPM oscillating plate 2D")):
        sub = [r for r in rows if r["case"] == label]
        sizes = sorted({r["particles"] for r in sub})
        configs = [(p, t) for p in ("double", "float") for t in threads]
        width = 0.8 / len(configs)
        for k, (p, t) in enumerate(configs):
            ys = [next((b.mega(r["particle_steps_per_second"]) for r in sub
                        if r["particles"] == n and r["precision"] == p and r["threads"] == t), 0) for n in sizes]
            ax.bar([i + k * width for i in range(len(sizes))], ys, width,
                   label=f"{p}, {t} thread{'s' if t != 1 else ''}" if t else f"{p}, gpu")
        ax.set_xticks([i + 0.4 - width / 2 for i in range(len(sizes))])
        ax.set_xticklabels([f"{n:,}" for n in sizes])
        ax.set_xlabel("particles")
        ax.set_ylabel("million particle-steps / s")
        ax.set_title(f"{label}, {'gnog' if label.startswith('ULSPH') else 'genog'}")
        ax.grid(axis="y", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
