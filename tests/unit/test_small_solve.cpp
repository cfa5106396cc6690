// Small matrices beyond the 2-D and 3-D tensors (kernels/core/small_solve.hpp):
// RKPM's moment matrices are (D + 1) x (D + 1) with a linear basis, 6 x 6
// with a quadratic one in 2-D. Gauss-Jordan with partial pivoting against
// the closed forms of mat.hpp (N = 2, 3), a matrix with a known inverse, a
// moment matrix of a real particle support and a singular support.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernels/core/small_solve.hpp"

using namespace mfsd;

namespace {

template <int N>
Mat<N, double> random_matrix(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Mat<N, double> A;
  for (int a = 0; a < N; ++a)
    for (int b = 0; b < N; ++b) A.m[a][b] = u(rng) + (a == b ? 2.0 : 0.0);
  return A;
}

template <int N>
double identity_error(const Mat<N, double>& A, const Mat<N, double>& B) {
  double e = 0;
  for (int a = 0; a < N; ++a)
    for (int b = 0; b < N; ++b) {
      double s = 0;
      for (int k = 0; k < N; ++k) s += A.m[a][k] * B.m[k][b];
      e = std::max(e, std::abs(s - (a == b ? 1.0 : 0.0)));
    }
  return e;
}

// RKPM's moment matrix M = sum_j H(x_j - x) H(x_j - x)^T phi_j with the
// linear basis H = (1, dx, dy, dz) and a cubic-spline weight (rkpm.md).
Mat<4, double> moment_matrix(const std::vector<Vec<3, double>>& support, double a) {
  Mat<4, double> M = Mat<4, double>::zero();
  for (const auto& d : support) {
    const double z = std::sqrt(d.v[0] * d.v[0] + d.v[1] * d.v[1] + d.v[2] * d.v[2]) / a;
    const double phi = z < 0.5 ? 2.0 / 3 - 4 * z * z + 4 * z * z * z : (z < 1 ? 4.0 / 3 * std::pow(1 - z, 3) : 0.0);
    const double H[4] = {1, d.v[0], d.v[1], d.v[2]};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) M.m[i][j] += H[i] * H[j] * phi;
  }
  return M;
}

}  // namespace

TEST(SmallSolve, MatchesTheClosedFormsIn2dAnd3d) {
  std::mt19937 rng(7);
  for (int k = 0; k < 20; ++k) {
    const auto A2 = random_matrix<2>(rng);
    const auto A3 = random_matrix<3>(rng);
    Mat<2, double> I2;
    Mat<3, double> I3;
    ASSERT_TRUE(try_inverse(A2, I2));
    ASSERT_TRUE(try_inverse(A3, I3));
    const auto C2 = inverse(A2);
    const auto C3 = inverse(A3);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        if (a < 2 && b < 2) {
          EXPECT_NEAR(I2.m[a][b], C2.m[a][b], 1e-13 * (1 + std::abs(C2.m[a][b])));
        }
        EXPECT_NEAR(I3.m[a][b], C3.m[a][b], 1e-13 * (1 + std::abs(C3.m[a][b])));
      }
    EXPECT_NEAR(det_by_elimination(A2), det(A2), 1e-14);
    EXPECT_NEAR(det_by_elimination(A3), det(A3), 1e-13);
  }
}

TEST(SmallSolve, InvertsAndSolvesUpToTheLargestSize) {
  std::mt19937 rng(11);
  const auto A4 = random_matrix<4>(rng);
  const auto A6 = random_matrix<6>(rng);
  const auto A8 = random_matrix<kMaxSmallSize>(rng);
  Mat<4, double> I4;
  Mat<6, double> I6;
  Mat<kMaxSmallSize, double> I8;
  ASSERT_TRUE(try_inverse(A4, I4));
  ASSERT_TRUE(try_inverse(A6, I6));
  ASSERT_TRUE(try_inverse(A8, I8));
  EXPECT_LT(identity_error(A4, I4), 1e-13);
  EXPECT_LT(identity_error(A6, I6), 1e-13);
  EXPECT_LT(identity_error(A8, I8), 1e-12);
  // A x = b against x = A^-1 b.
  Vec<6, double> b, x;
  for (int a = 0; a < 6; ++a) b.v[a] = a - 2.5;
  ASSERT_TRUE(solve(A6, b, x));
  for (int a = 0; a < 6; ++a) {
    double y = 0;
    for (int k = 0; k < 6; ++k) y += I6.m[a][k] * b.v[k];
    EXPECT_NEAR(x.v[a], y, 1e-13);
  }
  // det of a permuted triangular matrix: the product of its diagonal, with
  // the sign of the permutation (rows 0 and 3 swapped: -1).
  Mat<4, double> T = Mat<4, double>::zero();
  const double diag[4] = {2, -3, 0.5, 4};
  for (int a = 0; a < 4; ++a) {
    T.m[a][a] = diag[a];
    for (int c = a + 1; c < 4; ++c) T.m[a][c] = 0.1 * (a + c);
  }
  for (int c = 0; c < 4; ++c) std::swap(T.m[0][c], T.m[3][c]);
  EXPECT_NEAR(det_by_elimination(T), -(2 * -3 * 0.5 * 4), 1e-14);
}

TEST(SmallSolve, MomentMatrixOfAParticleSupportAndItsSingularCase) {
  // A lattice support of spacing 1 and radius a = 2: M is symmetric positive
  // definite, and M^-1 H(0) gives the shape functions' correction vector
  // b with sum_j b . H_j phi_j H_j = H(0) = (1, 0, 0, 0): the reproducing
  // condition of the linear basis.
  std::vector<Vec<3, double>> support;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j)
      for (int k = -2; k <= 2; ++k) support.push_back(Vec<3, double>{{0.9 * i + 0.05 * j, 1.0 * j, 1.1 * k - 0.1}});
  const auto M = moment_matrix(support, 2.0);
  Vec<4, double> e{{1, 0, 0, 0}}, bvec;
  ASSERT_TRUE(solve(M, e, bvec));
  Vec<4, double> check = Vec<4, double>::zero();
  for (const auto& d : support) {
    const double z = std::sqrt(d.v[0] * d.v[0] + d.v[1] * d.v[1] + d.v[2] * d.v[2]) / 2.0;
    const double phi = z < 0.5 ? 2.0 / 3 - 4 * z * z + 4 * z * z * z : (z < 1 ? 4.0 / 3 * std::pow(1 - z, 3) : 0.0);
    const double H[4] = {1, d.v[0], d.v[1], d.v[2]};
    double psi = 0;
    for (int a = 0; a < 4; ++a) psi += bvec.v[a] * H[a] * phi;
    for (int a = 0; a < 4; ++a) check.v[a] += psi * H[a];
  }
  EXPECT_NEAR(check.v[0], 1.0, 1e-12);
  for (int a = 1; a < 4; ++a) EXPECT_NEAR(check.v[a], 0.0, 1e-12);
  // All neighbours in one plane (z = 0): the z row of M is zero; singular.
  std::vector<Vec<3, double>> flat;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j) flat.push_back(Vec<3, double>{{0.9 * i, 1.0 * j, 0.0}});
  Mat<4, double> unchanged = Mat<4, double>::identity();
  EXPECT_FALSE(try_inverse(moment_matrix(flat, 2.0), unchanged));
  EXPECT_EQ(unchanged.m[0][1], 0.0);
  EXPECT_FALSE(solve(moment_matrix(flat, 2.0), e, bvec));
  // Singular only to round-off (row 3 = row 1 + row 2 in floating point):
  // elimination leaves a pivot of order 1e-17, not above 1e-12 of the
  // largest entry.
  Mat<3, double> near;
  const double rows[3][3] = {{0.1, 0.2, 0.3}, {0.4, 0.5, 0.6}, {0.1 + 0.4, 0.2 + 0.5, 0.3 + 0.6}};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) near.m[a][b] = rows[a][b];
  Mat<3, double> out;
  EXPECT_FALSE(try_inverse(near, out));
  Vec<3, double> rhs{{1, 2, 3}}, sol;
  EXPECT_FALSE(solve(near, rhs, sol));
  // float: the same support, to float's precision.
  Mat<4, float> Mf;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) Mf.m[a][b] = float(M.m[a][b]);
  Mat<4, float> If;
  ASSERT_TRUE(try_inverse(Mf, If, 1e-6f));
  Mat<4, double> Id;
  ASSERT_TRUE(try_inverse(M, Id));
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) EXPECT_NEAR(If.m[a][b], Id.m[a][b], 1e-4 * (1 + std::abs(Id.m[a][b])));
}
