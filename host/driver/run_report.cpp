#include "host/driver/run_report.hpp"

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <ctime>
#include <fstream>
#include <thread>

#include "host/output/atomic_file.hpp"
#include "host/scene/body_properties.hpp"
#include "host/version.hpp"

namespace mfsd {

namespace {
std::string now_iso() {
  std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}
}  // namespace

Json machine_description() {
  Json m;
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  m["host"] = host;
  std::ifstream cpu("/proc/cpuinfo");
  std::string line, model = "unknown";
  while (std::getline(cpu, line))
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  m["cpu"] = model;
  m["hardware_threads"] = std::thread::hardware_concurrency();
  double load[3] = {0, 0, 0};
  if (getloadavg(load, 3) == 3) m["load_average"] = {load[0], load[1], load[2]};
  if (cuda_compiled()) {
    m["cuda_devices"] = cuda_device_count();
    if (cuda_device_count() > 0) m["cuda_device"] = cuda_device_name();
  }
  return m;
}

namespace {

// CPU threads: the start's count and, when the governor chose it, every count it ran with.
void put_threads(Json& j, const RunOptions& options, const RunStatus& status) {
  j["threads"] = options.solver.backend != "cpu" ? 0
                 : status.threads > 0            ? status.threads
                                      : (options.solver.threads > 0 ? options.solver.threads : omp_get_max_threads());
  if (status.governed) {
    Json changes = Json::array();
    for (const auto& [step, n] : status.thread_changes) changes.push_back(Json::array({step, n}));
    j["thread_governor"] = {{"changes", changes}};
  }
}

}  // namespace

void write_run_json(const std::string& dir, const SceneDocument& doc, const RunOptions& options,
                    const SetupReport& setup, const RunStatus& status) {
  Json j;
  j["mfsd_version"] = MFSD_VERSION;
  j["git_commit"] = MFSD_GIT_COMMIT;
  j["cuda_compiled"] = cuda_compiled();
  j["command"] = options.command_line;
  j["scene_file"] = doc.source_name;
  j["backend"] = options.solver.backend;
  put_threads(j, options, status);
  j["precision"] = to_string(options.solver.precision);
  j["dimension"] = doc.scene.dimension;
  if (doc.scene.dimension == 3 && doc.scene.solver.hourglass == HourglassControl::genog)
    j["genog_record"] = options.solver.backend == "cpu" && options.solver.packed_genog_record ? "packed" : "scalar";
  j["particles"] = setup.particles;
  Json bodies = Json::array();
  for (size_t b = 0; b < doc.scene.bodies.size(); ++b) {
    const auto& body = doc.scene.bodies[b];
    const BodyProperties p = body_properties(body, doc.scene.solver, doc.scene.dimension);
    Json e;
    e["name"] = body.name;
    e["particles"] = b < setup.body_particles.size() ? setup.body_particles[b] : 0;
    e["spacing"] = body.spacing;
    e["smoothing_length"] = p.h;
    e["sound_speed"] = p.c0;
    e["bulk_modulus"] = p.K;
    e["shear_modulus"] = p.G;
    bodies.push_back(e);
  }
  j["bodies"] = bodies;
  j["neighbors"] = {{"pairs", setup.pairs},
                    {"mean", setup.mean_neighbors},
                    {"min", setup.min_neighbors},
                    {"max", setup.max_neighbors}};
  j["regularized_correction_matrices"] = setup.regularized_corrections;
  j["pair_loop"] = setup.pair_loop;
  j["pair_layout"] = setup.pair_layout;
  if (!setup.pair_precision.empty()) j["pair_precision"] = setup.pair_precision;
  j["bytes_per_particle"] = setup.bytes_per_particle;
  j["machine"] = machine_description();
  j["status"] = status.state;
  j["steps"] = status.steps;
  j["simulated_time"] = status.simulated_time;
  if (!status.message.empty()) j["message"] = status.message;
  if (!status.restarted_from.empty())
    j["restart"] = {{"from", status.restarted_from}, {"time", status.start_time}, {"steps", status.start_steps}};
  if (status.checkpoints > 0)
    j["checkpoints"] = {{"written", status.checkpoints},
                        {"last", status.checkpoint},
                        {"bytes", status.checkpoint_bytes},
                        {"seconds", status.checkpoint_seconds}};
  j["written"] = now_iso();
  j["scene"] = doc.resolved;
  write_file_atomically(dir + "/run.json", j.dump(2) + "\n");
}

void write_timing_json(const std::string& dir, const SetupReport& setup, const StageTimers& timers,
                       const RunOptions& options, const RunStatus& status) {
  Json j;
  j["particles"] = setup.particles;
  j["steps"] = status.steps;
  j["simulated_time"] = status.simulated_time;
  j["wall_seconds"] = status.wall_seconds;
  j["setup_seconds"] = status.setup_seconds;
  j["step_seconds"] = status.step_seconds;
  j["output_seconds"] = status.output_seconds;
  // Timed steps: all but the first --warmup-steps.
  const long timed = status.steps - status.start_steps - status.warmup_steps;  // this session's
  j["warmup_steps"] = status.warmup_steps;
  j["timed_steps"] = timed;
  const double ps = double(setup.particles) * double(timed);
  j["particle_steps_per_second"] = status.step_seconds > 0 ? ps / status.step_seconds : 0.0;
  j["microseconds_per_step"] = timed > 0 ? 1e6 * status.step_seconds / double(timed) : 0.0;
  if (!status.step_times.empty()) {  // distribution of the wall time of one step
    std::vector<double> t = status.step_times;
    std::sort(t.begin(), t.end());
    auto q = [&](double f) { return 1e6 * t[size_t(f * double(t.size() - 1) + 0.5)]; };
    j["step_microseconds"] = {{"min", q(0)}, {"p10", q(0.1)}, {"median", q(0.5)}, {"p90", q(0.9)}, {"max", q(1)}};
  }
  // Host waits for the backend per timed step (host/backend/round_trips.hpp):
  // 1 on every scene (issue 20); outputs' copies are not in steps.
  j["round_trips_per_step"] = timed > 0 ? double(timers.round_trips()) / double(timed) : 0.0;
  j["bytes_per_particle"] = setup.bytes_per_particle;
  j["backend"] = options.solver.backend;
  put_threads(j, options, status);
  j["precision"] = to_string(options.solver.precision);
  Json stages = Json::array();
  const double total = timers.total();
  for (auto& st : timers.stages()) {
    Json s;
    s["name"] = st.first;
    s["seconds"] = st.second;
    s["share"] = total > 0 ? st.second / total : 0.0;
    s["microseconds_per_step"] = timed > 0 ? 1e6 * st.second / double(timed) : 0.0;
    s["nanoseconds_per_particle_step"] = ps > 0 ? 1e9 * st.second / ps : 0.0;
    stages.push_back(s);
  }
  j["stages"] = stages;
  write_file_atomically(dir + "/timing.json", j.dump(2) + "\n");
}

}  // namespace mfsd
