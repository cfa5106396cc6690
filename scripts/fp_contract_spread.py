#!/usr/bin/env python3
"""How far apart do two correct builds of the same code drift? Runs every case
of the cross-backend tests (tests/gpu/test_cross_backend.cpp: the same
configs, --set overrides, precision and 300 steps) with two CPU builds that
differ only in floating-point contraction, build-cpu (MFSD_FP_CONTRACT=ON,
g++ -ffp-contract=fast with FMA from -march=native) and build-nofma
(MFSD_FP_CONTRACT=OFF), and reports per case the largest relative difference
of the quantities the cross-backend tests compare: the final probe
displacement and velocity, the probe trajectories (every step), the final
displacement and velocity fields (every particle; the velocity also after 30
steps), the energies (kinetic,
strain, dissipation, work, balance; every 30 steps) and, for the oscillating
plate, its period (a separate, longer run to the tip's second zero crossing).
The cross-backend tolerances are max(10 x this spread, a floor)
(docs/floating-point.md).

  python3 scripts/fp_contract_spread.py [--jobs-build 2] [--only CASE]
  python3 scripts/fp_contract_spread.py --growth taylor_bar_3d_round

--growth prints how one case's field velocity spread grows over the steps,
where it is largest and whether a particle yielded in one build only.

Writes docs/validation/fp_contract_spread.json and .md and prints the C++
tolerance table of tests/gpu/test_cross_backend.cpp. Configures and builds
build-nofma when missing (Ninja, -DMFSD_CUDA=OFF -DMFSD_FP_CONTRACT=OFF);
build-cpu must be configured (MFSD_FP_CONTRACT=ON, the default); both are
brought up to date (target mfsd_lib). Runs one case at a time on one thread
(OMP_NUM_THREADS=1: no thread-count effect on the order of sums).

The runs go through a small driver compiled here against each build's
libmfsd_lib.a and calling the solver as the test does (load_scene_file,
generate_particles, make_solver, step), because the CLI's CSV outputs keep 10
significant digits, too few for differences that start at 1e-16."""
import argparse
import json
import math
import os
import shlex
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, ".."))
BUILDS = {"contracted": "build-cpu", "uncontracted": "build-nofma"}
STEPS = 300
ENERGY_EVERY = 30
EARLY_STEPS = 30  # the fields are compared after this many steps too (before late divergence grows)

# (test, label, config, overrides, precision): the cross-backend tests' cases.
# The label names a case in the outputs and in the tests' worst_difference_
# properties: the config's stem, with the variant where a test runs several.
CASES = [
    ("OscillatingPlateDouble", "oscillating_plate_2d-none", "oscillating_plate_2d.json", ["solver.hourglass=none"],
     "double"),
    ("OscillatingPlateDouble", "oscillating_plate_2d-laplacian", "oscillating_plate_2d.json",
     ["solver.hourglass=laplacian"], "double"),
    ("OscillatingPlateDouble", "oscillating_plate_2d-genog", "oscillating_plate_2d.json", ["solver.hourglass=genog"],
     "double"),
    ("TwistingColumnDouble", "twisting_column_3d", "twisting_column_3d.json", ["constants.H_over_dp=4"], "double"),
    ("BendingColumnFloat", "bending_column_3d", "bending_column_3d.json", ["constants.H_over_dp=4"], "float"),
    ("ConditionsAndLoadsDouble", "cantilever_beam_2d", "cantilever_beam_2d.json", ["constants.dp=0.002"], "double"),
    ("ConditionsAndLoadsDouble", "cantilever_large_deformation_3d", "cantilever_large_deformation_3d.json",
     ["constants.dp=0.002", "constants.Tmax=0.0005"], "double"),
    ("TaylorBarsDouble", "taylor_bar_2d", "taylor_bar_2d.json", ["constants.H_over_dp=10"], "double"),
    ("TaylorBarsDouble", "taylor_bar_3d_round", "taylor_bar_3d_round.json", ["constants.R_over_dp=4"], "double"),
    ("ContactAndMandelReturnDouble", "flyer_plate_2d", "flyer_plate_2d.json", ["constants.L_over_dp=20"], "double"),
    ("ContactAndMandelReturnDouble", "oobleck_octopus_2d", "oobleck_octopus_2d.json", ["constants.dp=0.01"],
     "double"),
    ("ContactAndMandelReturnDouble", "taylor_bar_seed001_3d", "taylor_bar_seed001_3d.json", ["constants.R_over_dp=4"],
     "double"),
    ("RelaxationDouble", "necking_bar_2d", "necking_bar_2d.json",
     ["constants.H_over_dp=10", 'solver.relaxation={"viscosity": 1e4}'], "double"),
    ("RelaxationDouble", "twisting_column_3d-relaxation", "twisting_column_3d.json",
     ["constants.H_over_dp=4", 'solver.relaxation={"viscosity": 100}'], "double"),
    ("FractureDouble", "crack_branching_2d", "crack_branching_2d.json", ["constants.dp=0.5e-3"], "double"),
    ("UlsphDouble", "oscillating_plate_ulsph_2d", "oscillating_plate_ulsph_2d.json", [], "double"),
    ("UlsphDouble", "spinning_plate_ulsph_2d", "spinning_plate_ulsph_2d.json", ["solver.ulsph.time_stepping=dual"],
     "double"),
    ("UlsphFloat", "oscillating_plate_ulsph_2d-float", "oscillating_plate_ulsph_2d.json", [], "float"),
]
# The plate's period: its default (genog) run to the tip's second zero crossing.
PERIOD_CASE = ("OscillatingPlatePeriodDouble", "oscillating_plate_2d-period", "oscillating_plate_2d.json", [],
               "double")
PERIOD_MAX_STEPS = 30000

# Tolerance = max(SAFETY x measured spread, floor), rounded up to 1, 2 or 5 x
# 10^k. The floor in double is the tightest tolerance the H200 passed before
# this measurement (the plate and the twisting column, 1e-9): the GPU's other
# round-off sources (CUB's reduction order, the scalar genog loop in 3-D) are
# not in the contraction spread; in float, 1e-5 (about 100 x float's epsilon).
SAFETY = 10.0
FLOOR = {"double": 1e-9, "float": 1e-5}
# The compared quantities, in the order of struct Tolerances in the test;
# final_phase_field is absolute (s in [0, 1]), the others relative.
QUANTITIES = ["final_displacement", "final_velocity", "final_phase_field", "final_time", "trajectory_displacement",
              "trajectory_velocity", "field_displacement", "field_velocity", "early_field_velocity", "energy_kinetic",
              "energy_strain", "energy_dissipation", "energy_work", "energy_balance"]

DRIVER = r"""
// Generated by scripts/fp_contract_spread.py: runs one scene as
// tests/gpu/test_cross_backend.cpp does (probes after every step, energies at
// the start, every E steps and at the end) and writes them at full precision
// (OUT.json) with the fields after EARLY steps (OUT.early) and at the end
// (OUT.fields).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <string>
#include <vector>

#include "host/scene/particle_generator.hpp"
#include "host/scene/scene_reader.hpp"
#include "host/solver/solver.hpp"

using namespace mfsd;

// The fields sorted by particle id: n, then displacement, velocity and
// position (3 n doubles each) and the plastic strain (n; 0 without a J2 body).
bool write_fields(Solver& solver, const std::string& path) {
  const Snapshot snap = solver.snapshot();
  std::vector<size_t> order(snap.n);
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return snap.id[a] < snap.id[b]; });
  std::vector<double> fields;
  fields.push_back(double(snap.n));
  for (const std::vector<double>* v : {&snap.displacement, &snap.velocity, &snap.position})
    for (size_t i : order)
      for (int a = 0; a < 3; ++a) fields.push_back((*v)[3 * i + a]);
  const std::vector<double>* plastic = snap.field("plastic_strain");
  for (size_t i : order) fields.push_back(plastic ? (*plastic)[i] : 0.0);
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  std::fwrite(fields.data(), sizeof(double), fields.size(), f);
  return std::fclose(f) == 0;
}

int main(int argc, char** argv) {
  if (argc < 8) {
    std::fprintf(stderr, "usage: driver CONFIG float|double STEPS ENERGY_EVERY CROSSINGS EARLY OUT [SET...]\n");
    return 2;
  }
  const std::string config = argv[1];
  const Precision precision =
      std::string(argv[2]) == "float" ? Precision::single_precision : Precision::double_precision;
  const long steps = std::atol(argv[3]);
  const long energy_every = std::atol(argv[4]);  // 0: no energies
  const int crossings = std::atoi(argv[5]);      // > 0: stop after this many sign changes of probe 0's u_y
  const long early = std::atol(argv[6]);         // > 0: the fields after this many steps too
  const std::string out = argv[7];
  const std::vector<std::string> sets(argv + 8, argv + argc);
  const SceneDocument doc = load_scene_file(config, sets);
  const InitialParticles particles = generate_particles(doc.scene);
  SolverOptions o;
  o.backend = "cpu";
  o.threads = 1;
  o.precision = precision;
  auto solver = make_solver(doc.scene, particles, o);
  solver->initialize();
  std::string probe_rows, energy_rows;
  char buf[128];
  auto num = [&](std::string& to, double v) {
    std::snprintf(buf, sizeof buf, "%s%.17g", to.empty() || to.back() == '[' ? "" : ",", v);
    to += buf;
  };
  double last_uy = 0;
  int changes = 0;
  auto probes = [&] {
    probe_rows += probe_rows.empty() ? "[" : ",\n[";
    num(probe_rows, solver->time());
    const std::vector<ProbeSample> p = solver->probes();
    for (const ProbeSample& q : p) {
      for (int a = 0; a < 3; ++a) num(probe_rows, q.displacement[a]);
      for (int a = 0; a < 3; ++a) num(probe_rows, q.velocity[a]);
      num(probe_rows, q.phase_field);
    }
    probe_rows += "]";
    if (crossings > 0 && !p.empty()) {
      const double uy = p[0].displacement[1];
      if (last_uy != 0 && uy != 0 && (uy > 0) != (last_uy > 0)) ++changes;
      if (uy != 0) last_uy = uy;
    }
  };
  auto energies = [&] {
    const EnergySample e = solver->energies();
    BodyEnergy s;
    for (const BodyEnergy& b : e.bodies) {
      s.plastic += b.plastic;
      s.fracture += b.fracture;
      s.damping += b.damping;
      s.relaxation += b.relaxation;
      s.external_work += b.external_work;
      s.boundary_work += b.boundary_work;
      s.contact_work += b.contact_work;
      s.gravity_work += b.gravity_work;
    }
    s.kinetic = e.kinetic;
    s.strain = e.strain;
    energy_rows += energy_rows.empty() ? "[" : ",\n[";
    for (double v : {solver->time(), s.kinetic, s.strain, s.plastic + s.fracture + s.damping + s.relaxation,
                     s.external_work + s.boundary_work + s.contact_work + s.gravity_work, s.balance()})
      num(energy_rows, v);
    energy_rows += "]";
  };
  probes();
  if (energy_every > 0) energies();
  long s = 0;
  while (s < steps && !(crossings > 0 && changes >= crossings)) {
    solver->step();
    ++s;
    probes();
    if (energy_every > 0 && (s % energy_every == 0 || s == steps)) energies();
    if (s == early && !write_fields(*solver, out + ".early")) return 1;
  }
  FILE* f = std::fopen((out + ".json").c_str(), "w");
  if (!f) return 1;
  std::fprintf(f, "{\"steps\": %ld, \"probes\": [%s],\n\"energies\": [%s]}\n", s, probe_rows.c_str(),
               energy_rows.c_str());
  std::fclose(f);
  return write_fields(*solver, out + ".fields") ? 0 : 1;
}
"""


def sh(cmd, **kw):
    print("+", " ".join(shlex.quote(c) for c in cmd), flush=True)
    return subprocess.run(cmd, check=True, **kw)


def ensure_builds(jobs):
    """Configures build-nofma when missing; brings both libraries up to date."""
    nofma = os.path.join(ROOT, BUILDS["uncontracted"])
    if not os.path.exists(os.path.join(nofma, "CMakeCache.txt")):
        sh(["cmake", "-S", ROOT, "-B", nofma, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release", "-DMFSD_CUDA=OFF",
            "-DMFSD_FP_CONTRACT=OFF", "-DMFSD_TESTS=OFF", "-DMFSD_BENCH=OFF", "-DMFSD_NATIVE=ON"])
    for kind, build in BUILDS.items():
        path = os.path.join(ROOT, build)
        if not os.path.exists(os.path.join(path, "CMakeCache.txt")):
            sys.exit(f"{build} is not configured (scripts/common.sh, or cmake -S . -B {build} -DMFSD_CUDA=OFF)")
        sh(["cmake", "-S", ROOT, "-B", path], stdout=subprocess.DEVNULL)
        sh(["cmake", "--build", path, "--target", "mfsd_lib", "-j", str(jobs)], stdout=subprocess.DEVNULL)
        flags = compile_flags(path)
        want = "-ffp-contract=fast" if kind == "contracted" else "-ffp-contract=off"
        if want not in flags:
            sys.exit(f"{build} is not built with {want} (MFSD_FP_CONTRACT); its flags: {' '.join(flags)}")


def compile_flags(build):
    """The compile command of the build's host/cli/main.cpp, less -o/-c."""
    with open(os.path.join(build, "compile_commands.json")) as f:
        for e in json.load(f):
            if e["file"].endswith("host/cli/main.cpp"):
                words = shlex.split(e["command"])
                out, skip = [], False
                for w in words[1:]:
                    if skip:
                        skip = False
                    elif w in ("-o", "-c"):
                        skip = True
                    else:
                        out.append(w)
                return out
    sys.exit(f"{build}/compile_commands.json has no host/cli/main.cpp")


def build_driver(build):
    path = os.path.join(ROOT, build)
    src = os.path.join(path, "fp_contract_driver.cpp")
    exe = os.path.join(path, "fp_contract_driver")
    with open(src, "w") as f:
        f.write(DRIVER)
    sh(["c++"] + compile_flags(path) + ["-o", exe, src, os.path.join(path, "libmfsd_lib.a"), "-fopenmp", "-lpthread"])
    return exe


def read_fields(path):
    fields = np.fromfile(path, dtype=np.float64)
    n = int(fields[0])
    return {"displacement": fields[1:1 + 3 * n].reshape(n, 3), "velocity": fields[1 + 3 * n:1 + 6 * n].reshape(n, 3),
            "position": fields[1 + 6 * n:1 + 9 * n].reshape(n, 3), "plastic_strain": fields[1 + 9 * n:1 + 10 * n]}


def run_case(driver, case, out, steps, energy_every, crossings=0, early=0):
    _, _, config, sets, precision = case
    env = dict(os.environ, OMP_NUM_THREADS="1")
    for suffix in (".json", ".fields", ".early"):
        if os.path.exists(out + suffix):
            os.remove(out + suffix)
    t0 = time.time()
    sh([driver, os.path.join(ROOT, "configs", config), precision, str(steps), str(energy_every), str(crossings),
        str(early), out] + sets, env=env)
    with open(out + ".json") as f:
        d = json.load(f)
    d.update(read_fields(out + ".fields"))
    if early > 0:
        d["early"] = read_fields(out + ".early")
    d["seconds"] = time.time() - t0
    return d


def rel(diff, scale):
    if diff == 0:
        return 0.0
    return diff / scale if scale > 0 else math.inf


def spreads(a, b):
    """Largest relative differences of b against a (the contracted run), as the test measures them."""
    out = {}
    pa, pb = np.array(a["probes"]), np.array(b["probes"])
    if pa.shape != pb.shape:
        raise RuntimeError(f"probe rows differ: {pa.shape} vs {pb.shape}")
    out["final_time"] = rel(abs(pa[-1, 0] - pb[-1, 0]), abs(pa[-1, 0]))
    nprobes = (pa.shape[1] - 1) // 7
    for q, cols in (("displacement", slice(0, 3)), ("velocity", slice(3, 6))):
        fin, traj = 0.0, 0.0
        for k in range(nprobes):
            xa, xb = pa[:, 1 + 7 * k:][:, cols], pb[:, 1 + 7 * k:][:, cols]
            scale = np.abs(xa).max()
            fin = max(fin, rel(np.abs(xa[-1] - xb[-1]).max(), scale))
            traj = max(traj, rel(np.abs(xa - xb).max(), scale))
        out["final_" + q] = fin
        out["trajectory_" + q] = traj
    out["final_phase_field"] = max([abs(pa[-1, 7 + 7 * k] - pb[-1, 7 + 7 * k]) for k in range(nprobes)] + [0.0])
    for q in ("displacement", "velocity"):
        fa, fb = a[q], b[q]
        if fa.shape != fb.shape:
            raise RuntimeError(f"fields differ in size: {fa.shape} vs {fb.shape}")
        out["field_" + q] = rel(np.abs(fa - fb).max(), np.abs(fa).max())
    if "early" in a:
        fa, fb = a["early"]["velocity"], b["early"]["velocity"]
        out["early_field_velocity"] = rel(np.abs(fa - fb).max(), np.abs(fa).max())
    ea, eb = np.array(a["energies"]), np.array(b["energies"])
    if ea.size:
        # E_k and E_s against their own largest value; the accumulated terms
        # (dissipation, work: near 0 in some runs) and the balance against the
        # run's energy scale, the largest E_k + E_s + |dissipation| + |work|.
        energy_scale = np.abs(ea[:, 1:5]).sum(axis=1).max()
        for j, q in enumerate(("kinetic", "strain", "dissipation", "work", "balance"), start=1):
            scale = np.abs(ea[:, j]).max() if j <= 2 else energy_scale
            out["energy_" + q] = rel(np.abs(ea[:, j] - eb[:, j]).max(), scale)
    return out


def crossing_times(rows, col):
    """Times at which column col of the probe rows changes sign (linear interpolation)."""
    t, x = rows[:, 0], rows[:, col]
    times, last = [], None
    for i in range(len(x)):
        if x[i] == 0:
            continue
        if last is not None and (x[i] > 0) != (x[last] > 0):
            times.append(t[last] + (t[i] - t[last]) * x[last] / (x[last] - x[i]))
        last = i
    return times


def period_spread(a, b):
    """The plate tip's (probe 0) zero crossings: v_y's first (a quarter period),
    u_y's first (half) and second (the period)."""
    out = {}
    pa, pb = np.array(a["probes"]), np.array(b["probes"])
    for name, col, k in (("quarter_period", 5, 0), ("half_period", 2, 0), ("period", 2, 1)):
        ta, tb = crossing_times(pa, col), crossing_times(pb, col)
        if len(ta) > k and len(tb) > k:
            out[name] = {"contracted": ta[k], "uncontracted": tb[k], "relative": abs(ta[k] - tb[k]) / ta[k]}
        else:
            out[name] = None
    out["steps"] = [a["steps"], b["steps"]]
    return out


def tolerance(spread, precision):
    t = max(SAFETY * (spread or 0.0), FLOOR[precision])
    e = math.floor(math.log10(t))
    for m in (1, 2, 5, 10):
        if m * 10.0 ** e >= t * (1 - 1e-12):
            return m * 10.0 ** e
    return t


def fmt(x):
    if x is None:
        return "n/a"
    return "0" if x == 0 else f"{x:.1e}"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--jobs-build", type=int, default=2, help="build jobs (default 2)")
    ap.add_argument("--only", help="run only the cases whose label contains this")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "fp_contract_spread"))
    ap.add_argument("--docs", default=os.path.join(ROOT, "docs", "validation", "fp_contract_spread"),
                    help="output stem (.json, .md)")
    ap.add_argument("--growth", metavar="LABEL",
                    help="only print how the field velocity spread of case LABEL grows with the steps, and where")
    args = ap.parse_args()
    ensure_builds(args.jobs_build)
    drivers = {kind: build_driver(build) for kind, build in BUILDS.items()}
    if args.growth:
        return growth(drivers, [c for c in CASES if c[1] == args.growth][0], args.out)
    os.makedirs(args.out, exist_ok=True)
    cases = [c for c in CASES if not args.only or args.only in c[1]]
    results = []
    for case in cases:
        runs = {kind: run_case(drivers[kind], case, os.path.join(args.out, case[1] + "-" + kind), STEPS,
                               ENERGY_EVERY, early=EARLY_STEPS) for kind in BUILDS}
        s = spreads(runs["contracted"], runs["uncontracted"])
        results.append({"test": case[0], "label": case[1], "config": case[2], "overrides": case[3],
                        "precision": case[4], "steps": runs["contracted"]["steps"],
                        "particles": int(runs["contracted"]["velocity"].shape[0]),
                        "seconds": round(runs["contracted"]["seconds"], 2), "spread": s,
                        "tolerance": {q: tolerance(s.get(q), case[4]) for q in QUANTITIES}})
        print(f"{case[1]}: " + ", ".join(f"{q}={fmt(v)}" for q, v in s.items()), flush=True)
    period = None
    if not args.only or args.only in PERIOD_CASE[1]:
        runs = {kind: run_case(drivers[kind], PERIOD_CASE, os.path.join(args.out, PERIOD_CASE[1] + "-" + kind),
                               PERIOD_MAX_STEPS, 0, crossings=2) for kind in BUILDS}
        period = period_spread(runs["contracted"], runs["uncontracted"])
        period.update(test=PERIOD_CASE[0], label=PERIOD_CASE[1], config=PERIOD_CASE[2], overrides=PERIOD_CASE[3],
                      precision=PERIOD_CASE[4])
        if period["period"]:
            period["tolerance"] = tolerance(period["period"]["relative"], "double")
        print(f"period: {period}", flush=True)
    write_outputs(args, results, period)


def growth(drivers, case, outdir):
    """The field velocity spread after 1 ... 300 steps, the particle where it is
    largest (reference position, plastic strain) and how many particles have
    yielded in one build only (a J2 yield branch taken differently)."""
    os.makedirs(outdir, exist_ok=True)
    rows = []
    for steps in (1, 2, 5, 10, 20, 50, 100, 150, 200, 250, 300):
        r = {kind: run_case(drivers[kind], case, os.path.join(outdir, case[1] + "-growth-" + kind), steps, 0)
             for kind in BUILDS}
        a, b = r["contracted"], r["uncontracted"]
        dv = np.abs(a["velocity"] - b["velocity"]).max(axis=1)
        i = int(dv.argmax())
        reference = np.round(a["position"][i] - a["displacement"][i], 6)
        yielded_a, yielded_b = a["plastic_strain"] > 0, b["plastic_strain"] > 0
        rows.append(f"{steps:4d} steps: field v {fmt(dv[i] / np.abs(a['velocity']).max())} at reference position "
                    f"{reference} (plastic strain {a['plastic_strain'][i]:.3g}); yielded in one build only: "
                    f"{int(np.sum(yielded_a != yielded_b))} of {int(np.sum(yielded_a))}")
    print("\n".join([f"== {case[1]}"] + rows))


def machine():
    cpu = "?"
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    cxx = subprocess.run(["c++", "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    commit = "?"
    try:
        with open(os.path.join(ROOT, BUILDS["contracted"], "generated", "host", "git_commit.hpp")) as f:
            for w in f.read().split('"'):
                if w and all(c in "0123456789abcdef-dirty" for c in w):
                    commit = w
    except OSError:
        pass
    return {"cpu": cpu, "compiler": cxx, "commit": commit}


COLUMNS = [("final_displacement", "final u"), ("final_velocity", "final v"), ("final_time", "final t"),
           ("trajectory_displacement", "traj. u"), ("trajectory_velocity", "traj. v"),
           ("field_displacement", "field u"), ("field_velocity", "field v"),
           ("early_field_velocity", "field v @30"), ("energy_kinetic", "E_k"),
           ("energy_strain", "E_s"), ("energy_dissipation", "dissip."), ("energy_work", "work"),
           ("energy_balance", "balance")]


def write_outputs(args, results, period):
    command = "python3 scripts/fp_contract_spread.py" + (f" --only {args.only}" if args.only else "")
    doc = {"command": command, "date": time.strftime("%Y-%m-%d"), "machine": machine(), "steps": STEPS,
           "energy_every": ENERGY_EVERY, "threads": 1,
           "builds": {kind: {"dir": build, "flags": [w for w in compile_flags(os.path.join(ROOT, build))
                                                     if w.startswith(("-O", "-march", "-ffp"))]}
                      for kind, build in BUILDS.items()},
           "definition": "largest |contracted - uncontracted| over the compared entries, divided by the largest "
                         "|contracted| of the same quantity (per probe, over the run; per field, over the particles; "
                         "E_k, E_s: over the run; dissipation, work and balance: divided by the run's energy scale, "
                         "the largest E_k + E_s + |dissipation| + |work|); final_phase_field absolute",
           "tolerance_rule": f"max({SAFETY:g} x spread, floor {FLOOR}), rounded up to 1, 2 or 5 x 10^k",
           "cases": results, "period": period}
    with open(args.docs + ".json", "w") as f:
        json.dump(doc, f, indent=1)
    lines = [f"# FP contraction spread ({doc['date']})", "",
             f"`{command}`: {doc['machine']['cpu']}, {doc['machine']['compiler']}, commit {doc['machine']['commit']}; "
             f"one thread, {STEPS} steps (the cross-backend tests' runs), energies every {ENERGY_EVERY} steps. "
             "Largest relative difference between the contracted (build-cpu: `" +
             " ".join(doc["builds"]["contracted"]["flags"]) + "`) and the uncontracted build (build-nofma: `" +
             " ".join(doc["builds"]["uncontracted"]["flags"]) + "`); " + doc["definition"] + ". 0: bit-identical.", "",
             "| case | prec. | particles | " + " | ".join(c[1] for c in COLUMNS) + " |",
             "|---|---|---|" + "---|" * len(COLUMNS)]
    for r in results:
        lines.append(f"| {r['label']} | {r['precision']} | {r['particles']} | " +
                     " | ".join(fmt(r["spread"].get(q)) for q, _ in COLUMNS) + " |")
    if period:
        lines += ["", f"Oscillating plate (genog, default resolution), run to the tip's second zero crossing "
                      f"({period['steps'][0]} / {period['steps'][1]} steps):", ""]
        for name in ("quarter_period", "half_period", "period"):
            p = period[name]
            lines.append(f"- {name}: " + ("not reached" if not p else
                                          f"{p['contracted']:.12g} s vs {p['uncontracted']:.12g} s, "
                                          f"relative {fmt(p['relative'])}"))
    with open(args.docs + ".md", "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n" + cpp_table(results, period, command))
    print(f"wrote {args.docs}.json and .md")


def cpp_table(results, period, command):
    """The tolerance rows of tests/gpu/test_cross_backend.cpp, each after a
    comment with the measured spreads it follows from."""
    short = {"final_displacement": "u", "final_velocity": "v", "final_phase_field": "s", "final_time": "t",
             "trajectory_displacement": "traj u", "trajectory_velocity": "traj v", "field_displacement": "field u",
             "field_velocity": "field v", "early_field_velocity": "field v@30", "energy_kinetic": "Ek",
             "energy_strain": "Es", "energy_dissipation": "diss", "energy_work": "work", "energy_balance": "bal"}
    lines = [f"    // Generated by {command}; each row: max({SAFETY:g} x measured spread, floor "
             f"{FLOOR['double']:g} double / {FLOOR['float']:g} float), rounded up to 1, 2, 5 x 10^k."]
    for r in results:
        lines.append("    // measured " + " ".join(f"{short[q]} {fmt(r['spread'].get(q))}" for q in QUANTITIES))
        lines.append(f'    {{"{r["label"]}", {{' + ", ".join(f"{r['tolerance'][q]:g}" for q in QUANTITIES) + "}},")
    if period and period.get("tolerance"):
        lines.append(f"    // period: measured {fmt(period['period']['relative'])}, tolerance {period['tolerance']:g}")
    return "\n".join(lines)


if __name__ == "__main__":
    main()
