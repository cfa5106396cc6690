"""Suite `fracture`: the cost of phase-field fracture (seed 001 section 4.4's
performance set): the four-point-bending beam (configs/four_point_bending_3d.json,
slit at 90 degrees) with Saint Venant-Kirchhoff and neo-Hookean materials,
each without and with fracture, and J2 plasticity without fracture, all in
the standard form (hourglass none); particle-steps/s, time per step and the
time per particle-step of the stress, force and phase-field stages, and the
extra cost of fracture over the same material without it. Seed 001 measured
less than 0.25 % extra on its GPU and 9-11 % on its CPU."""
import json
import os

import bench_lib as b

SCENE = "configs/four_point_bending_3d.json"
VARIANTS = [  # (label, model, fracture kept, extra material keys)
    ("SVK", "saint_venant_kirchhoff", False, {}),
    ("NH", "neo_hookean", False, {}),
    ("fracture-SVK", "saint_venant_kirchhoff", True, {}),
    ("fracture-NH", "neo_hookean", True, {}),
    ("J2", "j2", False, {"yield_stress": 50.0e6, "hardening_modulus": 0.0}),
]


def variant_scene(label, model, fracture, extra, outdir):
    """The scene with the variant's material, written next to its run."""
    with open(os.path.join(b.ROOT, SCENE)) as f:
        doc = json.load(f)
    material = doc["bodies"][0]["material"]
    material["model"] = model
    material.update(extra)
    if not fracture:
        material.pop("fracture")
    os.makedirs(outdir, exist_ok=True)
    path = os.path.join(outdir, "scene.json")
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
    return path


def main(args):
    threads = (os.cpu_count() or 1) if args.backend == "cpu" else 0
    dp = 1.0e-3 if args.quick else 0.5e-3
    steps = 10 if args.quick else 30
    repeats = args.repeats or (1 if args.quick else 3)
    rows = []
    for label, model, fracture, extra in VARIANTS:
        out = os.path.join(b.OUT, "fracture", label)
        scene = variant_scene(label, model, fracture, extra, out + "_scene")
        sets = {"constants.dp": dp, **b.QUIET_OUTPUT}
        (timing, info, rss), rates = b.median_run(repeats, scene, sets, out, threads=threads, backend=args.backend,
                                                  max_steps=steps + 5, warmup=5)
        st = b.stage_table(timing)
        rows.append({"variant": label, "particles": timing["particles"], "threads": threads or "gpu",
                     "timed_steps": timing["timed_steps"], "repeats": repeats,
                     "particle_steps_per_second": timing["particle_steps_per_second"], "all_rates": rates,
                     "microseconds_per_step": timing["microseconds_per_step"], "stages": st})
    base = {r["variant"]: r["microseconds_per_step"] for r in rows}
    md = ["| variant | particles | M particle-steps/s | us/step | stress / force / phase field [ns per particle-step] "
          "| extra cost of fracture |", "|---|---|---|---|---|---|"]
    for r in rows:
        st = r["stages"]
        ns = " / ".join(f"{st[k]['ns_per_particle_step']:.3g}" if k in st else "-"
                        for k in ("stress", "force", "phase_field"))
        extra = ""
        if r["variant"].startswith("fracture-"):
            plain = base[r["variant"].split("-", 1)[1]]
            extra = f"{100 * (r['microseconds_per_step'] / plain - 1):+.0f} %"
            r["extra_cost_of_fracture"] = r["microseconds_per_step"] / plain - 1
        md.append(f"| {r['variant']} | {r['particles']} | {b.mega(r['particle_steps_per_second']):.2f} | "
                  f"{r['microseconds_per_step']:.0f} | {ns} | {extra} |")
    md.append("")
    b.write_results("fracture", {"machine": args.machine, "scene": SCENE, "dp": dp, "rows": rows},
                    "\n".join(md) + "\n", args.command)
