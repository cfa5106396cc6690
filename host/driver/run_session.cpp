#include "host/driver/run_session.hpp"

#include <omp.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <optional>

#include "host/distributed/distribution.hpp"
#include "host/driver/interrupt.hpp"
#include "host/driver/observers.hpp"
#include "host/driver/output_rows.hpp"
#include "host/driver/progress.hpp"
#include "host/driver/restart_hint.hpp"
#include "host/driver/run_checkpoint.hpp"
#include "host/driver/run_report.hpp"
#include "host/driver/thread_governor.hpp"
#include "host/output/checkpoint_file.hpp"
#include "host/output/csv_writer.hpp"
#include "host/output/pvd_index.hpp"
#include "host/output/vtu_writer.hpp"
#include "host/scene/particle_generator.hpp"
#include "host/scene/rigid_body.hpp"
#include "host/scene/scene_error.hpp"
#include "host/solver/memory_estimate.hpp"
#include "host/solver/numerical_failure.hpp"

namespace mfsd {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The rigid bodies' surface markers at time t as a snapshot (body = the
// rigid body's index, constrained = 1), with their rigid-motion velocity.
Snapshot rigid_body_snapshot(const Scene& scene, const std::vector<RigidBodyMotion>& motion,
                             const std::vector<std::vector<Point3>>& markers, double t) {
  Snapshot s;
  const double eps = 1e-7 * std::max(scene.solver.end_time, 1e-300);
  for (size_t k = 0; k < motion.size(); ++k)
    for (const Point3& X : markers[k]) {
      const Point3 x = motion[k].position(X, t), x0 = motion[k].position(X, 0.0);
      const Point3 xp = motion[k].position(X, t + eps), xm = motion[k].position(X, std::max(0.0, t - eps));
      const double span = t + eps - std::max(0.0, t - eps);
      s.id.push_back(long(s.n++));
      s.body.push_back(int(k));
      s.constrained.push_back(1);
      for (int a = 0; a < 3; ++a) {
        s.position.push_back(x[a]);
        s.displacement.push_back(x[a] - x0[a]);
        s.velocity.push_back((xp[a] - xm[a]) / span);
      }
    }
  for (const char* name : {"von_mises", "J", "hourglass", "von_mises_strain"})  // as on the bodies' particles
    s.fields.push_back({name, std::vector<double>(s.n, std::string(name) == "J" ? 1.0 : 0.0)});
  return s;
}

// The next output time after `t`: `next` itself, or the first multiple of the
// interval beyond t (in O(1), however many intervals a step spans).
double next_multiple(double next, double interval, double t) {
  if (next > t) return next;
  double n = (std::floor(t / interval) + 1.0) * interval;
  if (!(n > t)) n = t + interval;
  if (!(n > t)) n = std::nextafter(t, std::numeric_limits<double>::infinity());
  return n;
}

// Outputs of a previous run in the same folder would mix with this one's.
void remove_previous_outputs(const std::string& dir) {
  for (const char* f : {"run.json", "timing.json", "probes.csv", "observers.csv", "energies.csv", "boundary_forces.csv",
                        "snapshots.pvd", "rigid_bodies.pvd"})
    fs::remove(fs::path(dir) / f);
  fs::remove_all(fs::path(dir) / "snapshots");
  for (const char* c : {"checkpoint", "checkpoint.previous", "checkpoint.new"}) fs::remove_all(fs::path(dir) / c);
  for (auto& e : fs::directory_iterator(dir))  // the other ranks' checkpoints of a distributed run
    if (e.path().filename().string().rfind("checkpoint.rank", 0) == 0) fs::remove_all(e.path());
  for (auto& e : fs::directory_iterator(dir))
    if ((e.path().filename().string().rfind("measure_", 0) == 0 ||
         e.path().filename().string().rfind("crack_", 0) == 0) &&
        e.path().extension() == ".csv")
      fs::remove(e.path());
}

// Files a killed run was writing (written under .tmp, then renamed).
void remove_partial_files(const std::string& dir) {
  for (const fs::path& d : {fs::path(dir), fs::path(dir) / "snapshots"})
    if (fs::is_directory(d))
      for (auto& e : fs::directory_iterator(d))
        if (e.path().extension() == ".tmp") fs::remove(e.path());
}

}  // namespace

struct RunSession::Impl {
  Impl(const SceneDocument& d, const RunOptions& o) : doc(d), options(o), scene(doc.scene) {}

  SceneDocument doc;
  RunOptions options;
  const Scene& scene;
  std::unique_ptr<InterruptHandling> interrupts;  // SIGINT / SIGTERM: finish the step, checkpoint, stop
  std::unique_ptr<Distribution> dist;
  bool root = true;
  std::optional<RestartPoint> restart;
  std::optional<CheckpointContents> saved;
  std::vector<size_t> measure_sizes;  // particles of each measure plane, in the whole scene
  std::unique_ptr<Solver> solver;
  InitialParticles particles;  // what the outputs read: the rigid bodies' markers
  std::string dir, snapshot_stem;
  RunStatus status;
  SetupReport setup;
  std::vector<std::pair<std::string, CsvWriter*>> csv_files;
  std::unique_ptr<CsvWriter> probes_csv, energies_csv, forces_csv, observers_csv;
  std::unique_ptr<Observers> observers;
  std::vector<std::unique_ptr<CsvWriter>> measure_csv, crack_csv;
  std::unique_ptr<PvdIndex> pvd, rigid_pvd;
  std::vector<RigidBodyMotion> rigid;
  bool single = false;
  double end_time = 0, eps = 0;
  OutputPosition at;
  double output_seconds = 0, last_snapshot_time = -1;
  bool checkpointing = false, with_forces = false;
  Clock::time_point last_checkpoint_wall, t_loop;
  std::unique_ptr<Progress> progress;
  RunResult result;
  double step_seconds = 0;
  long session_steps = 0;
  std::optional<ThreadGovernor> governor;
  bool stop_requested = false, failed = false, finished = false;
  std::map<std::string, RunSession::Series> series;
  std::map<const CsvWriter*, std::string> series_of;
  std::optional<NumericalFailure> failure;

  // A row of a series: to its file (rank 0) and, when kept, to memory.
  void row(const std::unique_ptr<CsvWriter>& w, const std::vector<double>& values) {
    if (!w) return;
    w->row(values);
    if (options.keep_series) series[series_of[w.get()]].rows.push_back(values);
  }

  std::string rank_folder(const std::string& folder) const {
    return dist && dist->rank() > 0 ? folder + ".rank" + std::to_string(dist->rank()) : folder;
  }
  bool stop_signal() const { return dist ? dist->any(interrupt_signal() != 0) : interrupt_signal() != 0; }
  std::unique_ptr<CsvWriter> open_csv(const std::string& name, const std::vector<std::string>& columns);
  void setup_run();
  void write_outputs(bool snapshot);
  void write_checkpoint_now();
  void governed_step(double seconds);
  void fail(const NumericalFailure& f);
  bool running() const {
    return !finished && !failed && !stop_requested && solver->time() < end_time - eps && !step_limit_reached();
  }
  // --max-steps counts this session's steps: a continued run takes N more.
  bool step_limit_reached() const { return options.max_steps > 0 && session_steps >= options.max_steps; }
  bool step();
  void finish();
};

// The CSV series: new files, or for a continued run the files as they were
// at the checkpoint, appended to.
std::unique_ptr<CsvWriter> RunSession::Impl::open_csv(const std::string& name,
                                                      const std::vector<std::string>& columns) {
  std::unique_ptr<CsvWriter> w;
  if (!root) return w;  // rank 0 writes the series
  if (restart) {
    const auto it = restart->position.csv_bytes.find(name);
    if (it == restart->position.csv_bytes.end())
      throw CheckpointError("checkpoint " + restart->folder + " does not know " + name);
    try {
      w = std::make_unique<CsvWriter>(dir + "/" + name, columns, it->second);
    } catch (const std::runtime_error& e) {
      throw CheckpointError(std::string(e.what()) + " (continuing " + restart->folder + ")");
    }
  } else {
    w = std::make_unique<CsvWriter>(dir + "/" + name, columns);
  }
  csv_files.emplace_back(name, w.get());
  series_of[w.get()] = name;
  if (options.keep_series) series[name].columns = columns;
  return w;
}

void RunSession::Impl::setup_run() {
  if (options.handle_signals) interrupts = std::make_unique<InterruptHandling>();
  // Under mpirun (an MPI build): this rank's part of the run; null otherwise.
  // Rank 0 writes the CSVs, run.json and the indices; every rank its snapshot pieces.
  dist = make_distribution();
  root = !dist || dist->root();
  if (dist) dist->check(scene);
  // Each rank's checkpoint: rank 0's in the run's checkpoint folder (with the
  // outputs' positions), rank r's beside it in <folder>.rank<r>; a continued
  // run reads them on the same number of ranks (the same parts).
  // Everything that can be wrong with the input is found before the folder is
  // made or, for a continued run, touched.
  if (!options.restart.empty()) {
    restart = find_restart(options.restart, doc, options);
    const long ranks = Json::parse(read_checkpoint_meta(restart->folder)).value("ranks", 1L);
    if (ranks != (dist ? dist->ranks() : 1))
      throw CheckpointError("checkpoint " + restart->folder + " was written by " + std::to_string(ranks) +
                            " process(es); continue it on as many (this run has " +
                            std::to_string(dist ? dist->ranks() : 1) + ")");
    saved = read_checkpoint(rank_folder(restart->folder));
  }
  particles = generate_particles(scene);
  for (const auto& m : particles.measure_particles) measure_sizes.push_back(m.size());
  if (dist) particles = dist->local_particles(scene, particles);
  std::vector<long> body_particles;
  for (const auto& r : particles.body_range) body_particles.push_back(long(r.end - r.begin));
  check_run_memory(scene, body_particles, options.solver);
  solver = make_solver(scene, particles, options.solver);
  if (dist) solver = dist->distribute(std::move(solver));
  // The solver keeps its own copy: of the driver's, only what the outputs
  // read stays (the measure planes' sizes, the rigid bodies' markers), so
  // that the set-up's peak memory does not hold the particles twice.
  {
    InitialParticles kept;
    kept.rigid_markers = std::move(particles.rigid_markers);
    particles = std::move(kept);
  }

  dir = restart ? restart->output_dir : (options.output_dir.empty() ? "out/" + scene.name : options.output_dir);
  snapshot_stem = "snapshots/" + scene.name;
  if ((snapshot_stem + "_rigid_00000.vtu").size() - 10 > 255)
    throw SceneError("/name", "a name of " + std::to_string(scene.name.size()) + " characters",
                     "at most 239 characters (it names the snapshot files)");
  if (root) {
    const bool existed = fs::exists(dir);
    prepare_output_dir(dir);
    if (existed && !restart) remove_previous_outputs(dir);
    if (restart) remove_partial_files(dir);
    fs::create_directories(fs::path(dir) / "snapshots");
  }
  if (dist) dist->barrier();  // the folder is ready for every rank's pieces

  result.output_dir = dir;
  status.state = "running";
  const auto t_start = Clock::now();
  try {
    solver->initialize();
  } catch (const NumericalFailure& f) {  // e.g. an expression that fails at t = 0: exit 3 as in the loop
    // (a distributed run has ended every rank with the message already)
    failure = f;
    status.state = "failed";
    status.message = f.what();
    write_run_json(dir, doc, options, SetupReport{}, status);
    std::fprintf(stderr, "mfsd: run stopped at set-up: %s\n", f.what());
    result.exit_code = 3;
    result.message = f.what();
    failed = finished = true;
    return;
  }
  if (restart) {
    solver->restore_state(saved->archive);
    saved.reset();  // the state is in the solver now
    if (dist && dist->any(solver->steps() != restart->steps))
      throw CheckpointError("the ranks' checkpoints in " + restart->output_dir +
                            " are of different steps (a run stopped while writing them); no whole checkpoint");
    status.restarted_from = restart->folder;
    status.start_time = solver->time();
    status.start_steps = solver->steps();
    for (const auto& w : restart->warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  // The observers' fields are the solver's: checked now, before any file.
  if (!scene.observers.empty()) observers = std::make_unique<Observers>(scene, *solver);
  status.setup_seconds = seconds_since(t_start);
  setup = solver->setup_report();
  if (root) write_run_json(dir, doc, options, setup, status);

  if (!options.quiet && root) {
    std::printf("mfsd: scene '%s' (%dD), %ld particles, %.1f neighbours/particle, backend %s, %s precision\n",
                scene.name.c_str(), scene.dimension, setup.particles, setup.mean_neighbors,
                options.solver.backend.c_str(), to_string(options.solver.precision));
    if (setup.regularized_corrections > 0)
      std::printf("mfsd: %ld kernel-correction matrices were near-singular and regularized\n",
                  setup.regularized_corrections);
    if (restart)
      std::printf("mfsd: continuing from %s at t = %.9g s, step %ld\n", restart->folder.c_str(), solver->time(),
                  solver->steps());
    if (dist) std::printf("mfsd: distributed over %d processes (MPI)\n", dist->ranks());
    std::printf("mfsd: output in %s/\n", dir.c_str());
    std::fflush(stdout);
  }

  probes_csv = open_csv("probes.csv", probe_columns(scene));
  if (observers) observers_csv = open_csv("observers.csv", observers->columns());
  energies_csv = open_csv("energies.csv", energy_columns(scene));
  for (auto& mp : scene.measure_planes)
    measure_csv.push_back(open_csv("measure_" + mp.name + ".csv", measure_columns(scene)));
  for (const CrackSpec& c : crack_specs(scene))
    crack_csv.push_back(open_csv("crack_" + scene.bodies[c.body].name + ".csv", crack_columns(scene)));
  with_forces =
      !scene.clamps.empty() || !scene.conditions.empty() || !scene.walls.empty() || !scene.contact.rigid_bodies.empty();
  if (with_forces) forces_csv = open_csv("boundary_forces.csv", boundary_force_columns(scene));
  pvd = std::make_unique<PvdIndex>(root ? dir + "/snapshots.pvd" : "");
  for (size_t k = 0; k < scene.rigid_bodies.size(); ++k)
    rigid.emplace_back(scene.rigid_bodies[k], scene.constants, "/rigid_bodies/" + std::to_string(k));
  rigid_pvd = std::make_unique<PvdIndex>(root ? dir + "/rigid_bodies.pvd" : "");
  single = options.solver.precision == Precision::single_precision;
  end_time = scene.solver.end_time;
  eps = 1e-12 * end_time;
  at.next_output = scene.output.interval;
  at.next_probe = scene.output.probe_interval;
  at.next_checkpoint = scene.output.checkpoint_interval;
  if (restart) {
    at = restart->position;
    if (scene.output.vtu && root) pvd->restore(at.snapshots);
    if (scene.output.vtu && !rigid.empty() && root) rigid_pvd->restore(at.rigid_snapshots);
  }
  checkpointing = scene.output.checkpoint_interval > 0 || options.checkpoint_every_minutes > 0;
  last_checkpoint_wall = Clock::now();

  if (!restart) write_outputs(true);

  progress = std::make_unique<Progress>(end_time, !options.quiet && root, solver->time(), solver->steps());
  t_loop = Clock::now();
  // CPU runs whose thread count nobody fixed: the governor chooses it.
  if (options.solver.backend == "cpu") {
    status.threads = options.solver.threads > 0 ? options.solver.threads : omp_get_max_threads();
    if (options.solver.threads == 0 && !std::getenv("OMP_NUM_THREADS") && status.threads > 1) {
      governor.emplace(status.threads, [](int n) { omp_set_num_threads(n); });
      status.governed = true;
    }
  }
  // An interruption ends every rank of a distributed run at the same step.
  stop_requested = stop_signal();
}

void RunSession::Impl::write_outputs(bool snapshot) {
  const auto t0 = Clock::now();
  // Every rank takes part in the sums (distributed runs); rank 0 writes them.
  if (!scene.probes.empty()) {
    const auto p = solver->probes();
    if (root) row(probes_csv, probe_row(scene, solver->time(), p));
  }
  if (observers) {
    const std::vector<double> r = observers->row(*solver, solver->time());
    if (root) row(observers_csv, r);
  }
  if (with_forces) {
    const auto f = solver->boundary_forces();
    if (root) row(forces_csv, boundary_force_row(scene, solver->time(), f));
  }
  if (!crack_csv.empty()) {
    const auto tips = solver->crack_tips();
    for (size_t k = 0; k < tips.size(); ++k)
      if (root) row(crack_csv[k], crack_row(scene, solver->time(), tips[k]));
  }
  if (!measure_csv.empty()) {
    const auto m = solver->measures();
    for (size_t k = 0; k < m.size(); ++k)
      if (root) row(measure_csv[k], measure_row(scene, solver->time(), measure_sizes[k], m[k]));
  }
  if (snapshot) {
    const EnergySample e = solver->energies();
    if (root) row(energies_csv, energy_row(solver->time(), e, scene.dimension));
    if (scene.output.vtu) {
      char number[16];
      std::snprintf(number, sizeof number, "_%05d.vtu", at.snapshot_count);
      const std::string name = snapshot_stem + number;
      if (dist) {  // one piece per rank, and rank 0's index over them
        const Snapshot piece = solver->snapshot();
        const std::string stem = name.substr(0, name.size() - 4);
        auto piece_name = [&](int r) { return stem + "_r" + std::to_string(r) + ".vtu"; };
        write_vtu(dir + "/" + piece_name(dist->rank()), piece, single);
        if (root) {
          std::vector<std::string> pieces;
          for (int r = 0; r < dist->ranks(); ++r) pieces.push_back(fs::path(piece_name(r)).filename().string());
          write_pvtu(dir + "/" + stem + ".pvtu", piece, single, pieces);
          pvd->add(solver->time(), stem + ".pvtu");
        }
      } else {
        write_vtu(dir + "/" + name, solver->snapshot(), single);
        pvd->add(solver->time(), name);
      }
      if (!rigid.empty() && root) {
        const std::string rigid_name = snapshot_stem + "_rigid" + number;
        write_vtu(dir + "/" + rigid_name, rigid_body_snapshot(scene, rigid, particles.rigid_markers, solver->time()),
                  single);
        rigid_pvd->add(solver->time(), rigid_name);
      }
    }
    ++at.snapshot_count;
    last_snapshot_time = solver->time();
  }
  output_seconds += seconds_since(t0);
}

// A checkpoint of the state now and of where the outputs stand.
void RunSession::Impl::write_checkpoint_now() {
  at.snapshots = pvd->entries();
  at.rigid_snapshots = rigid_pvd->entries();
  at.csv_bytes.clear();
  for (auto& [name, w] : csv_files) at.csv_bytes[name] = w->bytes();
  StateArchive archive;
  solver->save_state(archive);
  Json meta = checkpoint_meta(doc, options, solver->time(), solver->steps(), at);
  if (dist) meta["ranks"] = dist->ranks();
  const CheckpointWriteReport r = mfsd::write_checkpoint(rank_folder(checkpoint_folder(dir)), meta.dump(), archive);
  ++status.checkpoints;
  status.checkpoint_bytes = double(r.bytes);
  status.checkpoint_seconds += r.seconds;
  status.checkpoint = checkpoint_folder(dir);
  last_checkpoint_wall = Clock::now();
}

void RunSession::Impl::governed_step(double seconds) {
  if (!governor) return;
  governor->step_done(seconds);
  if (governor->changes().size() != status.thread_changes.size()) {
    status.thread_changes.clear();
    for (const auto& c : governor->changes()) status.thread_changes.emplace_back(c.step, c.threads);
  }
}

void RunSession::Impl::fail(const NumericalFailure& f) {
  failure = f;
  progress->finish();
  status.state = "failed";
  status.message = f.what();
  result.exit_code = 3;
  result.message = f.what();
  failed = true;
  std::fprintf(stderr, "mfsd: run stopped: %s\nmfsd: the last good snapshot is kept in %s/snapshots\n", f.what(),
               dir.c_str());
}

bool RunSession::Impl::step() {
  if (!running()) return false;
  try {
    solver->limit_next_dt(end_time - solver->time());
    const auto t0 = Clock::now();
    solver->step();
    ++session_steps;
    const double seconds = seconds_since(t0);
    governed_step(seconds);
    if (session_steps > options.warmup_steps) {
      step_seconds += seconds;
      status.step_times.push_back(seconds);
    } else if (session_steps == options.warmup_steps) {
      solver->reset_timers();
    }
    const double t = solver->time();
    // Outputs at their times only (and at the end), the same whether the run
    // stops early or not: a continued run reproduces the uninterrupted one.
    const bool snap = t >= at.next_output - eps || t >= end_time - eps;
    if (snap || t >= at.next_probe - eps) write_outputs(snap);
    at.next_probe = next_multiple(at.next_probe, scene.output.probe_interval, t + eps);
    at.next_output = next_multiple(at.next_output, scene.output.interval, t + eps);
    bool checkpoint_due = (scene.output.checkpoint_interval > 0 && t >= at.next_checkpoint - eps) ||
                          (options.checkpoint_every_minutes > 0 &&
                           seconds_since(last_checkpoint_wall) >= 60.0 * options.checkpoint_every_minutes);
    if (dist && options.checkpoint_every_minutes > 0) checkpoint_due = dist->any(checkpoint_due);  // wall clocks differ
    if (scene.output.checkpoint_interval > 0)
      at.next_checkpoint = next_multiple(at.next_checkpoint, scene.output.checkpoint_interval, t + eps);
    stop_requested = stop_signal();  // one agreement per step in a distributed run
    const bool stops = t >= end_time - eps || step_limit_reached() || stop_requested;
    if (checkpoint_due && !stops) write_checkpoint_now();  // a stop writes its own in finish()
    progress->update(t, solver->steps());
  } catch (const NumericalFailure& f) {
    fail(f);
  }
  return running();
}

void RunSession::Impl::finish() {
  if (finished) return;
  finished = true;
  if (!failed) {
    try {
      progress->finish();
      const bool interrupted = stop_signal();
      // The checkpoint first: a continued run takes the CSVs and the PVD as they
      // are now, so the stop's last snapshot below is replaced by its own outputs.
      if (checkpointing || interrupted) write_checkpoint_now();
      if (last_snapshot_time != solver->time()) write_outputs(true);  // a run stopped early (--max-steps, a signal)
      if (interrupted) {
        status.state = "interrupted";
        result.exit_code = 128 + interrupt_signal();
        result.message = "interrupted";
      } else if (solver->time() < end_time - eps) {
        // Not "completed": the end time was not reached (--max-steps, or a
        // binding that finished early); run.json says where it stopped.
        status.state = "stopped";
        char why[160];
        std::snprintf(why, sizeof why, "%s at t = %.9g s of end_time %.9g s",
                      step_limit_reached() ? "stopped at the step limit (--max-steps)" : "finished before end_time",
                      solver->time(), end_time);
        status.message = why;
      } else {
        status.state = "completed";
      }
    } catch (const NumericalFailure& f) {
      fail(f);
    }
  }
  progress->finish();
  status.steps = solver->steps();
  status.warmup_steps = std::min(options.warmup_steps, session_steps);
  status.simulated_time = solver->time();
  status.step_seconds = step_seconds;
  status.output_seconds = output_seconds;
  status.wall_seconds = seconds_since(t_loop);
  if (root) {
    write_timing_json(dir, setup, solver->timers(), options, status);
    write_run_json(dir, doc, options, setup, status);
  }
  if (dist && !options.quiet) dist->print_report(session_steps - status.warmup_steps);

  result.steps = status.steps;
  result.time = status.simulated_time;
  if (status.state == "interrupted" && root)
    std::fprintf(stderr, "mfsd: interrupted at t = %.9g s, step %ld; checkpoint in %s/\nmfsd: continue with: %s%s\n",
                 solver->time(), solver->steps(), status.checkpoint.c_str(),
                 dist ? ("mpiexec -n " + std::to_string(dist->ranks()) + " ").c_str() : "",
                 restart_command(doc, options, dir).c_str());
  if (status.state == "stopped" && root && !options.quiet) std::printf("mfsd: %s\n", status.message.c_str());
  if (!options.quiet && root) {
    char wall[32];
    format_duration(status.wall_seconds, wall, sizeof wall);
    const long timed = session_steps - status.warmup_steps;
    const double ps = double(setup.particles) * double(timed);
    std::printf(
        "mfsd: %s: %ld particles, %ld steps to t = %.6g s in %s (%.3g particle-steps/s; set-up %.2fs, output %.2fs)\n",
        status.state.c_str(), setup.particles, status.steps, status.simulated_time, wall,
        step_seconds > 0 ? ps / step_seconds : 0.0, status.setup_seconds, output_seconds);
    if (status.checkpoints > 0)
      std::printf("mfsd: %ld checkpoint(s) in %s/ (%.3g MB each, %.2fs in all)\n", status.checkpoints,
                  status.checkpoint.c_str(), status.checkpoint_bytes / 1e6, status.checkpoint_seconds);
    const double total = solver->timers().total();
    std::printf("mfsd: stage               share   us/step   ns/particle-step\n");
    for (auto& st : solver->timers().stages())
      std::printf("mfsd:   %-18s %5.1f %%  %8.1f  %8.2f\n", st.first.c_str(), total > 0 ? 100 * st.second / total : 0,
                  session_steps ? 1e6 * st.second / session_steps : 0.0, ps > 0 ? 1e9 * st.second / ps : 0.0);
    std::fflush(stdout);
  }
  interrupts.reset();  // the previous signal handlers back
}

RunSession::RunSession(const SceneDocument& doc, const RunOptions& options)
    : impl_(std::make_unique<Impl>(doc, options)) {
  impl_->setup_run();
}

RunSession::~RunSession() = default;

bool RunSession::running() const { return impl_->running(); }
bool RunSession::step() { return impl_->step(); }
const RunResult& RunSession::finish() {
  impl_->finish();
  return impl_->result;
}
void RunSession::write_snapshot() {
  if (!impl_->finished) impl_->write_outputs(true);
}
std::string RunSession::write_checkpoint(const std::string& folder) {
  Impl& m = *impl_;
  if (folder.empty() || fs::weakly_canonical(folder) == fs::weakly_canonical(m.dir)) {
    m.write_checkpoint_now();
    return m.status.checkpoint;
  }
  if (m.dist) throw UsageError("a checkpoint in another folder is for single-process runs");
  prepare_output_dir(folder);
  if (!fs::is_empty(folder))
    throw SceneError("checkpoint folder '" + folder + "'", "a folder that holds files",
                     "an empty or new folder (the run's outputs so far are copied into it)");
  // The outputs so far, as the checkpoint's positions will name them.
  for (const auto& [name, writer] : m.csv_files) {
    (void)writer;
    fs::copy_file(fs::path(m.dir) / name, fs::path(folder) / name);
  }
  for (const char* index : {"snapshots.pvd", "rigid_bodies.pvd"})
    if (fs::exists(fs::path(m.dir) / index)) fs::copy_file(fs::path(m.dir) / index, fs::path(folder) / index);
  fs::copy(fs::path(m.dir) / "snapshots", fs::path(folder) / "snapshots", fs::copy_options::recursive);
  m.at.snapshots = m.pvd->entries();
  m.at.rigid_snapshots = m.rigid_pvd->entries();
  m.at.csv_bytes.clear();
  for (auto& [name, w] : m.csv_files) m.at.csv_bytes[name] = w->bytes();
  StateArchive archive;
  m.solver->save_state(archive);
  const Json meta = checkpoint_meta(m.doc, m.options, m.solver->time(), m.solver->steps(), m.at);
  mfsd::write_checkpoint(checkpoint_folder(folder), meta.dump(), archive);
  return checkpoint_folder(folder);
}
const std::map<std::string, RunSession::Series>& RunSession::series() const { return impl_->series; }
const std::optional<NumericalFailure>& RunSession::failure() const { return impl_->failure; }
Solver& RunSession::solver() { return *impl_->solver; }
const std::string& RunSession::output_dir() const { return impl_->dir; }
const SetupReport& RunSession::setup() const { return impl_->setup; }
double RunSession::end_time() const { return impl_->end_time; }

}  // namespace mfsd
