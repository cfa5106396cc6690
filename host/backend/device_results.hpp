// The results a step's reductions leave in backend memory (force and power
// sums of conditions and contact, the time-step maxima, error reports),
// brought to the host together by one copy at the end of the step: the
// step's one synchronisation (docs/architecture.md, "What synchronises").
// Each reduction gets a slot for its result in the order it runs; the
// owners read their slots after fetch(). Include after the backend header.
#pragma once
#include <thrust/system_error.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "host/backend/algorithms.hpp"
#include "host/backend/backend_error.hpp"

namespace mfsd {

// Where one result lies in the buffer (a byte offset), and its type.
template <class T>
struct ResultSlot {
  size_t offset = 0;
};

template <class B>
class DeviceResults {
 public:
  // Slots are handed out again from the start (at the start of each step).
  void clear() { used_ = 0; }

  // parallel_reduce into a new slot: f(i) exactly once per i, may write
  // element i's state (algorithms.hpp).
  template <class T, class F, class Op>
  ResultSlot<T> reduce(Index begin, Index end, const F& f, T init, Op op) {
    static_assert(std::is_trivially_copyable<T>::value, "results are copied as bytes");
    const ResultSlot<T> slot{reserve(sizeof(T))};
    parallel_reduce<B>(begin, end, f, init, op,
                       reinterpret_cast<T*>(reinterpret_cast<char*>(raw(buffer_)) + slot.offset));
    return slot;
  }

  // A reduction that the caller runs, given where its result goes (e.g.
  // half_pair_reduce): run(T* out).
  template <class T, class Run>
  ResultSlot<T> reduce_into(const Run& run) {
    static_assert(std::is_trivially_copyable<T>::value, "results are copied as bytes");
    const ResultSlot<T> slot{reserve(sizeof(T))};
    run(reinterpret_cast<T*>(reinterpret_cast<char*>(raw(buffer_)) + slot.offset));
    return slot;
  }

  // One copy of every slot of this step to the host (a round trip). A
  // device fault of any kernel queued before shows here: BackendError, deferred.
  void fetch() {
    host_.resize(used_ / sizeof(Word));
    if (used_ == 0) return;
    count_round_trip();
    try {
      thrust::copy(buffer_.begin(), buffer_.begin() + std::ptrdiff_t(used_ / sizeof(Word)), host_.begin());
    } catch (const thrust::system_error& e) {
      throw BackendError(std::string("device error: ") + e.what(), true);
    }
  }

  // A slot's value after fetch().
  template <class T>
  T get(ResultSlot<T> slot) const {
    T v;
    std::memcpy(static_cast<void*>(&v), reinterpret_cast<const char*>(host_.data()) + slot.offset, sizeof(T));
    return v;
  }

 private:
  static constexpr size_t kAlign = 16;
  size_t reserve(size_t bytes) {
    const size_t offset = used_;
    used_ += (bytes + kAlign - 1) / kAlign * kAlign;
    // Grows at the first steps only; stream order keeps earlier results
    // (the copy runs after the kernels that wrote them).
    if (used_ > buffer_.size() * sizeof(Word)) buffer_.resize(std::max<size_t>(2 * used_, 4096) / sizeof(Word));
    return offset;
  }
  // Raw 8-byte words, not double: float runs keep double out of every kernel,
  // the buffer's fill and copy included (scripts/check_float_ptx.py).
  using Word = std::uint64_t;
  DeviceVector<B, Word> buffer_;
  std::vector<Word> host_;
  size_t used_ = 0;
};

}  // namespace mfsd
