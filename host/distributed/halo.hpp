// Halo lists of a decomposition (issue 25): the particles each part needs
// from the others. A part's pairs are those of its own particles within the
// search radius r; every partner of an owned particle lies within r of the
// part's box, so the ghosts of part p are the other parts' particles within
// r of box p (complete by construction; a brute-force check is in
// tests/unit/test_rcb.cpp). Host-side; the exchange sends exactly these.
#pragma once
#include <vector>

#include "host/distributed/rcb.hpp"

namespace mfsd::distributed {

// ghosts[p]: the indices (ascending) of the points owned by other parts
// within `radius` of part p's box.
std::vector<std::vector<std::size_t>> halo_lists(const Decomposition& d, const std::vector<Point>& points,
                                                 const std::vector<int>& owner, double radius);

}  // namespace mfsd::distributed
