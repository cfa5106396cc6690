#include "host/distributed/rcb.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace mfsd::distributed {

double Box::distance(const Point& x, int dim) const {
  double d2 = 0;
  for (int a = 0; a < dim; ++a) {
    const double d = x[a] < lo[a] ? lo[a] - x[a] : (x[a] > hi[a] ? x[a] - hi[a] : 0.0);
    d2 += d * d;
  }
  return std::sqrt(d2);
}

int Decomposition::owner(const Point& x) const {
  int n = 0;
  while (tree[size_t(n)].axis >= 0) {
    const CutNode& c = tree[size_t(n)];
    n = x[c.axis] < c.position ? c.left : c.right;
  }
  return tree[size_t(n)].part;
}

double Decomposition::imbalance() const {
  long total = 0, most = 0;
  for (long c : counts) total += c, most = std::max(most, c);
  return total > 0 ? double(most) * double(parts) / double(total) : 1.0;
}

namespace {

struct Builder {
  const std::vector<Point>& points;
  int dim;
  Decomposition& d;
  std::vector<int>& owner;

  // Cuts the points idx[begin, end) inside `box` into parts [first, first + n).
  int build(std::vector<std::size_t>& idx, std::size_t begin, std::size_t end, int first, int n, const Box& box) {
    const int node = int(d.tree.size());
    d.tree.emplace_back();
    if (n == 1) {
      d.tree[size_t(node)].part = first;
      d.boxes[size_t(first)] = box;
      d.counts[size_t(first)] = long(end - begin);
      for (std::size_t k = begin; k < end; ++k) owner[idx[k]] = first;
      return node;
    }
    // The axis of the longest extent of these points (of the box where empty).
    int axis = 0;
    double widest = -1;
    for (int a = 0; a < dim; ++a) {
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (std::size_t k = begin; k < end; ++k)
        lo = std::min(lo, points[idx[k]][a]), hi = std::max(hi, points[idx[k]][a]);
      const double w = end > begin ? hi - lo : 0.0;
      if (w > widest) widest = w, axis = a;
    }
    const int n_left = n / 2;
    // Left gets round(count n_left / n) points: the points ordered along the
    // axis (ties by index, so that every process cuts alike).
    const std::size_t count = end - begin;
    const std::size_t k_left = std::size_t(std::llround(double(count) * n_left / n));
    auto less = [&](std::size_t i, std::size_t j) {
      return points[i][axis] < points[j][axis] || (points[i][axis] == points[j][axis] && i < j);
    };
    std::sort(idx.begin() + std::ptrdiff_t(begin), idx.begin() + std::ptrdiff_t(end), less);
    // The cut halfway between the last left and the first right point; equal
    // coordinates across the cut would make the owner ambiguous, so the cut
    // moves to the first change of coordinate at or after k_left.
    std::size_t k = k_left;
    while (k > 0 && k < count && points[idx[begin + k]][axis] == points[idx[begin + k - 1]][axis]) ++k;
    double position;
    if (count == 0) {  // an empty region: cut on its lower face (inside it, never into another part)
      position = std::isfinite(box.lo[axis]) ? box.lo[axis] : (std::isfinite(box.hi[axis]) ? box.hi[axis] : 0.0);
    } else if (k == 0) {
      position = points[idx[begin]][axis];  // everything right
    } else if (k >= count) {
      position = std::nextafter(points[idx[begin + count - 1]][axis], std::numeric_limits<double>::infinity());
      k = count;
    } else {
      position = 0.5 * (points[idx[begin + k - 1]][axis] + points[idx[begin + k]][axis]);
    }
    Box lb = box, rb = box;
    lb.hi[axis] = position;
    rb.lo[axis] = position;
    const int l = build(idx, begin, begin + k, first, n_left, lb);
    const int r = build(idx, begin + k, end, first + n_left, n - n_left, rb);
    CutNode& c = d.tree[size_t(node)];
    c.axis = axis;
    c.position = position;
    c.left = l;
    c.right = r;
    return node;
  }
};

}  // namespace

Decomposition recursive_coordinate_bisection(const std::vector<Point>& points, int dim, int parts,
                                             std::vector<int>& owner) {
  if (parts < 1) throw std::invalid_argument("recursive_coordinate_bisection: parts must be >= 1");
  if (dim < 1 || dim > 3) throw std::invalid_argument("recursive_coordinate_bisection: dim must be 1, 2 or 3");
  Decomposition d;
  d.dim = dim;
  d.parts = parts;
  d.boxes.assign(size_t(parts), Box{});
  d.counts.assign(size_t(parts), 0);
  owner.assign(points.size(), -1);
  std::vector<std::size_t> idx(points.size());
  std::iota(idx.begin(), idx.end(), std::size_t(0));
  Builder b{points, dim, d, owner};
  b.build(idx, 0, idx.size(), 0, parts, Box{});
  return d;
}

std::vector<long> part_counts(const Decomposition& d, const std::vector<Point>& points) {
  std::vector<long> c(size_t(d.parts), 0);
  for (const Point& x : points) ++c[size_t(d.owner(x))];
  return c;
}

bool rebalance_due(const Decomposition& d, const std::vector<Point>& points, double threshold) {
  Decomposition now = d;
  now.counts = part_counts(d, points);
  return now.imbalance() > threshold;
}

}  // namespace mfsd::distributed
