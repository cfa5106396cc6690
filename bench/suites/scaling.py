"""Suite `scaling`: CPU-thread strong scaling (bending column at about 80k
particles, 1 .. all threads) and problem-size scaling (time per step against
particles, log-log), the plots of seed 001 Fig. 40 b-c. With --backend cuda
the same cases run on the GPU (one column, no thread sweep)."""
import os

import bench_lib as b

SIZES = [6, 8, 12, 16, 24, 32, 48]
QUICK_SIZES = [6, 8, 12, 16, 24]


def steps_for(particles):
    return int(min(300, max(20, 2e7 / particles)))


def main(args):
    repeats = args.repeats or (1 if args.quick else 3)
    cores = os.cpu_count() or 1
    base = {"solver.hourglass": "genog", **b.QUIET_OUTPUT}
    strong = []
    if args.backend == "cpu":
        for precision in ("double", "float"):
            for t in range(1, cores + 1):
                out = os.path.join(b.OUT, "scaling", f"strong_{precision}_{t}")
                (timing, _, _), rates = b.median_run(repeats, b.BENDING, {**base, "constants.H_over_dp": 24}, out,
                                                     threads=t, precision=precision, max_steps=65, warmup=5)
                strong.append({"precision": precision, "threads": t, "particles": timing["particles"],
                               "microseconds_per_step": timing["microseconds_per_step"],
                               "particle_steps_per_second": timing["particle_steps_per_second"], "all_rates": rates})
        for r in strong:
            one = next(x for x in strong if x["precision"] == r["precision"] and x["threads"] == 1)
            r["speedup"] = r["particle_steps_per_second"] / one["particle_steps_per_second"]
            r["efficiency"] = r["speedup"] / r["threads"]
    size = []
    for precision in ("double", "float"):
        for res in (QUICK_SIZES if args.quick else SIZES):
            out = os.path.join(b.OUT, "scaling", f"size_{precision}_{res}")
            particles = res * res * (6 * res + 3)
            (timing, _, _), rates = b.median_run(repeats, b.BENDING, {**base, "constants.H_over_dp": res}, out,
                                                 threads=cores, precision=precision, backend=args.backend,
                                                 max_steps=steps_for(particles) + 5, warmup=5)
            size.append({"precision": precision, "H_over_dp": res, "particles": timing["particles"],
                         "microseconds_per_step": timing["microseconds_per_step"],
                         "particle_steps_per_second": timing["particle_steps_per_second"], "all_rates": rates})
    md = []
    if strong:
        md += ["Strong scaling, bending column H/dp = 24 (genog):", "",
               "| precision | threads | particles | ms/step | M particle-steps/s | speed-up | efficiency |",
               "|---|---|---|---|---|---|---|"]
        md += [f"| {r['precision']} | {r['threads']} | {r['particles']} | {r['microseconds_per_step'] / 1e3:.2f} | "
               f"{b.mega(r['particle_steps_per_second']):.2f} | {r['speedup']:.2f} | {100 * r['efficiency']:.0f} % |"
               for r in strong]
        md.append("")
    md += [f"Problem-size scaling, bending column (genog, {'GPU' if args.backend == 'cuda' else f'{cores} threads'}):",
           "", "| precision | H/dp | particles | ms/step | M particle-steps/s |", "|---|---|---|---|---|"]
    md += [f"| {r['precision']} | {r['H_over_dp']} | {r['particles']} | {r['microseconds_per_step'] / 1e3:.3f} | "
           f"{b.mega(r['particle_steps_per_second']):.2f} |" for r in size]
    stem = b.result_stem("scaling")
    plot(strong, size, cores, stem + ".png")
    md += ["", f"![scaling]({os.path.basename(stem)}.png)", ""]
    b.write_results("scaling", {"machine": args.machine, "strong": strong, "size": size}, "\n".join(md) + "\n",
                    args.command)


def plot(strong, size, cores, path):
    plt = b.plt()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    ax = axes[0]
    if strong:
        for p in ("double", "float"):
            rs = [r for r in strong if r["precision"] == p]
            ax.plot([r["threads"] for r in rs], [r["speedup"] for r in rs], "o-", label=p)
        ax.plot([1, cores], [1, cores], "k--", lw=0.8, label="ideal")
        ax.set_xlabel("threads")
        ax.set_ylabel("speed-up")
        ax.set_title("strong scaling, bending column H/dp = 24")
        ax.legend()
        ax.grid(alpha=0.3)
    else:
        ax.axis("off")
    ax = axes[1]
    for p in ("double", "float"):
        rs = [r for r in size if r["precision"] == p]
        ax.loglog([r["particles"] for r in rs], [r["microseconds_per_step"] / 1e3 for r in rs], "o-", label=p)
    if size:
        n0 = size[0]["particles"]
        t0 = size[0]["microseconds_per_step"] / 1e3
        ns = [r["particles"] for r in size]
        ax.loglog([min(ns), max(ns)], [t0 * min(ns) / n0, t0 * max(ns) / n0], "k--", lw=0.8, label="linear")
    ax.set_xlabel("particles")
    ax.set_ylabel("wall time per step [ms]")
    ax.set_title("problem-size scaling")
    ax.legend()
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
