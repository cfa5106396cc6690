// The 3-D genog force's second pass visits only the pairs its first pass
// recorded (kernels/tlsph/genog_active_pairs.hpp, issue 24 item 2). Checked:
// the record's own rules (the looser threshold, ascending order, overflow),
// and the force of a strongly disordered state, where particles have from
// none to many active pairs, against a direct sum over every
// pair (the oracle), on both CPU paths (packed record and scalar): particles
// without an active pair, with their active pairs recorded, and with rows too
// long for the record.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "kernels/tlsph/acceleration.hpp"
#include "particle_fixture.hpp"

using namespace mfsd;

TEST(GenogActivePairs, RecordsWhatTheSecondPassCanAcceptInOrder) {
  using Record = GenogActivePairs<double>;
  const double t2 = 0.05 * 0.05;
  // A row as the first pass records it: (|h|^2, |g|^2) of each pair.
  auto visited = [](const std::vector<std::pair<double, double>>& row) {
    Record r;
    for (size_t k = 0; k < row.size(); ++k)
      r.put(PairIndex(k), row[k].first - Record::loose_threshold2 * row[k].second);
    std::vector<PairIndex> k;
    r.for_each(PairIndex(row.size()), [&](PairIndex p) { k.push_back(p); });
    return k;
  };
  EXPECT_EQ(visited({{0.5 * t2, 1.0},           // clearly inactive
                     {t2 * (1 + 1e-9), 1.0},    // active
                     {t2 * (1 - 1e-6), 1.0},    // just below the threshold: visited (the margin)
                     {t2 * (1 - 1e-2), 1.0},    // below the margin: not visited
                     {4.0, 1.0}}),              // far above
            (std::vector<PairIndex>{1, 2, 4}));
  // A full row: every third pair active.
  const int cap = Record::capacity;
  std::vector<std::pair<double, double>> row;
  std::vector<PairIndex> every_third;
  for (int k = 0; k < cap; ++k) {
    row.push_back({k % 3 == 0 ? 1.0 : 0.0, 1.0});
    if (k % 3 == 0) every_third.push_back(k);
  }
  EXPECT_EQ(visited(row), every_third);
  EXPECT_FALSE(Record::overflowed(cap));
  EXPECT_TRUE(Record::overflowed(cap + 1));
}

namespace {

Mat<3, double> random_matrix(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Mat<3, double> m;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) m.m[a][b] = u(rng);
  return m;
}

}  // namespace

TEST(GenogActivePairs, SecondPassOverTheRecordEqualsTheDirectSum) {
  // h = 2.4 dp: interior rows are longer than the record's capacity (the
  // full second pass), rows at the corners shorter (the recorded one).
  const int n[3] = {9, 9, 9};
  const double dp = 0.1, h = 2.4 * dp;
  const auto x = test::lattice<3>(n, dp, 0.1, 3);
  for (const GenogLimiter limiter : {GenogLimiter::capped, GenogLimiter::paper}) {
    test::Fixture<3, double> fx(x, dp, h, false, {}, limiter == GenogLimiter::paper);
    const ReferencePairs<3, double> pairs = fx.pairs.view();
    const Index N = Index(x.size());
    // A disordered state: F^{-1} = I + noise, u with a non-affine part, both
    // growing along x, so that |e_hat| spreads across the 0.05 threshold.
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<Mat<3, double>> Q(N), S(N), Finv(N);
    std::vector<Vec<3, double>> disp(N), a(N), v(N, Vec<3, double>::zero());
    std::vector<GenogNeighborRecord<double>> record(size_t(N) + kPairPrefetchDistance);
    for (Index i = 0; i < N; ++i) {
      Q[i] = random_matrix(rng, 1e6);
      S[i] = random_matrix(rng, 1e5);
      const double s = x[size_t(i)].v[0] / (n[0] * dp);  // 0 to 1
      Finv[i] = Mat<3, double>::identity() + random_matrix(rng, 0.12 * s);
      for (int c = 0; c < 3; ++c) disp[i].v[c] = 0.1 * s * dp * u(rng);
      record[size_t(i)].set(Q[i], Finv[i], disp[i]);
    }
    GenogWeight<double> weight{limiter, 8.0 * 3, GenogForm::vector};
    const double inv_rho0 = 1.0 / 1100;
    // The oracle: every pair, in order, with the test of the second pass.
    int none = 0, recorded = 0, overflowed = 0;
    std::vector<Vec<3, double>> expected(N);
    for (Index i = 0; i < N; ++i) {
      Vec<3, double> sum = Vec<3, double>::zero(), corrections = Vec<3, double>::zero();
      int active = 0;
      for (PairIndex p = pairs.offsets[i]; p < pairs.offsets[i + 1]; ++p) {
        const Index j = pairs.neighbor[p];
        const Vec<3, double> g = pairs.grad[p];
        sum += Q[j] * g;
        const Vec<3, double> hv = scaled_e_hat(Finv[i], Finv[j], disp[i], disp[j], g, pairs.stretch[p]);
        const double h2 = squared_norm(hv), g2 = squared_norm(g);
        if (h2 > 0.05 * 0.05 * g2) {
          ++active;
          const double phi = weight(std::sqrt(h2 / g2), pairs.beta ? pairs.beta[p] : 0.0);
          corrections += (S[i] + S[j]) * weight.correction(g, hv, phi, g2);
        }
      }
      const PairIndex row = pairs.offsets[i + 1] - pairs.offsets[i];
      (active == 0 ? none : row <= GenogActivePairs<double>::capacity ? recorded : overflowed)++;
      expected[i] = (Q[i] * pairs.gradient_sum[i] + sum + corrections) * inv_rho0;
    }
    EXPECT_GT(none, 0);
    EXPECT_GT(recorded, 0);
    EXPECT_GT(overflowed, 0);
    for (const bool packed : {true, false}) {
      SCOPED_TRACE(packed ? "packed record" : "scalar");
      AccelerationFunctor<3, double, HourglassGenog> f{pairs,
                                                       Q.data(),
                                                       nullptr,
                                                       S.data(),
                                                       Finv.data(),
                                                       disp.data(),
                                                       packed ? record.data() : nullptr,
                                                       inv_rho0,
                                                       Vec<3, double>::zero(),
                                                       weight,
                                                       0.0,
                                                       a.data(),
                                                       v.data()};
      for (Index i = 0; i < N; ++i) f(i);
      double worst = 0, scale = 0;
      for (Index i = 0; i < N; ++i) {
        worst = std::max(worst, norm(a[i] - expected[i]));
        scale = std::max(scale, norm(expected[i]));
      }
      EXPECT_LT(worst, 1e-12 * scale) << "a pair's correction is missing or extra";
    }
  }
}
