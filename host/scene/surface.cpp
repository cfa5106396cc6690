#include "host/scene/surface.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace mfsd {

void mark_surface(const std::vector<Point3>& positions, long begin, long end, double dp, int dim,
                  std::vector<unsigned char>& surface) {
  if (end <= begin) return;
  Point3 lo = positions[size_t(begin)];
  for (long i = begin; i < end; ++i)
    for (int a = 0; a < dim; ++a) lo[a] = std::min(lo[a], positions[size_t(i)][a]);
  // Integer lattice coordinates, offset by 1 so that a missing neighbour below
  // the lowest layer has coordinate 0, never negative.
  auto cell = [&](long i, int a) { return std::int64_t(std::llround((positions[size_t(i)][a] - lo[a]) / dp)) + 1; };
  constexpr std::int64_t kBits = 21, kMask = (std::int64_t(1) << kBits) - 1;
  auto key = [&](std::int64_t c0, std::int64_t c1, std::int64_t c2) {
    return (c0 & kMask) | ((c1 & kMask) << kBits) | ((c2 & kMask) << (2 * kBits));
  };
  std::unordered_set<std::int64_t> occupied;
  occupied.reserve(size_t(end - begin) * 2);
  for (long i = begin; i < end; ++i) occupied.insert(key(cell(i, 0), cell(i, 1), dim == 3 ? cell(i, 2) : 0));
  for (long i = begin; i < end; ++i) {
    std::int64_t c[3] = {cell(i, 0), cell(i, 1), dim == 3 ? cell(i, 2) : 0};
    unsigned char exposed = 0;
    for (int a = 0; a < dim; ++a)
      for (int s = 0; s < 2; ++s) {
        std::int64_t n[3] = {c[0], c[1], c[2]};
        n[a] += s ? 1 : -1;
        if (!occupied.count(key(n[0], n[1], n[2]))) exposed |= (unsigned char)(1u << (2 * a + s));
      }
    surface[size_t(i)] = exposed;
  }
}

}  // namespace mfsd
