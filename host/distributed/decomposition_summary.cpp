#include "host/distributed/decomposition_summary.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "host/distributed/halo.hpp"
#include "host/distributed/rcb.hpp"
#include "host/halo/halo_radius.hpp"

namespace mfsd::distributed {

std::string decomposition_summary(const SceneDocument& doc, const InitialParticles& particles, int ranks) {
  const Scene& scene = doc.scene;
  std::vector<Point> points(particles.position.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    points[i] = Point{particles.position[i][0], particles.position[i][1], particles.position[i][2]};
  std::vector<int> owner;
  const Decomposition d = recursive_coordinate_bisection(points, scene.dimension, ranks, owner);
  const double radius = halo_radius(scene);
  const auto ghosts = halo_lists(d, points, owner, radius);
  std::ostringstream o;
  o << "scene '" << scene.name << "': " << points.size() << " particles in " << ranks
    << " parts (recursive coordinate bisection of the reference positions), halo radius " << radius << " m\n";
  o << "rank      owned     ghosts  ghosts/owned  box\n";
  long total_ghosts = 0, most_ghosts = 0;
  for (int p = 0; p < ranks; ++p) {
    const long own = d.counts[size_t(p)], g = long(ghosts[size_t(p)].size());
    total_ghosts += g;
    most_ghosts = std::max(most_ghosts, g);
    o << std::setw(4) << p << std::setw(11) << own << std::setw(11) << g << std::setw(14) << std::fixed
      << std::setprecision(4) << (own > 0 ? double(g) / double(own) : 0.0) << std::defaultfloat << "  [";
    for (int a = 0; a < scene.dimension; ++a) {
      o << (a ? ", " : "") << d.boxes[size_t(p)].lo[a] << ".." << d.boxes[size_t(p)].hi[a];
    }
    o << "]\n";
  }
  o << "imbalance (max/mean owned) " << d.imbalance() << "; ghosts: " << total_ghosts << " in all, at most "
    << most_ghosts << " on one rank, " << double(total_ghosts) / double(std::max<std::size_t>(points.size(), 1))
    << " per particle\n";
  return o.str();
}

}  // namespace mfsd::distributed
