// mfsd command-line interface:
//   mfsd run [SCENE] [-o DIR] [--backend cpu|cuda] [--threads N] [--precision float|double]
//            [--set path=value]... [--max-steps N] [--quiet] [--restart DIR] [--checkpoint-every MIN]
//   mfsd check SCENE [--set path=value]... [--recipe]
//   mfsd decompose SCENE --ranks N [--set path=value]...
//   mfsd --version | --help
// Exit codes: 0 success, 2 bad input, 3 numerical failure, 130 / 143 interrupted
// by SIGINT / SIGTERM (checkpoint written), 1 an internal error (a bug).
#include <cmath>
#include <cstdio>
#include <optional>
// --set values may hold JSON with commas: never split option values.
#define CXXOPTS_VECTOR_DELIMITER '\0'
#include <cxxopts.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "host/backend/backend_error.hpp"
#include "host/cli/check_summary.hpp"
#include "host/distributed/decomposition_summary.hpp"
#include "host/distributed/distribution.hpp"
#include "host/driver/run.hpp"
#include "host/output/checkpoint_file.hpp"
#include "host/scene/particle_generator.hpp"
#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"
#include "host/solver/step_recipes.hpp"
#include "host/version.hpp"

using namespace mfsd;

namespace {

const char* kUsage =
    "mfsd " MFSD_VERSION
    " - meshfree solid dynamics (total- and updated-Lagrangian SPH with hourglass control)\n"
    "\n"
    "usage:\n"
    "  mfsd run [SCENE.json] [options]   run a scene (without SCENE: the built-in oscillating plate)\n"
    "  mfsd check SCENE.json [--set ..] [--recipe]  validate a scene and print its resolved summary\n"
    "                                   (--recipe: the step's stages, equations and halo refreshes)\n"
    "  mfsd decompose SCENE.json --ranks N  the scene cut into N parts and each part's halo\n"
    "                          (issue 25's domain decomposition; docs/distributed.md)\n"
    "  mfsd --version                    version, build and available backends\n"
    "  mfsd --help                       this text\n"
    "\n"
    "run options:\n"
    "  -o, --output DIR        output folder (default out/<scene name>)\n"
    "  --backend cpu|cuda      execution backend (default cpu)\n"
    "  --threads N             CPU threads, fixed (default: up to all, chosen while running:\n"
    "                          fewer when the cores are shared; docs/performance.md)\n"
    "  --precision float|double  floating-point precision (default: the scene's, else double)\n"
    "  --set path=value        override a scene value, e.g. --set solver.hourglass=laplacian\n"
    "                          --set bodies.plate.material.poisson_ratio=0.4 (repeatable)\n"
    "  --max-steps N           stop after N steps\n"
    "  --warmup-steps N        leave the first N steps out of timing.json (benchmarks)\n"
    "  --genog-record packed|scalar  3-D genog on cpu: packed neighbour record (default) or the\n"
    "                          scalar path the GPU takes\n"
    "  --pair-loop full|half   cpu: each pair from both its rows (full gather, as on the GPU) or once\n"
    "                          from the row of its smaller index (half, the default on cpu)\n"
    "  --pair-layout csr|sliced  TLSPH full gather: compressed rows (default) or sliced rows, interleaved\n"
    "                          32 at a time for coalesced GPU loads (implies --pair-loop full on cpu)\n"
    "  --pair-precision float  a double run with its reference pairs' data in float (the cpu half-pair\n"
    "                          loop's list; a third less memory; docs/performance.md)\n"
    "  --checkpoint-every MIN  write a checkpoint every MIN minutes of wall time (also: output.checkpoint_interval)\n"
    "  --restart DIR           continue the run whose output (or checkpoint) folder is DIR, in that folder\n"
    "  -q, --quiet             no progress line and no summary\n"
    "\n"
    "outputs: run.json, snapshots.pvd + snapshots/*.vtu (ParaView), probes.csv, energies.csv, timing.json\n"
    "exit codes: 0 success, 2 bad input, 3 numerical failure (NaN/Inf or particle out of bounds), 4 device error,\n"
    "            130 / 143 interrupted by Ctrl-C / SIGTERM (a checkpoint is written: continue with --restart)\n";

std::string join_args(int argc, char** argv) {
  std::string s;
  for (int k = 0; k < argc; ++k) s += (k ? " " : "") + std::string(argv[k]);
  return s;
}

void print_version() {
  std::printf("mfsd %s (commit %s)\n", MFSD_VERSION, MFSD_GIT_COMMIT);
  std::printf("backends: cpu (OpenMP)%s\n", cuda_compiled() ? ", cuda" : "");
  if (cuda_compiled()) std::printf("cuda devices: %d (%s)\n", cuda_device_count(), cuda_device_name().c_str());
  std::printf("precisions: float, double; dimensions: 2, 3\n");
}

// Accepted but doubtful input (scene.warnings), on stderr.
void print_warnings(const Scene& scene) {
  for (const auto& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
}

int command_check(int argc, char** argv) {
  cxxopts::Options opts("mfsd check", "validate a scene");
  opts.add_options()("set", "override", cxxopts::value<std::vector<std::string>>())(
      "recipe", "print the method's step recipe")("scene", "scene file", cxxopts::value<std::string>());
  opts.parse_positional({"scene"});
  auto r = opts.parse(argc, argv);
  if (!r.count("scene")) throw UsageError("mfsd check: a scene file is required (mfsd check SCENE.json)");
  if (r.unmatched().size()) throw UsageError("mfsd check: unexpected argument '" + r.unmatched()[0] + "'");
  std::vector<std::string> sets;
  if (r.count("set")) sets = r["set"].as<std::vector<std::string>>();
  const SceneDocument doc = load_scene_file(r["scene"].as<std::string>(), sets);
  const InitialParticles particles = generate_particles(doc.scene);
  print_warnings(doc.scene);
  std::cout << check_summary(doc, particles);
  if (r.count("recipe")) std::cout << step_recipe_text(doc.scene, particles);
  return 0;
}

int command_decompose(int argc, char** argv) {
  cxxopts::Options opts("mfsd decompose", "decompose a scene");
  opts.add_options()("set", "override", cxxopts::value<std::vector<std::string>>())(
      "ranks", "parts", cxxopts::value<int>())("scene", "scene file", cxxopts::value<std::string>());
  opts.parse_positional({"scene"});
  auto r = opts.parse(argc, argv);
  if (!r.count("scene")) throw UsageError("mfsd decompose: a scene file is required (mfsd decompose SCENE.json)");
  if (r.unmatched().size()) throw UsageError("mfsd decompose: unexpected argument '" + r.unmatched()[0] + "'");
  const int ranks = r.count("ranks") ? r["ranks"].as<int>() : 0;
  if (ranks < 1) throw UsageError("mfsd decompose: --ranks N (N >= 1) is required");
  std::vector<std::string> sets;
  if (r.count("set")) sets = r["set"].as<std::vector<std::string>>();
  const SceneDocument doc = load_scene_file(r["scene"].as<std::string>(), sets);
  const InitialParticles particles = generate_particles(doc.scene);
  std::cout << distributed::decomposition_summary(doc, particles, ranks);
  return 0;
}

int command_run(int argc, char** argv, const std::string& command_line) {
  cxxopts::Options opts("mfsd run", "run a scene");
  opts.add_options()("o,output", "", cxxopts::value<std::string>())("backend", "", cxxopts::value<std::string>())(
      "threads", "", cxxopts::value<int>())("precision", "", cxxopts::value<std::string>())(
      "set", "", cxxopts::value<std::vector<std::string>>())("max-steps", "", cxxopts::value<long>())(
      "warmup-steps", "", cxxopts::value<long>())("q,quiet", "")("scene", "", cxxopts::value<std::string>())(
      "restart", "", cxxopts::value<std::string>())("checkpoint-every", "", cxxopts::value<double>())(
      "genog-record", "", cxxopts::value<std::string>())("pair-loop", "", cxxopts::value<std::string>())(
      "pair-layout", "", cxxopts::value<std::string>())("pair-precision", "", cxxopts::value<std::string>());
  opts.parse_positional({"scene"});
  auto r = opts.parse(argc, argv);
  if (r.unmatched().size()) throw UsageError("mfsd run: unexpected argument '" + r.unmatched()[0] + "'");
  std::vector<std::string> sets;
  if (r.count("set")) sets = r["set"].as<std::vector<std::string>>();
  const SceneDocument doc = r.count("scene") ? load_scene_file(r["scene"].as<std::string>(), sets)
                                             : load_scene_text(default_scene_text(), "<default scene>", sets);
  print_warnings(doc.scene);
  RunOptions o;
  o.command_line = command_line;
  o.solver.precision = doc.scene.solver.precision;
  if (r.count("output")) o.output_dir = r["output"].as<std::string>();
  if (r.count("backend")) o.solver.backend = r["backend"].as<std::string>();
  if (o.solver.backend != "cpu" && o.solver.backend != "cuda")
    throw UsageError("--backend " + o.solver.backend + ": expected cpu or cuda");
  if (r.count("threads")) {
    o.solver.threads = r["threads"].as<int>();
    if (o.solver.threads < 1) throw UsageError("--threads " + std::to_string(o.solver.threads) + ": expected N >= 1");
  }
  if (r.count("precision")) {
    const std::string p = r["precision"].as<std::string>();
    if (p != "float" && p != "double") throw UsageError("--precision " + p + ": expected float or double");
    o.solver.precision = p == "float" ? Precision::single_precision : Precision::double_precision;
    o.precision_given = true;
  }
  if (r.count("max-steps")) {
    o.max_steps = r["max-steps"].as<long>();
    if (o.max_steps < 1) throw UsageError("--max-steps: expected N >= 1");
  }
  if (r.count("warmup-steps")) {
    o.warmup_steps = r["warmup-steps"].as<long>();
    if (o.warmup_steps < 0) throw UsageError("--warmup-steps: expected N >= 0");
  }
  o.quiet = r.count("quiet") > 0;
  if (r.count("genog-record")) {
    const std::string g = r["genog-record"].as<std::string>();
    if (g != "packed" && g != "scalar") throw UsageError("--genog-record " + g + ": expected packed or scalar");
    o.solver.packed_genog_record = g == "packed";
  }
  if (r.count("pair-loop")) {
    const std::string l = r["pair-loop"].as<std::string>();
    if (l != "full" && l != "half") throw UsageError("--pair-loop " + l + ": expected full or half");
    o.solver.pair_loop = l == "half" ? SolverOptions::PairLoop::half : SolverOptions::PairLoop::full;
  }
  if (r.count("pair-layout")) {
    const std::string l = r["pair-layout"].as<std::string>();
    if (l != "csr" && l != "sliced") throw UsageError("--pair-layout " + l + ": expected csr or sliced");
    if (l == "sliced") {
      if (o.solver.pair_loop == SolverOptions::PairLoop::half)
        throw UsageError("--pair-layout sliced is a layout of the full gather; it cannot go with --pair-loop half");
      o.solver.pair_layout = SolverOptions::PairLayout::sliced;
      o.solver.pair_loop = SolverOptions::PairLoop::full;
    }
  }
  if (r.count("pair-precision")) {
    const std::string p = r["pair-precision"].as<std::string>();
    if (p != "float" && p != "double") throw UsageError("--pair-precision " + p + ": expected float or double");
    if (p == "double" && o.solver.precision == Precision::single_precision)
      throw UsageError("--pair-precision double: a float run keeps its pair data in float");
    if (p == "float") o.solver.pair_precision = SolverOptions::PairPrecision::single;
  }
  if (r.count("checkpoint-every")) {
    o.checkpoint_every_minutes = r["checkpoint-every"].as<double>();
    if (!(o.checkpoint_every_minutes > 0) || !std::isfinite(o.checkpoint_every_minutes))
      throw UsageError("--checkpoint-every: expected a positive number of minutes");
  }
  if (r.count("restart")) {
    o.restart = r["restart"].as<std::string>();
    if (r.count("output")) throw UsageError("--restart continues in the checkpoint's output folder; drop -o");
  }
  const RunResult result = run_scene(doc, o);
  return result.exit_code;
}

}  // namespace

int run_command(int argc, char** argv) {
  const std::string command_line = join_args(argc, argv);
  try {
    if (argc < 2) {
      std::fputs(kUsage, stdout);
      return 0;
    }
    const std::string cmd = argv[1];
    if (cmd == "--help" || cmd == "-h" || cmd == "help") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (cmd == "--version" || cmd == "version") {
      print_version();
      return 0;
    }
    if (cmd == "check") return command_check(argc - 1, argv + 1);
    if (cmd == "decompose") return command_decompose(argc - 1, argv + 1);
    if (cmd == "run") return command_run(argc - 1, argv + 1, command_line);
    throw UsageError("unknown command '" + cmd + "' (expected run, check, --version or --help)");
  } catch (const SceneError& e) {
    std::fprintf(stderr, "mfsd: error: %s\n", e.what());
    return 2;
  } catch (const CheckpointError& e) {
    std::fprintf(stderr, "mfsd: error: %s\n", e.what());
    return 2;
  } catch (const StateMismatch& e) {
    std::fprintf(stderr, "mfsd: error: the checkpoint does not fit this run: %s\n", e.what());
    return 2;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "mfsd: error: %s\nrun 'mfsd --help' for usage\n", e.what());
    return 2;
  } catch (const cxxopts::exceptions::exception& e) {
    std::fprintf(stderr, "mfsd: error: %s\nrun 'mfsd --help' for usage\n", e.what());
    return 2;
  } catch (const BackendError& e) {
    std::fprintf(stderr, "mfsd: device error: %s\n", e.what());
    return 4;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mfsd: internal error: %s\n", e.what());
    return 1;
  }
}

int main(int argc, char** argv) {
  std::optional<mfsd::MpiSession> mpi;
  try {
    mpi.emplace(argc, argv);  // MPI_Init under mpirun in an MPI build (issue 25)
  } catch (const mfsd::UsageError& e) {
    std::fprintf(stderr, "mfsd: error: %s\n", e.what());
    return 2;
  }
  const int code = run_command(argc, argv);
  // A rank that stops with an error (printed above) ends every rank, whatever collective they wait in.
  // (An interrupted run, 128 + signal, stopped on every rank at the same step: it ends normally.)
  if (code != 0 && code < 128 && mfsd::MpiSession::active()) mfsd::MpiSession::abort("", code);
  return code;
}
