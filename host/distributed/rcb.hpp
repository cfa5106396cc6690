// Recursive coordinate bisection on particle counts (issue 25): the domain
// decomposition of the distributed engine. A set of points is cut into
// `parts` boxes by planes normal to a coordinate axis, each cut at the count
// that gives its two sides particle numbers proportional to their part
// counts (any part count, not only powers of two), along the axis of the
// longest extent of the points being cut. Every region is an axis-aligned
// box (infinite on the outer sides), so a point's owner is found by walking
// the cut tree (migration) and the ghosts a part needs are the other parts'
// points within the search radius of its box (halo.hpp).
//
// Host-side and deterministic: the same points give the same cuts on every
// process (ties broken by index), so every rank can compute the whole
// decomposition from the gathered positions, and a rebalance is the same
// call.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace mfsd::distributed {

using Point = std::array<double, 3>;

struct Box {
  Point lo{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
           -std::numeric_limits<double>::infinity()};
  Point hi{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
           std::numeric_limits<double>::infinity()};
  // The distance from x to the box (0 inside), over the first `dim` axes.
  double distance(const Point& x, int dim) const;
};

// A node of the cut tree: an inner node cuts at `position` along `axis`
// (x < position goes to `left`), a leaf holds a part.
struct CutNode {
  int axis = -1;  // -1: leaf
  double position = 0;
  int left = -1, right = -1;  // child node indices
  int part = -1;              // leaf: the part (rank)
};

struct Decomposition {
  int dim = 3;
  int parts = 1;
  std::vector<CutNode> tree;  // tree[0] is the root
  std::vector<Box> boxes;     // per part
  std::vector<long> counts;   // particles per part at the decomposition
  // The part owning x (ties on a cut go right, as in the build).
  int owner(const Point& x) const;
  // max count / mean count (1: perfect balance).
  double imbalance() const;
};

// Cuts `points` (the first `dim` coordinates) into `parts` parts; owner[i]
// gets the part of point i. parts >= 1; an empty point set gives empty boxes
// that still tile space (cuts at 0).
Decomposition recursive_coordinate_bisection(const std::vector<Point>& points, int dim, int parts,
                                             std::vector<int>& owner);

// The counts of a decomposition for other points (the particles after they
// moved) and whether its imbalance exceeds `threshold` (a rebalance is due).
std::vector<long> part_counts(const Decomposition& d, const std::vector<Point>& points);
bool rebalance_due(const Decomposition& d, const std::vector<Point>& points, double threshold);

}  // namespace mfsd::distributed
