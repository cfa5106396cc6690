#include "host/distributed/halo.hpp"

namespace mfsd::distributed {

std::vector<std::vector<std::size_t>> halo_lists(const Decomposition& d, const std::vector<Point>& points,
                                                 const std::vector<int>& owner, double radius) {
  std::vector<std::vector<std::size_t>> ghosts(size_t(d.parts));
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int p = 0; p < d.parts; ++p)
      if (p != owner[i] && d.boxes[size_t(p)].distance(points[i], d.dim) < radius) ghosts[size_t(p)].push_back(i);
  return ghosts;
}

}  // namespace mfsd::distributed
