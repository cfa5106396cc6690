// The radius within which a particle's partners lie: per body 2h (SPH
// kernels) or, for RKPM, (a~ reach + cell half-diagonal + skin) dp; the
// largest over the bodies. What a distributed run's halo must cover.
#pragma once
#include "host/scene/scene.hpp"

namespace mfsd::distributed {

double halo_radius(const Scene& scene);

}  // namespace mfsd::distributed
