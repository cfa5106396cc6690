// Surface particles of a lattice-filled body: a particle is on the surface
// when one of its 2D lattice neighbours (at +-dp along each axis) is not a
// particle of the same body; the missing directions are its exposed faces. Exact for the generator's lattices (particle
// centres at min + (k + 1/2) dp); used to put surface tractions only on the
// outermost layer of a selection.
#pragma once
#include <vector>

#include "host/scene/shape.hpp"

namespace mfsd {

// Marks positions[begin, end) (one body, spacing dp) in surface[begin, end)
// with the faces each exposes: bit 2a for -e_a, bit 2a + 1 for +e_a; 0 inside.
void mark_surface(const std::vector<Point3>& positions, long begin, long end, double dp, int dim,
                  std::vector<unsigned char>& surface);

}  // namespace mfsd
