#include "host/driver/run_checkpoint.hpp"

#include <omp.h>

#include <filesystem>

#include "host/output/checkpoint_file.hpp"
#include "host/version.hpp"

namespace mfsd {

namespace fs = std::filesystem;

namespace {

constexpr int kFormat = 1;

int thread_count(const RunOptions& o) {
  return o.solver.backend == "cpu" ? (o.solver.threads > 0 ? o.solver.threads : omp_get_max_threads()) : 0;
}

// The resolved scene without the keys a continued run may change (key order
// does not matter: compared as an unordered JSON value).
nlohmann::json comparable_scene(const Json& ordered) {
  nlohmann::json scene = nlohmann::json::parse(ordered.dump());
  if (scene.contains("solver") && scene["solver"].is_object()) scene["solver"].erase("end_time");
  if (scene.contains("output") && scene["output"].is_object()) scene["output"].erase("checkpoint_interval");
  return scene;
}

std::string text(const nlohmann::json& j) {
  std::string s = j.dump();
  return s.size() > 80 ? s.substr(0, 77) + "..." : s;
}

}  // namespace

std::string checkpoint_folder(const std::string& output_dir) { return output_dir + "/checkpoint"; }

Json checkpoint_meta(const SceneDocument& doc, const RunOptions& options, double time, long steps,
                     const OutputPosition& p) {
  Json j;
  j["format"] = kFormat;
  j["mfsd_version"] = MFSD_VERSION;
  j["git_commit"] = MFSD_GIT_COMMIT;
  j["time"] = time;
  j["steps"] = steps;
  j["backend"] = options.solver.backend;
  j["precision"] = to_string(options.solver.precision);
  j["threads"] = thread_count(options);
  j["scene_file"] = doc.source_name;
  Json out;
  out["next_output"] = p.next_output;
  out["next_probe"] = p.next_probe;
  out["next_checkpoint"] = p.next_checkpoint;
  out["snapshot_count"] = p.snapshot_count;
  auto entries = [](const std::vector<PvdIndex::Entry>& e) {
    Json a = Json::array();
    for (auto& [t, file] : e) a.push_back({{"time", t}, {"file", file}});
    return a;
  };
  out["snapshots"] = entries(p.snapshots);
  out["rigid_snapshots"] = entries(p.rigid_snapshots);
  out["csv_bytes"] = p.csv_bytes;
  j["outputs"] = out;
  j["scene"] = doc.resolved;
  return j;
}

RestartPoint find_restart(const std::string& where, const SceneDocument& doc, const RunOptions& options) {
  RestartPoint r;
  if (fs::exists(fs::path(where) / "checkpoint.json")) {
    r.folder = where;
    fs::path parent = fs::path(where).lexically_normal().parent_path();
    r.output_dir = parent.empty() ? "." : parent.string();
  } else if (fs::exists(fs::path(checkpoint_folder(where)) / "checkpoint.json")) {
    r.folder = checkpoint_folder(where);
    r.output_dir = where;
  } else {
    throw CheckpointError("--restart " + where + ": no checkpoint there (expected " + where +
                          "/checkpoint/checkpoint.json or " + where + "/checkpoint.json)");
  }
  Json meta;
  try {
    meta = Json::parse(read_checkpoint_meta(r.folder));
  } catch (const Json::exception&) {
    throw CheckpointError(r.folder + "/checkpoint.json is not valid JSON (damaged)");
  }
  const std::string what = "checkpoint " + r.folder + ": ";
  try {
    if (meta.value("format", 0) != kFormat)
      throw CheckpointError(what + "format " + std::to_string(meta.value("format", 0)) + ", this mfsd reads format " +
                            std::to_string(kFormat));
    const std::string version = meta.at("mfsd_version").get<std::string>();
    const std::string commit = meta.at("git_commit").get<std::string>();
    if (version != MFSD_VERSION || commit != MFSD_GIT_COMMIT)
      throw CheckpointError(what + "written by mfsd " + version + " (commit " + commit + "), this is mfsd " +
                            MFSD_VERSION + " (commit " + MFSD_GIT_COMMIT +
                            "); continue it with the binary that wrote it");
    const nlohmann::json old_scene = comparable_scene(meta.at("scene")), new_scene = comparable_scene(doc.resolved);
    if (old_scene != new_scene) {
      using Pointer = nlohmann::json::json_pointer;
      const nlohmann::json patch = nlohmann::json::diff(old_scene, new_scene);
      const std::string path = patch.empty() ? "/" : patch.at(0).at("path").get<std::string>();
      const nlohmann::json before = old_scene.contains(Pointer(path)) ? old_scene.at(Pointer(path)) : nlohmann::json();
      const nlohmann::json after = new_scene.contains(Pointer(path)) ? new_scene.at(Pointer(path)) : nlohmann::json();
      throw CheckpointError(what + "written for another scene: " + path + " was " + text(before) + ", is " +
                            text(after) + " (only solver.end_time and output.checkpoint_interval may change)");
    }
    const std::string backend = meta.at("backend").get<std::string>(), precision = meta.at("precision");
    if (backend != options.solver.backend)
      throw CheckpointError(what + "written by the " + backend + " backend; continue it with --backend " + backend);
    if (precision != to_string(options.solver.precision))
      throw CheckpointError(what + "written in " + precision + " precision; continue it with --precision " + precision);
    if (meta.at("threads").get<int>() != thread_count(options))
      r.warnings.push_back(what + "written with " + std::to_string(meta.at("threads").get<int>()) +
                           " threads, continued with " + std::to_string(thread_count(options)) +
                           ": the run continues, but not bit for bit as the uninterrupted one would");
    r.time = meta.at("time").get<double>();
    r.steps = meta.at("steps").get<long>();
    if (r.time >= doc.scene.solver.end_time)
      throw CheckpointError(what + "at t = " + std::to_string(r.time) +
                            " s, not before solver.end_time = " + std::to_string(doc.scene.solver.end_time) +
                            " s: nothing to continue (raise end_time with --set solver.end_time=...)");
    const Json& out = meta.at("outputs");
    r.position.next_output = out.at("next_output").get<double>();
    r.position.next_probe = out.at("next_probe").get<double>();
    r.position.next_checkpoint = out.at("next_checkpoint").get<double>();
    r.position.snapshot_count = out.at("snapshot_count").get<int>();
    for (auto& e : out.at("snapshots")) r.position.snapshots.emplace_back(e.at("time"), e.at("file"));
    for (auto& e : out.at("rigid_snapshots")) r.position.rigid_snapshots.emplace_back(e.at("time"), e.at("file"));
    for (auto& [name, bytes] : out.at("csv_bytes").items()) r.position.csv_bytes[name] = bytes.get<std::uint64_t>();
  } catch (const Json::exception& e) {
    throw CheckpointError(what + "checkpoint.json lacks a part or has a wrong type (" + e.what() + ")");
  }
  return r;
}

}  // namespace mfsd
