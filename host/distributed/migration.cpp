#include "host/distributed/migration.hpp"

#include <algorithm>
#include <iterator>
#include <stdexcept>

#include "host/distributed/halo.hpp"

namespace mfsd::distributed {

Repartition repartition(const Decomposition& current, const std::vector<Point>& points, double radius,
                        double threshold) {
  Repartition r;
  if (rebalance_due(current, points, threshold)) {
    r.decomposition = recursive_coordinate_bisection(points, current.dim, current.parts, r.owner);
    r.rebalanced = true;
  } else {
    r.decomposition = current;
    r.owner.resize(points.size());
    for (size_t i = 0; i < points.size(); ++i) r.owner[i] = current.owner(points[i]);
    r.decomposition.counts = part_counts(current, points);
  }
  r.halo = halo_lists(r.decomposition, points, r.owner, radius);
  return r;
}

std::vector<std::vector<long>> holdings(const Repartition& r) {
  const size_t parts = size_t(r.decomposition.parts);
  std::vector<std::vector<long>> owned(parts), out(parts);
  for (size_t i = 0; i < r.owner.size(); ++i) owned[size_t(r.owner[i])].push_back(long(i));
  for (size_t p = 0; p < parts; ++p) {
    const std::vector<long> ghosts(r.halo[p].begin(), r.halo[p].end());
    std::merge(owned[p].begin(), owned[p].end(), ghosts.begin(), ghosts.end(), std::back_inserter(out[p]));
  }
  return out;
}

std::vector<double> to_numbers(const Decomposition& d) {
  std::vector<double> v{double(d.dim), double(d.parts), double(d.tree.size())};
  for (const CutNode& n : d.tree)
    v.insert(v.end(), {double(n.axis), n.position, double(n.left), double(n.right), double(n.part)});
  for (const Box& b : d.boxes) {
    v.insert(v.end(), b.lo.begin(), b.lo.end());
    v.insert(v.end(), b.hi.begin(), b.hi.end());
  }
  for (long c : d.counts) v.push_back(double(c));
  return v;
}

Decomposition decomposition_from(const std::vector<double>& v) {
  Decomposition d;
  size_t k = 0;
  auto next = [&] {
    if (k >= v.size()) throw std::runtime_error("a decomposition's numbers end early");
    return v[k++];
  };
  d.dim = int(next());
  d.parts = int(next());
  d.tree.resize(size_t(next()));
  for (CutNode& n : d.tree) {
    n.axis = int(next());
    n.position = next();
    n.left = int(next());
    n.right = int(next());
    n.part = int(next());
  }
  d.boxes.resize(size_t(d.parts));
  for (Box& b : d.boxes) {
    for (double& x : b.lo) x = next();
    for (double& x : b.hi) x = next();
  }
  d.counts.resize(size_t(d.parts));
  for (long& c : d.counts) c = long(next());
  return d;
}

}  // namespace mfsd::distributed
