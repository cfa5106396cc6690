"""Suite `scenes`: the seed scenes of configs/ at the seeds' resolutions,
written with velocity conditions and loads as the seed writes them (so the
expressions' cost is included): particle-steps/s, time per step, the share of
the loads and boundary stages, set-up time and peak memory per particle, for
a fixed number of steps after a warm-up on all threads. Full runs of these
scenes are far beyond CI; this is how long they would take here."""
import os

import bench_lib as b

CASES = [  # (label, scene, overrides, simulated time of the seed's run [s])
    ("cantilever beam 2D, dx = 0.125 mm", "configs/cantilever_beam_2d.json", {"constants.dp": 0.125e-3}, 1.0),
    ("cantilever plate 3D, dx = 0.5 mm", "configs/cantilever_plate_3d.json", {}, 0.6),
    ("large-deformation cantilever 3D, dx = 1 mm", "configs/cantilever_large_deformation_3d.json", {}, 1.2),
    ("twisting column 3D (Fig. 21), dx = 1/30 m", "configs/twisting_column_seed001_3d.json", {}, 0.2),
    ("flyer plates 2D (seed 001 4.3.1), dx = 0.01 m", "configs/flyer_plate_2d.json", {}, 1.0e-3),
    ("copper Taylor bar 3D (seed 001 4.3.2), dx = 0.2 mm", "configs/taylor_bar_seed001_3d.json",
     {"constants.R_over_dp": 16}, 1.0e-4),
    ("round Taylor bar 3D (seed 000 Table 6), R/dp = 16", "configs/taylor_bar_3d_round.json",
     {"constants.R_over_dp": 16}, 8.0e-5),
]
QUICK = [CASES[2], CASES[3]]


def main(args):
    threads = (os.cpu_count() or 1) if args.backend == "cpu" else 0
    steps = 10 if args.quick else 25
    rows = []
    for label, scene, sets, sim_time in (QUICK if args.quick else CASES):
        out = os.path.join(b.OUT, "scenes", os.path.basename(scene)[:-5])
        s = {**sets, **b.QUIET_OUTPUT}
        (timing, info, rss) = b.run(scene, s, out, threads=threads, backend=args.backend, max_steps=steps + 5,
                                    warmup=5)
        st = b.stage_table(timing)
        dt = timing["simulated_time"] / timing["steps"]
        rows.append({"case": label, "scene": scene, "sets": sets, "particles": timing["particles"],
                     "threads": threads, "timed_steps": timing["timed_steps"],
                     "particle_steps_per_second": timing["particle_steps_per_second"],
                     "microseconds_per_step": timing["microseconds_per_step"],
                     "loads_and_boundary_share": sum(st[k]["share"] for k in ("loads", "boundary") if k in st),
                     "setup_seconds": timing["setup_seconds"],
                     "peak_memory_bytes_per_particle": rss / timing["particles"],
                     "time_step": dt, "seed_simulated_time": sim_time,
                     "estimated_hours_for_the_seed_run": sim_time / dt * timing["microseconds_per_step"] * 1e-6 / 3600})
    md = ["| scene | particles | M particle-steps/s | s/step | loads + boundary | set-up [s] | memory [B/particle] | "
          "seed's run: simulated s / estimated hours |", "|" + "---|" * 8]
    for r in rows:
        md.append(f"| {r['case']} | {r['particles']} | {b.mega(r['particle_steps_per_second']):.2f} | "
                  f"{r['microseconds_per_step'] / 1e6:.3f} | {100 * r['loads_and_boundary_share']:.0f} % | "
                  f"{r['setup_seconds']:.1f} | {r['peak_memory_bytes_per_particle']:.0f} | "
                  f"{r['seed_simulated_time']:g} / {r['estimated_hours_for_the_seed_run']:.1f} |")
    md.append("")
    md.append("The estimate assumes the first steps' time step for the whole run (the time step shrinks where "
              "the motion is violent).")
    b.write_results("scenes", {"machine": args.machine, "rows": rows}, "\n".join(md) + "\n", args.command)
