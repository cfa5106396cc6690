// Structure-of-arrays particle storage with a registry of fields that stages
// declare (design.md, "Particle storage"). One buffer per field in the
// backend's memory space; vector and tensor fields are arrays of Vec/Mat.
// Bodies are index ranges [begin, end) of one set.
#pragma once
#include <cstring>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <typeinfo>
#include <vector>

#include "host/backend/algorithms.hpp"
#include "host/particles/field_memory.hpp"
#include "host/particles/state_archive.hpp"
#include "kernels/core/mat.hpp"
#include "kernels/core/vec.hpp"

namespace mfsd {

template <class T>
struct FieldLayout {
  static constexpr bool plain = std::is_arithmetic<T>::value;
  static constexpr int components = 1, rows = 0, scalar_bytes = int(sizeof(T));
  static constexpr char kind = std::is_floating_point<T>::value ? 'f' : std::is_signed<T>::value ? 'i' : 'u';
};
template <int N, class S>
struct FieldLayout<Vec<N, S>> : FieldLayout<S> {
  static constexpr int components = N, rows = 0;
};
template <int N, class S>
struct FieldLayout<Mat<N, S>> : FieldLayout<S> {
  static constexpr int components = N * N, rows = N;
};

struct BodyRange {
  Index begin = 0;
  Index end = 0;
  Index size() const { return end - begin; }
};

template <class B>
class ParticleSet {
 public:
  explicit ParticleSet(Index n = 0) : n_(n) {}

  Index size() const { return n_; }

  // Registers a field of n elements, zero-initialized. Registering the same
  // name twice with the same type returns the existing buffer.
  template <class T>
  T* add(const std::string& name) {
    auto it = fields_.find(name);
    if (it != fields_.end()) return typed<T>(name, *it->second).data_ptr();
    auto f = std::make_unique<Field<T>>();
    f->data.resize(size_t(n_));
    T* p = f->data_ptr();
    fields_.emplace(name, std::move(f));
    return p;
  }

  template <class T>
  T* get(const std::string& name) {
    return typed<T>(name, find(name)).data_ptr();
  }
  template <class T>
  const T* get(const std::string& name) const {
    return typed<T>(name, find(name)).data_ptr();
  }
  template <class T>
  DeviceVector<B, T>& buffer(const std::string& name) {
    return typed<T>(name, find(name)).data;
  }

  bool has(const std::string& name) const { return fields_.count(name) != 0; }

  // Frees a field that is no longer needed (e.g. set-up data).
  void remove(const std::string& name) { fields_.erase(name); }

  std::vector<std::string> field_names() const {
    std::vector<std::string> r;
    for (auto& kv : fields_) r.push_back(kv.first);
    return r;
  }

  // The layout and address of a field's values (FieldMemory).
  FieldMemory memory(const std::string& name) const { return find(name).memory(name); }
  // A field's values copied to the host, element after element.
  std::string bytes(const std::string& name) const { return find(name).save(); }

  // Bytes held by all fields (for the memory-per-particle report).
  size_t bytes() const {
    size_t s = 0;
    for (auto& kv : fields_) s += kv.second->bytes();
    return s;
  }

  // Every field's bytes as "field/<name>" (checkpoints).
  void save(StateArchive& archive) const {
    for (auto& kv : fields_) archive.put_bytes("field/" + kv.first, kv.second->save());
  }
  // Every registered field from the archive, which must hold each with the
  // same size; fields the archive has and this set lacks are a mismatch too.
  void restore(const StateArchive& archive) {
    for (auto& kv : fields_) kv.second->restore(archive.bytes("field/" + kv.first), kv.first);
    for (auto& kv : archive.blobs())
      if (kv.first.rfind("field/", 0) == 0 && !has(kv.first.substr(6)))
        throw StateMismatch("the checkpoint has particle field '" + kv.first.substr(6) + "', which this run does not");
  }

  // The raw bytes of a field's elements at `index`, in that order, and back
  // into the elements at `index` (the ghost exchange, host/distributed/).
  std::vector<char> pack(const std::string& name, const DeviceVector<B, Index>& index) const {
    return find(name).pack(index);
  }
  void unpack(const std::string& name, const DeviceVector<B, Index>& index, const std::vector<char>& bytes) {
    find(name).unpack(index, bytes);
  }
  size_t element_bytes(const std::string& name) const { return find(name).element_bytes(); }

  // A new particle count for every field (the particles a distributed run's
  // rank holds after a migration, whose values are then unpacked in);
  // the elements kept keep their values.
  void resize(Index n) {
    n_ = n;
    for (auto& kv : fields_) kv.second->resize(size_t(n));
  }

  // Reorders every field: new[k] = old[perm[k]]. Ids travel with the data, so
  // outputs still name particles by their original index.
  void permute(const DeviceVector<B, Index>& perm) {
    if (Index(perm.size()) != n_) throw std::logic_error("ParticleSet::permute: size mismatch");
    for (auto& kv : fields_) kv.second->permute(perm);
  }

 private:
  struct FieldBase {
    virtual ~FieldBase() = default;
    virtual void permute(const DeviceVector<B, Index>& perm) = 0;
    virtual void resize(size_t n) = 0;
    virtual size_t bytes() const = 0;
    virtual const std::type_info& type() const = 0;
    virtual std::string save() const = 0;
    virtual void restore(const std::string& bytes, const std::string& name) = 0;
    virtual std::vector<char> pack(const DeviceVector<B, Index>& index) const = 0;
    virtual size_t element_bytes() const = 0;
    virtual void unpack(const DeviceVector<B, Index>& index, const std::vector<char>& bytes) = 0;
    virtual FieldMemory memory(const std::string& name) = 0;
  };
  template <class T>
  struct Field final : FieldBase {
    DeviceVector<B, T> data;
    T* data_ptr() { return raw(data); }
    void permute(const DeviceVector<B, Index>& perm) override {
      DeviceVector<B, T> tmp(data.size());
      gather<B, T>(perm, data, tmp);
      data.swap(tmp);
    }
    void resize(size_t n) override { data.resize(n); }
    size_t bytes() const override { return data.size() * sizeof(T); }
    size_t element_bytes() const override { return sizeof(T); }
    const std::type_info& type() const override { return typeid(T); }
    FieldMemory memory(const std::string& name) override {
      using L = FieldLayout<T>;
      FieldMemory m;
      m.name = name;
      m.data = static_cast<void*>(raw(data));
      m.count = data.size();
      m.components = L::components;
      m.rows = L::rows;
      m.kind = L::kind;
      m.scalar_bytes = L::scalar_bytes;
      m.plain = L::plain && sizeof(T) == size_t(L::components) * size_t(L::scalar_bytes);
      m.on_device = !std::is_same<B, Cpu>::value;
      return m;
    }
    std::string save() const override {
      const std::vector<T> h = to_host<B>(data);
      return std::string(reinterpret_cast<const char*>(h.data()), h.size() * sizeof(T));
    }
    void restore(const std::string& bytes, const std::string& name) override {
      if (bytes.size() != data.size() * sizeof(T))
        throw StateMismatch("checkpoint field '" + name + "' holds " + std::to_string(bytes.size()) +
                            " bytes, this run's " + std::to_string(data.size() * sizeof(T)));
      std::vector<T> h(data.size());
      if (!bytes.empty()) std::memcpy(static_cast<void*>(h.data()), bytes.data(), bytes.size());
      from_host<B>(h, data);
    }
    std::vector<char> pack(const DeviceVector<B, Index>& index) const override {
      DeviceVector<B, T> picked(index.size());
      gather<B, T>(index, data, picked);
      const std::vector<T> h = to_host<B>(picked);
      std::vector<char> bytes(h.size() * sizeof(T));
      if (!h.empty()) std::memcpy(bytes.data(), static_cast<const void*>(h.data()), bytes.size());
      return bytes;
    }
    void unpack(const DeviceVector<B, Index>& index, const std::vector<char>& bytes) override {
      if (bytes.size() != index.size() * sizeof(T)) throw std::logic_error("ParticleSet::unpack: size mismatch");
      std::vector<T> h(index.size());
      if (!h.empty()) std::memcpy(static_cast<void*>(h.data()), bytes.data(), bytes.size());
      DeviceVector<B, T> values(index.size());
      from_host<B>(h, values);
      scatter<B, T>(values, index, data);
    }
  };

  FieldBase& find(const std::string& name) const {
    auto it = fields_.find(name);
    if (it == fields_.end()) throw std::logic_error("particle field '" + name + "' is not registered");
    return *it->second;
  }
  template <class T>
  static Field<T>& typed(const std::string& name, FieldBase& f) {
    if (f.type() != typeid(T)) throw std::logic_error("particle field '" + name + "' has another type");
    return static_cast<Field<T>&>(f);
  }

  Index n_;
  std::map<std::string, std::unique_ptr<FieldBase>> fields_;
};

}  // namespace mfsd
