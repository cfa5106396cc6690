#include "host/output/checkpoint_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace mfsd {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'M', 'F', 'S', 'D', 'S', 'T', 'A', '1'};

std::uint64_t fnv1a64(const std::string& s) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

template <class T>
void append(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

// state.bin: magic, blob count, then per blob: name length, name, size, bytes.
std::string encode(const StateArchive& archive) {
  std::string out(kMagic, sizeof kMagic);
  append<std::uint64_t>(out, archive.blobs().size());
  for (auto& kv : archive.blobs()) {
    append<std::uint32_t>(out, std::uint32_t(kv.first.size()));
    out += kv.first;
    append<std::uint64_t>(out, kv.second.size());
    out += kv.second;
  }
  return out;
}

StateArchive decode(const std::string& in, const std::string& path) {
  size_t at = 0;
  auto take = [&](size_t n) {
    if (in.size() - at < n) throw CheckpointError(path + " ends early (damaged)");
    const size_t from = at;
    at += n;
    return from;
  };
  auto number = [&](auto tag) {
    decltype(tag) v;
    std::memcpy(&v, in.data() + take(sizeof v), sizeof v);
    return v;
  };
  if (in.compare(0, sizeof kMagic, std::string(kMagic, sizeof kMagic)) != 0)
    throw CheckpointError(path + " is not an mfsd state file");
  take(sizeof kMagic);
  StateArchive a;
  const std::uint64_t count = number(std::uint64_t{});
  for (std::uint64_t k = 0; k < count; ++k) {
    const std::uint32_t name_size = number(std::uint32_t{});
    const std::string name = in.substr(take(name_size), name_size);
    const std::uint64_t size = number(std::uint64_t{});
    if (size > in.size()) throw CheckpointError(path + " ends early (damaged)");
    a.put_bytes(name, in.substr(take(size_t(size)), size_t(size)));
  }
  if (at != in.size()) throw CheckpointError(path + " has trailing bytes (damaged)");
  return a;
}

// Writes and fsyncs a file, so that the renames below publish whole files.
void write_synced(const std::string& path, const std::string& content) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw std::runtime_error("cannot write '" + path + "': " + std::strerror(errno));
  size_t done = 0;
  while (done < content.size()) {
    const ssize_t w = ::write(fd, content.data() + done, content.size() - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      throw std::runtime_error("cannot write '" + path + "': " + why);
    }
    done += size_t(w);
  }
  ::fsync(fd);
  ::close(fd);
}

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CheckpointError("cannot read '" + path + "'");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

CheckpointWriteReport write_checkpoint(const std::string& folder, const std::string& meta_json,
                                       const StateArchive& archive) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string fresh = folder + ".new", previous = folder + ".previous";
  fs::remove_all(fresh);
  fs::create_directories(fresh);
  const std::string state = encode(archive);
  nlohmann::ordered_json meta = nlohmann::ordered_json::parse(meta_json);
  meta["state"] = {{"file", "state.bin"}, {"bytes", state.size()}, {"fnv1a64", fnv1a64(state)}};
  const std::string meta_text = meta.dump(2) + "\n";
  write_synced(fresh + "/state.bin", state);
  write_synced(fresh + "/checkpoint.json", meta_text);
  if (fs::exists(folder)) {
    fs::remove_all(previous);
    fs::rename(folder, previous);
  }
  fs::rename(fresh, folder);
  CheckpointWriteReport r;
  r.bytes = state.size() + meta_text.size();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

std::string read_checkpoint_meta(const std::string& folder) {
  const std::string path = folder + "/checkpoint.json";
  if (!fs::exists(path)) throw CheckpointError("'" + folder + "' holds no checkpoint (no checkpoint.json)");
  return read_all(path);
}

CheckpointContents read_checkpoint(const std::string& folder) {
  CheckpointContents c;
  c.meta_json = read_checkpoint_meta(folder);
  nlohmann::json meta;
  try {
    meta = nlohmann::json::parse(c.meta_json);
  } catch (const nlohmann::json::exception&) {
    throw CheckpointError(folder + "/checkpoint.json is not valid JSON (damaged)");
  }
  const std::string path = folder + "/state.bin";
  const std::string state = read_all(path);
  const auto& s = meta.value("state", nlohmann::json::object());
  if (!s.contains("bytes") || !s.contains("fnv1a64")) throw CheckpointError(folder + "/checkpoint.json has no state");
  if (s["bytes"].get<std::uint64_t>() != state.size())
    throw CheckpointError(path + " holds " + std::to_string(state.size()) + " bytes, checkpoint.json says " +
                          std::to_string(s["bytes"].get<std::uint64_t>()) + " (damaged)");
  if (s["fnv1a64"].get<std::uint64_t>() != fnv1a64(state))
    throw CheckpointError(path + " does not match its checksum (damaged)");
  c.archive = decode(state, path);
  return c;
}

}  // namespace mfsd
