#include "host/halo/halo_radius.hpp"

#include <algorithm>
#include <cmath>

namespace mfsd::distributed {

double halo_radius(const Scene& scene) {
  const int dim = scene.dimension;
  double r = 0;
  for (const BodySpec& b : scene.bodies) {
    if (b.method == Method::rkpm) {
      const RkpmSpec& k = scene.solver.rkpm;
      const double reach = k.box_supports ? std::sqrt(double(dim)) : 1.0;
      // The list's radius (the support, the cell's half diagonal and the
      // skin) and one spacing for the travel between migrations; a
      // migration widens it as the supports and cells grow (rkpm_solver.hpp).
      r = std::max(r, (k.support_factor * reach + 0.5 * std::sqrt(double(dim)) + k.skin + 1.0) * b.spacing);
    } else if (b.method == Method::ulsph) {
      // The support and one h of skin: a distributed ULSPH run keeps its
      // set-up's ghosts (docs/distributed.md).
      r = std::max(r, 3.0 * scene.solver.h_over_dp * b.spacing);
    } else {
      r = std::max(r, 2.0 * scene.solver.h_over_dp * b.spacing);  // the kernels' support 2h
    }
  }
  return r;
}

}  // namespace mfsd::distributed
