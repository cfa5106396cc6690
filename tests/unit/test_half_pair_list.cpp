// The half-pair list filled straight from the search (issue 24, item 6:
// the set-up never holds the full rows) against the one derived from the
// full list: the same pairs and data bit for bit, the same gradient sums and
// bandwidth; the moment matrices the search leaves give the same B0 as the
// full rows; and the half loop's deformation rate of a linear field from it is
// exact (seed 000 eq. 22).
#include <gtest/gtest.h>

#include <random>

#include "kernels/tlsph/correction_matrix.hpp"
#include "kernels/tlsph/deformation_rate_half.hpp"
#include "particle_fixture.hpp"

using namespace mfsd;

namespace {

template <int D>
std::vector<double> jittered_volumes(size_t n, double dp) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.6, 1.4);
  std::vector<double> v(n);
  for (auto& x : v) x = u(rng) * std::pow(dp, D);
  return v;
}

template <class T>
void expect_same(const DeviceVector<Cpu, T>& a, const DeviceVector<Cpu, T>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  EXPECT_EQ(0, std::memcmp(raw(a), raw(b), a.size() * sizeof(T))) << what;
}

template <int D, class Real>
void half_only_equals_derived(bool beta) {
  const int n[3] = {11, 9, 7};
  const double dp = 0.01;
  const auto x = test::lattice<D>(n, dp, 0.2, 5);
  const auto vd = jittered_volumes<D>(x.size(), dp);
  const std::vector<Real> vol(vd.begin(), vd.end());
  // Two bodies, so that the search's per-body grids are exercised.
  std::vector<int> body(x.size(), 0);
  for (size_t i = x.size() / 2; i < x.size(); ++i) body[i] = 1;
  test::Fixture<D, Real> full(x, dp, 1.3 * dp, true, body, beta, {}, vol, true, false);
  test::Fixture<D, Real> half(x, dp, 1.3 * dp, true, body, beta, {}, vol, true, true);
  ASSERT_TRUE(build_half_pair_list(full.pairs, Index(x.size())));

  EXPECT_FALSE(half.pairs.full_rows);
  EXPECT_TRUE(half.pairs.neighbor.empty());
  EXPECT_TRUE(half.pairs.grad.empty());
  EXPECT_EQ(half.pairs.pairs(), full.pairs.pairs());
  EXPECT_EQ(half.pairs.bandwidth, full.pairs.bandwidth);
  EXPECT_GT(half.pairs.bandwidth, 0);
  expect_same(half.pairs.offsets, full.pairs.offsets, "offsets (the neighbour counts)");
  expect_same(half.pairs.half_offsets, full.pairs.half_offsets, "half offsets");
  expect_same(half.pairs.half_neighbor, full.pairs.half_neighbor, "half neighbours");
  expect_same(half.pairs.half_grad, full.pairs.half_grad, "half gradients");
  expect_same(half.pairs.half_stretch, full.pairs.half_stretch, "half stretches");
  expect_same(half.pairs.half_beta, full.pairs.half_beta, "half beta");
  expect_same(half.pairs.gradient_sum, full.pairs.gradient_sum, "gradient sums");
  EXPECT_EQ(2 * half.pairs.half_grad.size(), size_t(full.pairs.pairs()));  // each pair once
  // The particles were reordered alike.
  EXPECT_EQ(half.template host<Index>(field::id), full.template host<Index>(field::id));
  expect_same(half.particles.template buffer<Mat<D, Real>>(field::correction_matrix),
              full.particles.template buffer<Mat<D, Real>>(field::correction_matrix), "moment matrices");
}

TEST(HalfPairList, FilledFromTheSearchEqualsTheDerivedOne3D) { half_only_equals_derived<3, double>(false); }
TEST(HalfPairList, FilledFromTheSearchEqualsTheDerivedOne2DWithBeta) { half_only_equals_derived<2, double>(true); }
TEST(HalfPairList, FilledFromTheSearchEqualsTheDerivedOne3DFloat) { half_only_equals_derived<3, float>(true); }

TEST(HalfPairList, NeedsTheReorderingSearch) {
  const int n[3] = {5, 5, 5};
  const auto x = test::lattice<3>(n, 0.01, 0.0, 1);
  EXPECT_THROW((test::Fixture<3, double>(x, 0.01, 0.013, false, {}, false, {}, {}, true, true)), std::logic_error);
}

// B0 from the search's moments (what the solver uses) against B0 from the
// full rows (CorrectionMatrixFunctor), with unequal volumes and a surface.
template <int D>
void moments_give_the_rows_b0() {
  const int n[3] = {10, 8, 6};
  const double dp = 0.01;
  const auto x = test::lattice<D>(n, dp, 0.2, 7);
  const auto vd = jittered_volumes<D>(x.size(), dp);
  test::Fixture<D, double> f(x, dp, 1.15 * dp, true, {}, false, {}, vd, true, false);
  const size_t m = x.size();
  DeviceVector<Cpu, Mat<D, double>> rows_B(m);
  DeviceVector<Cpu, unsigned char> rows_flag(m), flag(m);
  parallel_for<Cpu>(Index(m), CorrectionMatrixFunctor<D, double>{f.pairs.view(), raw(rows_B), raw(rows_flag), 0.1});
  auto* B = f.particles.template get<Mat<D, double>>(field::correction_matrix);
  parallel_for<Cpu>(Index(m), CorrectionFromMomentFunctor<D, double>{B, raw(flag), 0.1});
  const auto a = to_host<Cpu>(rows_B);
  const auto b = f.template host<Mat<D, double>>(field::correction_matrix);
  double worst = 0, scale = 0;
  for (size_t i = 0; i < m; ++i)
    for (int r = 0; r < D; ++r)
      for (int c = 0; c < D; ++c) {
        worst = std::max(worst, std::abs(a[i].m[r][c] - b[i].m[r][c]));
        scale = std::max(scale, std::abs(a[i].m[r][c]));
      }
  EXPECT_GT(scale, 0.5);
  EXPECT_LT(worst / scale, 1e-13);  // the same sum in another order of operations
  EXPECT_EQ(to_host<Cpu>(rows_flag), to_host<Cpu>(flag));
}

TEST(HalfPairList, SearchMomentsGiveTheRowsCorrection2D) { moments_give_the_rows_b0<2>(); }
TEST(HalfPairList, SearchMomentsGiveTheRowsCorrection3D) { moments_give_the_rows_b0<3>(); }

// The half loop's rate of a linear field, on the list filled from the
// search, with B0 from its moments: exact (seed 000 eq. 22).
TEST(HalfPairList, HalfLoopRateOfALinearFieldIsExact) {
  constexpr int D = 3;
  const int n[3] = {12, 8, 6};
  const double dp = 0.01;
  const auto x = test::lattice<D>(n, dp, 0.15, 3);
  const auto vd = jittered_volumes<D>(x.size(), dp);
  test::Fixture<D, double> f(x, dp, 1.2 * dp, true, {}, false, {}, vd, true, true);
  const Index m = Index(x.size());
  DeviceVector<Cpu, unsigned char> flag(static_cast<size_t>(m));
  auto* B = f.particles.template get<Mat<D, double>>(field::correction_matrix);
  parallel_for<Cpu>(m, CorrectionFromMomentFunctor<D, double>{B, raw(flag), 0.1});
  Mat<D, double> L;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) L.m[a][b] = 0.3 * (a + 1) - 0.2 * b + (a == b ? 0.5 : 0.0);
  const auto X = f.template host<Vec<D, double>>(field::reference_position);
  std::vector<Vec<D, double>> v(X.size());
  for (size_t i = 0; i < X.size(); ++i) v[i] = L * X[i] + Vec<D, double>{{1.0, -2.0, 0.5}};
  DeviceVector<Cpu, Vec<D, double>> vel;
  from_host<Cpu>(v, vel);
  DeviceVector<Cpu, Mat<D, double>> rate(X.size());
  std::vector<Mat<D, double>> workspace;
  const DeformationRateHalfFunctor<D, double> h{
      {f.pairs.half_view(), raw(vel), f.particles.template get<double>(field::volume)}, B, raw(rate)};
  half_pair_for(Cpu{}, Index(0), m, f.pairs.bandwidth, Mat<D, double>::zero(), raw(rate), workspace, h,
                [&](Index i, const Mat<D, double>& t) { h.finish(i, t); });
  double worst = 0;
  for (const auto& r : to_host<Cpu>(rate))
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) worst = std::max(worst, std::abs(r.m[a][b] - L.m[a][b]));
  EXPECT_LT(worst, 1e-11);
}

}  // namespace
