// Reference neighbour list (cell list + sort-based reordering + CSR) against
// a brute-force O(N^2) oracle: same neighbour sets by particle id, same
// per-pair data, fields carried consistently by the reordering, and no pairs
// across bodies.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "particle_fixture.hpp"

using namespace mfsd;

namespace {

template <int D>
void check_against_oracle(bool reorder, double jitter) {
  const int n[3] = {13, 9, 7};
  const double dp = 0.1, h = 1.15 * dp;
  auto x = test::lattice<D>(n, dp, jitter, 7);
  // Second body: the same lattice shifted so that it overlaps the first one.
  const size_t n0 = x.size();
  auto x2 = test::lattice<D>(n, dp, jitter, 8);
  for (auto& p : x2) p.v[0] += 0.35;
  x.insert(x.end(), x2.begin(), x2.end());
  std::vector<int> body(x.size(), 0);
  std::fill(body.begin() + long(n0), body.end(), 1);

  test::Fixture<D, double> f(x, dp, h, reorder, body, true);
  const auto ids = f.template host<Index>(field::id);
  const auto xs = f.template host<Vec<D, double>>(field::reference_position);
  const auto bs = f.template host<int>(field::body);
  const auto offsets = to_host<Cpu>(f.pairs.offsets);
  const auto nb = to_host<Cpu>(f.pairs.neighbor);
  const auto grad = to_host<Cpu>(f.pairs.grad);
  const auto stretch = to_host<Cpu>(f.pairs.stretch);
  const auto gradient_sum = to_host<Cpu>(f.pairs.gradient_sum);
  const auto beta = to_host<Cpu>(f.pairs.beta);
  const auto kernel = WendlandC2<D, double>::make(h);

  // Fields travel together: the particle now at k is the original ids[k].
  for (size_t k = 0; k < x.size(); ++k) {
    for (int a = 0; a < D; ++a) EXPECT_EQ(xs[k].v[a], x[size_t(ids[k])].v[a]);
    EXPECT_EQ(bs[k], body[size_t(ids[k])]);
  }
  // Bodies stay contiguous.
  for (size_t k = 1; k < bs.size(); ++k) EXPECT_LE(bs[k - 1], bs[k]);
  if (reorder) {
    EXPECT_FALSE(std::is_sorted(ids.begin(), ids.end()));
  }

  size_t total = 0;
  for (size_t k = 0; k < x.size(); ++k) {
    const size_t i = size_t(ids[k]);
    std::set<size_t> oracle;
    for (size_t j = 0; j < x.size(); ++j)
      if (j != i && body[j] == body[i] && norm(x[i] - x[j]) < 2 * h) oracle.insert(j);
    std::set<size_t> found;
    Vec<D, double> sum = Vec<D, double>::zero();
    for (auto p = offsets[k]; p < offsets[k + 1]; ++p) {
      const size_t j = size_t(ids[size_t(nb[size_t(p)])]);
      found.insert(j);
      // grad = V0_j dW/dr e0, stretch = V0_j dW/dr / r0, with e0 = (X_i - X_j)/r0.
      const double r = norm(x[i] - x[j]);
      const double dwv = std::pow(dp, D) * kernel.dW(r);
      const double scale = std::abs(dwv) / r + 1e-300;
      for (int a = 0; a < D; ++a) {
        EXPECT_NEAR(grad[size_t(p)].v[a], dwv * (x[i].v[a] - x[j].v[a]) / r, 1e-12 * scale);
        sum.v[a] += dwv * (x[i].v[a] - x[j].v[a]) / r;
      }
      EXPECT_NEAR(stretch[size_t(p)], dwv / r, 1e-12 * scale);
      EXPECT_NEAR(beta[size_t(p)], kernel.W(r) / kernel.W(0), 1e-14);
    }
    for (int a = 0; a < D; ++a) EXPECT_NEAR(gradient_sum[k].v[a], sum.v[a], 1e-9 * std::pow(dp, D - 1));
    EXPECT_EQ(found, oracle) << "particle " << i;
    total += oracle.size();
  }
  EXPECT_EQ(size_t(f.pairs.pairs()), total);
}

}  // namespace

TEST(NeighborSearch, MatchesOracle2DReordered) { check_against_oracle<2>(true, 0.2); }
TEST(NeighborSearch, MatchesOracle2DNotReordered) { check_against_oracle<2>(false, 0.2); }
TEST(NeighborSearch, MatchesOracle3DReordered) { check_against_oracle<3>(true, 0.3); }
TEST(NeighborSearch, MatchesOracle3DNotReordered) { check_against_oracle<3>(false, 0.0); }

TEST(NeighborSearch, FullSupportCountOnLattice) {
  // Interior particle of a 3-D lattice with h = 1.15 dp (cut-off 2.3 dp):
  // lattice points with |k| < 2.3, k != 0: 1 + 6 + 12 + 8 + 6 + 24 + 24 ... = 56.
  const int n[3] = {9, 9, 9};
  const auto x = test::lattice<3>(n, 1.0, 0.0, 1);
  test::Fixture<3, double> f(x, 1.0, 1.15, true);
  const auto ids = f.template host<Index>(field::id);
  const auto offsets = to_host<Cpu>(f.pairs.offsets);
  int expected = 0;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j)
      for (int k = -2; k <= 2; ++k)
        if ((i || j || k) && i * i + j * j + k * k < 2.3 * 2.3) ++expected;
  for (size_t k = 0; k < ids.size(); ++k)
    if (ids[k] == 4 + 9 * 4 + 81 * 4) {
      EXPECT_EQ(offsets[k + 1] - offsets[k], expected);
    }
}

// Two small bodies 1,000 body-lengths apart (issue 20, item 7): each body has
// its own grid, so the search holds cells for the bodies only (a grid over the
// union box would need 1000^3 times more), and the pairs are the oracle's.
TEST(NeighborSearch, BodiesFarApartCostOnlyTheirOwnCells) {
  const int n[3] = {6, 5, 4};
  const double dp = 0.1, h = 1.15 * dp, length = 0.6;
  auto x = test::lattice<3>(n, dp, 0.1, 3);
  const size_t n0 = x.size();
  auto x2 = test::lattice<3>(n, dp, 0.1, 4);
  for (auto& p : x2)
    for (int a = 0; a < 3; ++a) p.v[a] += 1000 * length;
  x.insert(x.end(), x2.begin(), x2.end());
  std::vector<int> body(x.size(), 0);
  std::fill(body.begin() + long(n0), body.end(), 1);
  test::Fixture<3, double> f(x, dp, h, true, body);
  // Each body's box is at most 3 x 3 x 2 cells of edge 2h = 0.23.
  EXPECT_LE(f.pairs.cells, 2 * 3 * 3 * 2);
  const auto ids = f.template host<Index>(field::id);
  const auto offsets = to_host<Cpu>(f.pairs.offsets);
  const auto nb = to_host<Cpu>(f.pairs.neighbor);
  for (size_t k = 0; k < x.size(); ++k) {
    const size_t i = size_t(ids[k]);
    std::set<size_t> oracle, found;
    for (size_t j = 0; j < x.size(); ++j)
      if (j != i && body[j] == body[i] && norm(x[i] - x[j]) < 2 * h) oracle.insert(j);
    for (PairIndex p = offsets[k]; p < offsets[k + 1]; ++p) found.insert(size_t(ids[size_t(nb[size_t(p)])]));
    EXPECT_EQ(found, oracle) << "particle " << i;
  }
}
