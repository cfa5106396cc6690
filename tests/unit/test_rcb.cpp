// Recursive coordinate bisection and halo lists (host/distributed/, issue
// 25): every particle owned once, counts balanced to the cut's rounding (and
// a lattice column), the boxes tile space and agree with owner(), and the
// halo of each part is complete against a brute-force pair search and holds
// only other parts' points within r of its box (the box criterion sends
// 1.3x (2-D) to 2.2x (3-D) the points that pairs need: measured here).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "host/distributed/halo.hpp"
#include "host/distributed/rcb.hpp"

using namespace mfsd::distributed;

namespace {

std::vector<Point> random_cloud(std::size_t n, int dim, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Point> p(n, Point{0, 0, 0});
  for (auto& x : p)
    for (int a = 0; a < dim; ++a) x[a] = u(rng) * (a == 0 ? 3.0 : 1.0);  // longest along x
  return p;
}

std::vector<Point> lattice(int nx, int ny, int nz, double dp) {
  std::vector<Point> p;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) p.push_back(Point{(i + 0.5) * dp, (j + 0.5) * dp, nz > 1 ? (k + 0.5) * dp : 0.0});
  return p;
}

void check_tiling(const Decomposition& d, const std::vector<Point>& pts, const std::vector<int>& owner) {
  long total = 0;
  for (long c : d.counts) total += c;
  EXPECT_EQ(total, long(pts.size()));
  for (std::size_t i = 0; i < pts.size(); ++i) {
    ASSERT_GE(owner[i], 0);
    EXPECT_EQ(d.owner(pts[i]), owner[i]) << i;
    // In its own box, in no other box's interior.
    EXPECT_EQ(d.boxes[size_t(owner[i])].distance(pts[i], d.dim), 0.0);
    for (int p = 0; p < d.parts; ++p) {
      if (p == owner[i]) continue;
      bool inside = true;
      for (int a = 0; a < d.dim; ++a)
        inside = inside && pts[i][a] > d.boxes[size_t(p)].lo[a] && pts[i][a] < d.boxes[size_t(p)].hi[a];
      EXPECT_FALSE(inside) << "point " << i << " inside box " << p;
    }
  }
  EXPECT_EQ(part_counts(d, pts), d.counts);
}

}  // namespace

TEST(RecursiveCoordinateBisection, RandomCloudsAnyPartCount) {
  for (int dim : {2, 3})
    for (int parts : {1, 2, 3, 4, 5, 7, 8}) {
      const auto pts = random_cloud(10007, dim, unsigned(17 * dim + parts));
      std::vector<int> owner;
      const Decomposition d = recursive_coordinate_bisection(pts, dim, parts, owner);
      check_tiling(d, pts, owner);
      // Each cut rounds its share to a whole particle: within parts/2 + 1 of the mean.
      const double mean = double(pts.size()) / parts;
      for (long c : d.counts) EXPECT_LE(std::abs(double(c) - mean), parts / 2.0 + 1.0) << dim << "D, " << parts;
      EXPECT_LT(d.imbalance(), 1.001);
      // The first cut is along x, the longest extent.
      if (parts > 1) {
        EXPECT_EQ(d.tree[0].axis, 0);
      }
    }
}

TEST(RecursiveCoordinateBisection, LatticeCutsBetweenColumns) {
  // A 40 x 10 lattice (the oscillating plate's shape) in 4 parts: every cut
  // falls between lattice lines, so equal coordinates never straddle a cut.
  const auto pts = lattice(40, 10, 1, 0.1);
  std::vector<int> owner;
  const Decomposition d = recursive_coordinate_bisection(pts, 2, 4, owner);
  check_tiling(d, pts, owner);
  for (long c : d.counts) EXPECT_EQ(c, 100);
  for (const CutNode& c : d.tree)
    if (c.axis >= 0) {
      const double s = c.position / 0.1;
      EXPECT_NEAR(s, std::round(s), 1e-9) << "cut at " << c.position;  // on a cell boundary
    }
  // 3 parts of a lattice: columns decide, so the imbalance is one column at most.
  const Decomposition d3 = recursive_coordinate_bisection(pts, 2, 3, owner);
  check_tiling(d3, pts, owner);
  for (long c : d3.counts) EXPECT_LE(std::abs(c - 400.0 / 3.0), 10.0 + 1.0);
}

TEST(RecursiveCoordinateBisection, RebalanceWhenTheParticlesMove) {
  auto pts = random_cloud(4000, 2, 5);
  std::vector<int> owner;
  const Decomposition d = recursive_coordinate_bisection(pts, 2, 4, owner);
  EXPECT_FALSE(rebalance_due(d, pts, 1.1));
  // Half of the particles crowd into one corner: part counts skew.
  for (std::size_t i = 0; i < pts.size(); i += 2) pts[i] = Point{0.01 * pts[i][0], 0.01 * pts[i][1], 0};
  EXPECT_TRUE(rebalance_due(d, pts, 1.1));
  const Decomposition again = recursive_coordinate_bisection(pts, 2, 4, owner);
  EXPECT_LT(again.imbalance(), 1.01);
  check_tiling(again, pts, owner);
}

TEST(RecursiveCoordinateBisection, EmptyAndDegenerateSets) {
  std::vector<int> owner;
  const Decomposition e = recursive_coordinate_bisection({}, 3, 4, owner);
  EXPECT_EQ(e.boxes.size(), 4u);
  for (long c : e.counts) EXPECT_EQ(c, 0);
  // All points at one position: one part takes them all, owner() agrees.
  const std::vector<Point> same(10, Point{1, 2, 3});
  const Decomposition s = recursive_coordinate_bisection(same, 3, 3, owner);
  check_tiling(s, same, owner);
  EXPECT_THROW(recursive_coordinate_bisection(same, 3, 0, owner), std::invalid_argument);
}

TEST(HaloLists, CompleteAgainstBruteForce) {
  for (int dim : {2, 3}) {
    const auto pts = random_cloud(dim == 2 ? 3000 : 2000, dim, 99u + unsigned(dim));
    const double radius = dim == 2 ? 0.06 : 0.12;
    std::vector<int> owner;
    const Decomposition d = recursive_coordinate_bisection(pts, dim, 5, owner);
    const auto ghosts = halo_lists(d, pts, owner, radius);
    std::size_t needed_total = 0, sent_total = 0;
    for (int p = 0; p < d.parts; ++p) {
      std::vector<char> needed(pts.size(), 0);
      for (std::size_t i = 0; i < pts.size(); ++i) {
        if (owner[i] != p) continue;
        for (std::size_t j = 0; j < pts.size(); ++j) {
          if (owner[j] == p) continue;
          double d2 = 0;
          for (int a = 0; a < dim; ++a) d2 += (pts[i][a] - pts[j][a]) * (pts[i][a] - pts[j][a]);
          if (d2 < radius * radius) needed[j] = 1;
        }
      }
      const auto& g = ghosts[size_t(p)];
      EXPECT_TRUE(std::is_sorted(g.begin(), g.end()));
      for (std::size_t j = 0; j < pts.size(); ++j)
        if (needed[j]) {
          EXPECT_TRUE(std::binary_search(g.begin(), g.end(), j)) << "part " << p << " misses " << j;
        }
      for (std::size_t j : g) {
        EXPECT_NE(owner[j], p);
        EXPECT_LT(d.boxes[size_t(p)].distance(pts[j], dim), radius);
      }
      needed_total += size_t(std::count(needed.begin(), needed.end(), 1));
      sent_total += g.size();
    }
    // The box criterion sends more than the pairs need (box corners): report it.
    std::printf("halo %dD, 5 parts: %zu ghosts sent for %zu needed (%.2f)\n", dim, sent_total, needed_total,
                double(sent_total) / double(needed_total));
    EXPECT_GE(sent_total, needed_total);
  }
}
