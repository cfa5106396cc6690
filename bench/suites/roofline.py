"""Suite `roofline`: a STREAM-like triad (bench/triad.cpp) measured in the
same run, and the bytes per second the force and deformation-rate stages
achieve on the bending column (about 80k particles, genog), as a fraction of
the triad bandwidth at the same thread count.

Bytes per particle-step are counted by a streaming model (docs/performance.md):
per pair the index and the reference data are read once; per particle each
field the stage reads or writes counts once (neighbours' fields come from the
cache, because the particles are reordered by cell). R = bytes per real."""
import os

import bench_lib as b


def model_bytes(stage, R, pairs_per_particle, D=3):
    """Streaming bytes per particle-step of a stage (3-D, genog, neo-Hookean,
    CPU backend: the stress stage writes the packed neighbour record of 28
    reals (columns of Q and F^-1, u) that the force stage reads)."""
    vec, mat, index, offset, record = D * R, D * D * R, 4, 8, 28 * R
    if stage == "force":  # pairs: j, grad, stretch; reads record, S, G, v; writes a, v
        return pairs_per_particle * (index + vec + R) + offset + record + mat + 2 * vec + 2 * vec
    if stage == "deformation_rate":  # pairs: j, grad; reads v G B0 F u X a, writes dF F u
        return pairs_per_particle * (index + vec) + offset + 2 * vec + 2 * mat + 2 * vec + 2 * vec + 2 * mat
    if stage == "stress":  # reads dF F u v, writes F u S record
        return 2 * mat + 2 * vec + mat + vec + mat + record
    raise ValueError(stage)


def main(args):
    repeats = args.repeats or (1 if args.quick else 3)
    cores = os.cpu_count() or 1
    threads = sorted({1, cores})
    # The triad is measured before and after the stage runs; the fractions use
    # the higher of the two medians (this shared machine's bandwidth drifts).
    before = {t: b.triad(t) for t in threads}
    compute = b.fma_peak()
    rows = []
    for precision, R in (("double", 8), ("float", 4)):
        for t in threads:
            out = os.path.join(b.OUT, "roofline", f"{precision}_{t}")
            (timing, info, _), _ = b.median_run(repeats, b.BENDING, {"constants.H_over_dp": 24,
                                                                     "solver.hourglass": "genog", **b.QUIET_OUTPUT},
                                                out, threads=t, precision=precision, max_steps=65, warmup=5)
            nbrs = info["neighbors"]["mean"]
            for stage in ("force", "deformation_rate", "stress"):
                ns = next(s["nanoseconds_per_particle_step"] for s in timing["stages"] if s["name"] == stage)
                by = model_bytes(stage, R, nbrs)
                gbs = by / ns  # bytes per ns = GB/s
                rows.append({"precision": precision, "threads": t, "stage": stage, "particles": timing["particles"],
                             "neighbors_per_particle": nbrs, "bytes_per_particle_step": by,
                             "ns_per_particle_step": ns, "achieved_gb_per_s": gbs})
            total = sum(model_bytes(s, R, nbrs) for s in ("force", "deformation_rate", "stress"))
            rows.append({"precision": precision, "threads": t, "stage": "step", "particles": timing["particles"],
                         "neighbors_per_particle": nbrs, "bytes_per_particle_step": total,
                         "ns_per_particle_step": 1e9 / timing["particle_steps_per_second"],
                         "achieved_gb_per_s": total * timing["particle_steps_per_second"] * 1e-9})
    after = {t: b.triad(t) for t in threads}
    triads = {t: {"before": before[t], "after": after[t],
                  "median_gb_per_s": max(before[t]["median_gb_per_s"], after[t]["median_gb_per_s"])}
              for t in threads}
    for r in rows:
        bw = triads[r["threads"]]["median_gb_per_s"]
        r["triad_gb_per_s"] = bw
        r["fraction_of_triad"] = r["achieved_gb_per_s"] / bw
        r["bandwidth_bound_particle_steps_per_second"] = bw * 1e9 / r["bytes_per_particle_step"]
        if compute and r["stage"] in ("force", "deformation_rate"):  # core time per pair, in cycles
            r["core_cycles_per_pair"] = (r["ns_per_particle_step"] * r["threads"] * compute["clock_ghz"] /
                                         r["neighbors_per_particle"])
    md = ["Triad (median of 20, before / after the stage runs; fractions use the higher): " +
          ", ".join(f"{t} thread{'s' if t > 1 else ''} {before[t]['median_gb_per_s']:.1f} / "
                    f"{after[t]['median_gb_per_s']:.1f} GB/s" for t in threads), "",
          "| precision | threads | stage | bytes/particle-step | ns/particle-step | GB/s | fraction of triad | "
          "bandwidth bound [M particle-steps/s] | core cycles per pair |", "|" + "---|" * 9]
    md += [f"| {r['precision']} | {r['threads']} | {r['stage']} | {r['bytes_per_particle_step']:.0f} | "
           f"{r['ns_per_particle_step']:.1f} | {r['achieved_gb_per_s']:.1f} | {100 * r['fraction_of_triad']:.0f} % | "
           f"{b.mega(r['bandwidth_bound_particle_steps_per_second']):.1f} | "
           f"{format(r['core_cycles_per_pair'], '.1f') if 'core_cycles_per_pair' in r else ''} |" for r in rows]
    if compute:
        md = [f"Compute roof of one core (bench/fma_peak.cpp): {compute['fma4_per_second'] * 1e-9:.2f} G 4-wide "
              f"double FMA/s, clock {compute['clock_ghz']:.2f} GHz (dependent FMA chain, latency "
              f"{compute['assumed_fma_latency']} cycles assumed), {compute['fma4_per_cycle']:.2f} FMA per cycle.",
              ""] + md
    stem = b.result_stem("roofline")
    plot(rows, threads, stem + ".png")
    md += ["", f"![roofline]({os.path.basename(stem)}.png)", ""]
    b.write_results("roofline", {"machine": args.machine, "triad": triads, "compute": compute, "rows": rows}, "\n".join(md) + "\n",
                    args.command)


def plot(rows, threads, path):
    plt = b.plt()
    fig, ax = plt.subplots(figsize=(7, 4))
    labels, values = [], []
    for r in rows:
        if r["threads"] == threads[-1]:
            labels.append(f"{r['stage']}\n{r['precision']}")
            values.append(100 * r["fraction_of_triad"])
    ax.bar(range(len(values)), values, color=["C0" if "double" in l else "C1" for l in labels])
    ax.axhline(100, color="k", lw=0.8)
    ax.axhline(40, color="r", ls="--", lw=0.8, label="40 % target (force)")
    ax.set_xticks(range(len(values)))
    ax.set_xticklabels(labels, fontsize=7)
    ax.set_ylabel(f"% of triad bandwidth ({threads[-1]} threads)")
    ax.set_title("achieved streaming bandwidth per stage, bending column H/dp = 24")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)
