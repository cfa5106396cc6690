#include "host/backend/round_trips.hpp"

#include <atomic>

namespace mfsd {

namespace {
std::atomic<long> counter{0};
}

long round_trips() { return counter.load(std::memory_order_relaxed); }
void count_round_trip() { counter.fetch_add(1, std::memory_order_relaxed); }

}  // namespace mfsd
