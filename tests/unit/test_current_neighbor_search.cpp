// The current-configuration search of ULSPH (host/neighbors/cell_list_search.hpp
// with kernels/ulsph/current_pair_fill.hpp) against a brute-force O(N^2)
// oracle, in float and double, with and without reordering: the same
// neighbour sets by particle id after the particles have moved (a search on
// a displaced, sheared lattice of two overlapping bodies), the re-index hook
// given the permutation that the fields were moved by, the pair data
// grad = V_j dW e and stretch = V_j dW / r with V = m / rho, and the refresh
// of the kept pairs at new positions equal to a new fill.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "host/backend/cpu.hpp"
#include "host/neighbors/cell_list_search.hpp"
#include "kernels/ulsph/current_pair_fill.hpp"

using namespace mfsd;

namespace {

template <int D, class Real>
void check(bool reorder) {
  const double dp = 0.1, h = 1.3 * dp;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.3 * dp, 0.3 * dp);
  std::vector<Vec<D, Real>> x;
  std::vector<int> body;
  for (int b = 0; b < 2; ++b)
    for (int k = 0; k < (D == 2 ? 150 : 400); ++k) {
      const int n = D == 2 ? 15 : 10;
      Vec<D, Real> p;
      int rest = k;
      for (int a = 0; a < D; ++a, rest /= n) p.v[a] = Real(dp * (rest % n) + jitter(rng) + 0.45 * b);
      p.v[0] += Real(0.4 * p.v[D - 1]);  // sheared: the current configuration is not the lattice
      x.push_back(p);
      body.push_back(b);
    }
  const Index n = Index(x.size());
  ParticleSet<Cpu> set(n);
  std::vector<Index> id(x.size());
  std::vector<Real> mass(x.size()), density(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    id[i] = Index(i);
    mass[i] = Real(1 + 0.01 * double(i % 7));
    density[i] = Real(1000 + double(i % 5));
  }
  set.add<Index>(field::id);
  from_host<Cpu>(id, set.buffer<Index>(field::id));
  set.add<int>(field::body);
  from_host<Cpu>(body, set.buffer<int>(field::body));
  set.add<Vec<D, Real>>(field::current_position);
  from_host<Cpu>(x, set.buffer<Vec<D, Real>>(field::current_position));
  set.add<Real>(field::mass);
  from_host<Cpu>(mass, set.buffer<Real>(field::mass));
  set.add<Real>(field::density);
  from_host<Cpu>(density, set.buffer<Real>(field::density));

  const Index half = n / 2;
  const std::vector<BodySearch> bodies{{{0, half}, h}, {{half, n}, h}};
  std::vector<double> lo(2 * D, 1e30), hi(2 * D, -1e30);
  for (size_t i = 0; i < x.size(); ++i)
    for (int a = 0; a < D; ++a) {
      const size_t k = size_t(body[i]) * D + size_t(a);
      lo[k] = std::min(lo[k], double(x[i].v[a]));
      hi[k] = std::max(hi[k], double(x[i].v[a]));
    }
  CellIndex<Cpu, D, Real> cells;
  std::vector<Index> seen_order;
  sort_into_cells<Cpu, D, Real>(set, field::current_position, body_cell_grids<D, Real>(bodies, lo, hi), reorder, cells,
                                [&](const DeviceVector<Cpu, Index>& order) { seen_order = to_host<Cpu>(order); });
  const auto ids = to_host<Cpu>(set.buffer<Index>(field::id));
  if (reorder) {
    ASSERT_EQ(seen_order.size(), x.size());
    EXPECT_EQ(seen_order, ids);  // the hook saw the permutation the fields moved by
    EXPECT_FALSE(std::is_sorted(ids.begin(), ids.end()));
  } else {
    EXPECT_TRUE(seen_order.empty());
  }
  CellNeighborhood<D, Real> hood = cell_neighborhood<Cpu, D, Real>(set, field::current_position, cells);
  DeviceVector<Cpu, Index> count;
  DeviceVector<Cpu, PairIndex> offsets;
  const PairIndex pairs = count_pairs<Cpu, D, Real>(hood, bodies, n, count, offsets);
  DeviceVector<Cpu, Index> neighbor(size_t(pairs) + kPairPrefetchDistance, 0);
  const size_t np = size_t(pairs), nn = size_t(n);
  DeviceVector<Cpu, Vec<D, Real>> grad(np), grad2(np), sum(nn), sum2(nn);
  DeviceVector<Cpu, Real> stretch(np), stretch2(np);
  const auto kernel = WendlandC2<D, Real>::make(Real(h));
  hood.radius2 = support_radius2<Real>(h);
  parallel_for<Cpu>(
      n, ulsph::CurrentPairFillFunctor<D, Real>{hood, kernel, set.get<Real>(field::mass), set.get<Real>(field::density),
                                                raw(offsets), raw(neighbor), raw(grad), raw(stretch), raw(sum)});
  const auto off = to_host<Cpu>(offsets);
  const auto nb = to_host<Cpu>(neighbor);
  const auto g = to_host<Cpu>(grad);
  const auto st = to_host<Cpu>(stretch);
  const double tol = std::is_same<Real, float>::value ? 2e-4 : 1e-11;
  size_t total = 0;
  for (Index k = 0; k < n; ++k) {
    const size_t i = size_t(ids[size_t(k)]);
    std::set<size_t> oracle, found;
    for (size_t j = 0; j < x.size(); ++j)
      if (j != i && body[j] == body[i] && squared_norm(x[i] - x[j]) < support_radius2<Real>(h)) oracle.insert(j);
    for (PairIndex p = off[size_t(k)]; p < off[size_t(k) + 1]; ++p) {
      const size_t j = size_t(ids[size_t(nb[size_t(p)])]);
      found.insert(j);
      const Vec<D, Real> d = x[i] - x[j];
      const double r = double(norm(d));
      const double w = double(mass[j]) / double(density[j]) * double(kernel.dW(Real(r))) / r;
      EXPECT_NEAR(double(st[size_t(p)]), w, tol * std::abs(w));
      for (int a = 0; a < D; ++a) EXPECT_NEAR(double(g[size_t(p)].v[a]), double(d.v[a]) * w, tol * std::abs(w) * h);
    }
    EXPECT_EQ(found, oracle) << "particle " << i;
    total += oracle.size();
  }
  EXPECT_EQ(size_t(pairs), total);
  EXPECT_GT(total, x.size() * (D == 2 ? 8 : 20));

  // The refresh of the kept pairs at the same positions is the fill again.
  DeviceVector<Cpu, Vec<D, Real>> zero(size_t(n), Vec<D, Real>::zero()), x2(static_cast<size_t>(n));
  DeviceVector<Cpu, Real> volume(static_cast<size_t>(n));
  parallel_for<Cpu>(n, ulsph::PositionVolumeFunctor<D, Real>{set.get<Vec<D, Real>>(field::current_position), raw(zero),
                                                             set.get<Real>(field::mass), set.get<Real>(field::density),
                                                             raw(x2), raw(volume)});
  for (const auto& b : bodies)
    parallel_for<Cpu>(b.range.begin, b.range.end,
                      ulsph::PairRefreshFunctor<D, Real>{raw(x2), raw(volume), kernel, raw(offsets), raw(neighbor),
                                                         raw(grad2), raw(stretch2), raw(sum2)});
  const auto g2 = to_host<Cpu>(grad2);
  const auto st2 = to_host<Cpu>(stretch2);
  for (size_t p = 0; p < size_t(pairs); ++p) {
    EXPECT_NEAR(double(st2[p]), double(st[p]), tol * std::abs(double(st[p])));
    for (int a = 0; a < D; ++a) EXPECT_NEAR(double(g2[p].v[a]), double(g[p].v[a]), tol * std::abs(double(st[p])) * h);
  }
}

}  // namespace

TEST(CurrentNeighborSearch, MatchesOracle2DDoubleReordered) { check<2, double>(true); }
TEST(CurrentNeighborSearch, MatchesOracle2DFloatNotReordered) { check<2, float>(false); }
TEST(CurrentNeighborSearch, MatchesOracle3DDoubleNotReordered) { check<3, double>(false); }
TEST(CurrentNeighborSearch, MatchesOracle3DFloatReordered) { check<3, float>(true); }
