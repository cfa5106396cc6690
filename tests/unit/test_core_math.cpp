// kernels/core: Vec/Mat operations and the symmetric eigen-decomposition,
// in float and double, 2-D and 3-D, against closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "kernels/core/eigen_symmetric.hpp"
#include "kernels/core/mat.hpp"

using namespace mfsd;

template <class T>
struct Tol;
template <>
struct Tol<float> {
  static constexpr double value = 2e-5;
};
template <>
struct Tol<double> {
  static constexpr double value = 1e-12;
};

template <class P>
class CoreMath : public ::testing::Test {};
template <int D_, class Real_>
struct Param {
  static constexpr int D = D_;
  using Real = Real_;
};
using Params = ::testing::Types<Param<2, float>, Param<2, double>, Param<3, float>, Param<3, double>>;
TYPED_TEST_SUITE(CoreMath, Params);

template <int D, class Real>
Mat<D, Real> random_matrix(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Mat<D, Real> A;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) A.m[a][b] = Real(u(rng) + (a == b ? 2.0 : 0.0));
  return A;
}

TYPED_TEST(CoreMath, InverseTimesMatrixIsIdentity) {
  constexpr int D = TypeParam::D;
  using Real = typename TypeParam::Real;
  std::mt19937 rng(1);
  for (int trial = 0; trial < 50; ++trial) {
    const Mat<D, Real> A = random_matrix<D, Real>(rng);
    const Mat<D, Real> I = A * inverse(A);
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) EXPECT_NEAR(double(I.m[a][b]), a == b ? 1.0 : 0.0, 50 * Tol<Real>::value);
  }
}

TYPED_TEST(CoreMath, DeterminantIsMultiplicativeAndMatchesCofactors) {
  constexpr int D = TypeParam::D;
  using Real = typename TypeParam::Real;
  std::mt19937 rng(2);
  const Mat<D, Real> A = random_matrix<D, Real>(rng), B = random_matrix<D, Real>(rng);
  EXPECT_NEAR(double(det(A * B)), double(det(A)) * double(det(B)),
              50 * Tol<Real>::value * std::abs(double(det(A * B))));
  // Known value: diag(2, 3[, 4]) with one off-diagonal entry (upper triangular).
  Mat<D, Real> T = Mat<D, Real>::zero();
  for (int a = 0; a < D; ++a) T.m[a][a] = Real(a + 2);
  T.m[0][D - 1] = Real(7);
  EXPECT_NEAR(double(det(T)), D == 2 ? 6.0 : 24.0, 1e-6);
  EXPECT_NEAR(double(det(transpose(A))), double(det(A)), 10 * Tol<Real>::value);
}

TYPED_TEST(CoreMath, ProductsTraceDeviatorAndContractions) {
  constexpr int D = TypeParam::D;
  using Real = typename TypeParam::Real;
  std::mt19937 rng(3);
  const Mat<D, Real> A = random_matrix<D, Real>(rng), B = random_matrix<D, Real>(rng);
  const Mat<D, Real> AB = A * B, ABt = mul_transposed(A, B), ref = A * transpose(B);
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) {
      double s = 0;
      for (int k = 0; k < D; ++k) s += double(A.m[a][k]) * double(B.m[k][b]);
      EXPECT_NEAR(double(AB.m[a][b]), s, 10 * Tol<Real>::value);
      EXPECT_NEAR(double(ABt.m[a][b]), double(ref.m[a][b]), 10 * Tol<Real>::value);
      EXPECT_EQ(transpose(A).m[a][b], A.m[b][a]);
    }
  EXPECT_NEAR(double(trace(deviator(A))), 0.0, 10 * Tol<Real>::value);
  EXPECT_NEAR(double(trace(A * B)), double(ddot(A, transpose(B))), 10 * Tol<Real>::value);
  Vec<D, Real> x, y;
  for (int a = 0; a < D; ++a) x.v[a] = Real(a + 1), y.v[a] = Real(2 - a);
  const Mat<D, Real> O = outer(x, y);
  const Vec<D, Real> Oz = O * x;  // (x (x) y) x = x (y . x)
  for (int a = 0; a < D; ++a) EXPECT_NEAR(double(Oz.v[a]), double(x.v[a]) * double(dot(y, x)), 1e-5);
}

TYPED_TEST(CoreMath, SymmetricEigenReconstructsAndIsOrthonormal) {
  constexpr int D = TypeParam::D;
  using Real = typename TypeParam::Real;
  std::mt19937 rng(4);
  for (int trial = 0; trial < 100; ++trial) {
    Mat<D, Real> A = random_matrix<D, Real>(rng);
    A = (A + transpose(A)) * Real(0.5);
    if (trial % 10 == 0) A = Mat<D, Real>::diagonal(Real(3));  // degenerate eigenvalues
    const auto e = eigen_symmetric(A);
    const Mat<D, Real> R = compose_symmetric(e.values, e.vectors);
    const Mat<D, Real> QtQ = transpose(e.vectors) * e.vectors;
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) {
        EXPECT_NEAR(double(R.m[a][b]), double(A.m[a][b]), 20 * Tol<Real>::value);
        EXPECT_NEAR(double(QtQ.m[a][b]), a == b ? 1.0 : 0.0, 20 * Tol<Real>::value);
      }
    double sum = 0;
    for (int a = 0; a < D; ++a) sum += double(e.values.v[a]);
    EXPECT_NEAR(sum, double(trace(A)), 20 * Tol<Real>::value);
  }
}

TEST(CoreMath, EigenOfKnownMatrix) {
  // [[2,1],[1,2]] has eigenvalues 1 and 3.
  Mat<2, double> A{{{2, 1}, {1, 2}}};
  auto e = eigen_symmetric(A);
  double lo = std::min(e.values[0], e.values[1]), hi = std::max(e.values[0], e.values[1]);
  EXPECT_NEAR(lo, 1.0, 1e-14);
  EXPECT_NEAR(hi, 3.0, 1e-14);
  // 3-D: eigenvalues of [[4,1,0],[1,4,1],[0,1,4]] are 4 - sqrt2, 4, 4 + sqrt2.
  Mat<3, double> B{{{4, 1, 0}, {1, 4, 1}, {0, 1, 4}}};
  auto f = eigen_symmetric(B);
  std::array<double, 3> v{f.values[0], f.values[1], f.values[2]};
  std::sort(v.begin(), v.end());
  EXPECT_NEAR(v[0], 4 - std::sqrt(2.0), 1e-13);
  EXPECT_NEAR(v[1], 4.0, 1e-13);
  EXPECT_NEAR(v[2], 4 + std::sqrt(2.0), 1e-13);
}

TEST(CoreMath, CrossProductAndNorm) {
  Vec<3, double> x{{1, 0, 0}}, y{{0, 1, 0}};
  const auto z = cross(x, y);
  EXPECT_DOUBLE_EQ(z[2], 1.0);
  EXPECT_DOUBLE_EQ(norm(Vec<2, double>{{3, 4}}), 5.0);
}
