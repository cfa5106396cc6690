// A run's state as named byte blobs (checkpoints): each part of a solver
// (particle fields, time and step, the conditions' work sums, the relaxation's
// random generator, ...) puts what it needs to continue bit for bit and gets
// it back by the same name. The file format is in host/output/checkpoint_file.hpp.
#pragma once
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace mfsd {

// A checkpoint that does not fit the run it is restored into (a missing
// part, a size that differs); the CLI reports it as an input error.
class StateMismatch : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class StateArchive {
 public:
  void put_bytes(const std::string& name, std::string bytes) { blobs_[name] = std::move(bytes); }

  template <class T>
  void put(const std::string& name, const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable<T>::value, "state blobs hold plain data");
    std::string b(values.size() * sizeof(T), '\0');
    if (!b.empty()) std::memcpy(&b[0], values.data(), b.size());
    put_bytes(name, std::move(b));
  }
  template <class T>
  void put_value(const std::string& name, const T& value) {
    put(name, std::vector<T>{value});
  }

  bool has(const std::string& name) const { return blobs_.count(name) != 0; }

  const std::string& bytes(const std::string& name) const {
    auto it = blobs_.find(name);
    if (it == blobs_.end()) throw StateMismatch("the checkpoint has no '" + name + "'");
    return it->second;
  }

  // The blob as `count` values of T (count < 0: as many as it holds).
  template <class T>
  std::vector<T> get(const std::string& name, long count = -1) const {
    const std::string& b = bytes(name);
    if (b.size() % sizeof(T) != 0 || (count >= 0 && b.size() != size_t(count) * sizeof(T)))
      throw StateMismatch(
          "checkpoint part '" + name + "' holds " + std::to_string(b.size()) + " bytes, expected " +
          (count >= 0 ? std::to_string(size_t(count) * sizeof(T)) : "a multiple of " + std::to_string(sizeof(T))));
    std::vector<T> v(b.size() / sizeof(T));
    if (!b.empty()) std::memcpy(v.data(), b.data(), b.size());
    return v;
  }
  template <class T>
  T get_value(const std::string& name) const {
    return get<T>(name, 1)[0];
  }

  const std::map<std::string, std::string>& blobs() const { return blobs_; }
  size_t total_bytes() const {
    size_t s = 0;
    for (auto& kv : blobs_) s += kv.second.size();
    return s;
  }

 private:
  std::map<std::string, std::string> blobs_;
};

}  // namespace mfsd
