// The decomposition of moved particles (host/distributed/migration.hpp, issue
// 25): below the imbalance threshold the cuts stay and the owners follow the
// cut tree; above it the moved points are bisected again; each part's
// holdings (owned and ghosts) contain every partner within the radius of its
// owned points (brute force); a decomposition survives its numbers (the
// checkpoints of migrated runs).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "host/distributed/migration.hpp"

using namespace mfsd::distributed;

namespace {

// A 40 x 10 lattice, spacing 1, in 2-D.
std::vector<Point> lattice() {
  std::vector<Point> p;
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 40; ++i) p.push_back({i + 0.5, j + 0.5, 0.0});
  return p;
}

void expect_complete(const Repartition& r, const std::vector<Point>& x, double radius) {
  const auto held = holdings(r);
  for (int p = 0; p < r.decomposition.parts; ++p) {
    const std::set<long> here(held[size_t(p)].begin(), held[size_t(p)].end());
    EXPECT_TRUE(std::is_sorted(held[size_t(p)].begin(), held[size_t(p)].end()));
    for (size_t i = 0; i < x.size(); ++i) {
      if (r.owner[i] != p) continue;
      EXPECT_TRUE(here.count(long(i)));
      for (size_t j = 0; j < x.size(); ++j) {
        const double dx = x[i][0] - x[j][0], dy = x[i][1] - x[j][1];
        if (dx * dx + dy * dy < radius * radius) EXPECT_TRUE(here.count(long(j))) << "part " << p << " misses " << j;
      }
    }
  }
}

}  // namespace

TEST(Migration, SmallMotionKeepsTheCuts) {
  std::vector<Point> x = lattice();
  std::vector<int> owner;
  const Decomposition d = recursive_coordinate_bisection(x, 2, 4, owner);
  for (auto& p : x)  // all move a little; half of the column left of the first cut crosses it
    p[0] += (p[0] == 9.5 && p[1] < 5) ? 1.0 : 0.3;
  const Repartition r = repartition(d, x, 2.5);
  EXPECT_FALSE(r.rebalanced);
  ASSERT_EQ(r.decomposition.tree.size(), d.tree.size());
  for (size_t k = 0; k < d.tree.size(); ++k) EXPECT_EQ(r.decomposition.tree[k].position, d.tree[k].position);
  long moved = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(r.owner[i], d.owner(x[i]));
    moved += r.owner[i] != owner[i];
  }
  EXPECT_EQ(moved, 5);  // the half column changed owner
  EXPECT_LE(r.decomposition.imbalance(), kRebalanceThreshold);
  expect_complete(r, x, 2.5);
}

TEST(Migration, CrowdedPartsAreBisectedAgain) {
  std::vector<Point> x = lattice();
  std::vector<int> owner;
  const Decomposition d = recursive_coordinate_bisection(x, 2, 4, owner);
  for (auto& p : x) p[0] *= 0.5;  // squeezed into the left half: two parts hold everything
  EXPECT_GT(rebalance_due(d, x, kRebalanceThreshold), 0);
  const Repartition r = repartition(d, x, 2.5);
  EXPECT_TRUE(r.rebalanced);
  for (long c : r.decomposition.counts) EXPECT_EQ(c, 100);
  expect_complete(r, x, 2.5);
}

TEST(Migration, DecompositionSurvivesItsNumbers) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  std::vector<Point> x(500);
  for (auto& p : x) p = {u(random), u(random), u(random)};
  std::vector<int> owner;
  const Decomposition d = recursive_coordinate_bisection(x, 3, 5, owner);
  const Decomposition e = decomposition_from(to_numbers(d));
  EXPECT_EQ(e.dim, 3);
  EXPECT_EQ(e.parts, 5);
  EXPECT_EQ(e.counts, d.counts);
  for (int k = 0; k < 2000; ++k) {
    const Point p{u(random) * 1.4 - 2, u(random) * 1.4 - 2, u(random) * 1.4 - 2};
    EXPECT_EQ(e.owner(p), d.owner(p));
  }
  for (int p = 0; p < 5; ++p)
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(e.boxes[size_t(p)].lo[size_t(a)], d.boxes[size_t(p)].lo[size_t(a)]);
      EXPECT_EQ(e.boxes[size_t(p)].hi[size_t(a)], d.boxes[size_t(p)].hi[size_t(a)]);
    }
  EXPECT_THROW(decomposition_from({2.0, 4.0}), std::runtime_error);
}
