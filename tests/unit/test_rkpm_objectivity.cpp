// RKPM objectivity through the whole node chain (rkpm.md 7.4): a cloud moved
// by prescribed increments du_I on every node, each step the production
// functors as host/solver/rkpm/rkpm_solver.hpp runs them: OperatorFunctor
// (shape functions, smoothed gradients, NSNI implicit gradients) in the
// current configuration, then StressFunctor (L_n from the smoothed gradients,
// Hughes-Winget, elastic predictor, F_cell, re-celling, NSNI sigma^(i)); rows
// rebuilt by brute force within max(reach_L, reach_I) + 0.1 dp each step.
//   cloud  plane strain, 11 x 11 lattice nodes, dp = 1, interior nodes
//          perturbed by up to +-0.2 dp (a fixed pseudo-random pattern), sphere
//          cubic B-spline a = 2 dp, lattice cells clipped on the sides,
//          mapped cells, NSNI on, E = 1, nu = 0.3
//   rotation  prestress sigma0 (all six components) rotated rigidly about
//          the centre by 90 deg in 100 increments x <- R_k x: every node's
//          sigma must equal R sigma0 R^T (rkpm.md 7.4: <= 1e-12 relative),
//          the NSNI gradients stay 0 (a linear motion has no strain gradient)
//   shear  simple shear x += dgamma y to gamma = 2 pi in 100 steps, from zero
//          stress: every node reproduces the material-point Jaumann/Dienes
//          numbers of rkpm.md 7.1 (sigma_12 = mu sin gamma, sigma_11 =
//          -sigma_22 = mu (1 - cos gamma); error 5.17e-4 mu at 100 steps, gate
//          1e-3 mu) and agrees with the others to round-off; the cells
//          re-cell (kappa_max 10) or, with kappa_max 1e9, distort to cond
//          F_cell 57: the stresses are the same.
// Measured (fp64): rotation max relative error 2.6e-14, |sigma^(i)| 2.3e-14;
// shear: Dienes error 5.166e-4 mu (the material point's number), spread of
// the nodes 6.9e-15 mu (re-celled) and 9.8e-15 mu (not), re-celled against
// not 1.8e-15 mu. Exception, found here: at gamma = 2 pi the sheared block's
// corners are 9 deg wide and the +-0.2 dp cloud gets locally near-collinear,
// so 19 of the 121 nodes (the rows along the two acute corners, 5 interior
// ones) had a regularized moment matrix in some step (quasi-linear fallback,
// rkpm.md 1.6): their stresses differ by up to 3.1 mu. The gates apply to the
// nodes that were never regularized, and at most 1/5 of the nodes may be.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "kernels/rkpm/stress_stage.hpp"

using namespace mfsd;
using namespace mfsd::rkpm;

namespace {

using V2 = Vec<2, double>;
using M2 = Mat<2, double>;
using M3 = Mat<3, double>;

constexpr int kSide = 11;
constexpr int kNodes = kSide * kSide;
constexpr double kE = 1.0, kNu = 0.3;
constexpr double kSupport = 2.0;

// A moving cloud driven through the operator and stress stages.
struct Cloud {
  double recell_condition;
  std::vector<V2> x, du, lo, hi;
  std::vector<double> a, V0, reach, nearest;
  std::vector<unsigned char> status, ever;  // status bits of the last step; OR over all steps
  std::vector<PairIndex> offsets;
  std::vector<Index> neighbor;
  std::vector<NodeOperator<2, double>> op;
  std::vector<ImplicitGradient<2, double>> grad;
  std::vector<M2> cell_map;
  std::vector<M3> stress;
  std::vector<StressGradient<2, double>> sigma_i, tau_i;
  std::vector<double> work;
  long recelled = 0;  // nodes whose F_cell was re-celled in some step
  double max_condition = 1.0;

  explicit Cloud(double kappa) : recell_condition(kappa) {
    unsigned state = 12345u;
    auto jitter = [&]() {  // +-0.2, a fixed linear congruential pattern
      state = state * 1664525u + 1013904223u;
      return 0.4 * (double(state >> 8) / double(1u << 24) - 0.5);
    };
    for (int j = 0; j < kSide; ++j)
      for (int i = 0; i < kSide; ++i) {
        const bool interior = i > 0 && j > 0 && i < kSide - 1 && j < kSide - 1;
        x.push_back(V2{{i + (interior ? jitter() : 0.0), j + (interior ? jitter() : 0.0)}});
        V2 l, h;
        const int idx[2] = {i, j};
        for (int k = 0; k < 2; ++k) {
          l.v[k] = idx[k] == 0 ? 0.0 : 0.5;
          h.v[k] = idx[k] == kSide - 1 ? 0.0 : 0.5;
        }
        lo.push_back(l);
        hi.push_back(h);
        V0.push_back((l.v[0] + h.v[0]) * (l.v[1] + h.v[1]));
      }
    a.assign(kNodes, kSupport);
    reach.assign(kNodes, kSupport + 0.75);
    nearest.assign(kNodes, 0.0);
    status.assign(kNodes, 0);
    du.assign(kNodes, V2::zero());
    cell_map.assign(kNodes, M2::identity());
    stress.assign(kNodes, M3::zero());
    StressGradient<2, double> zero;
    for (auto& g : zero.g) g = M2::zero();
    sigma_i.assign(kNodes, zero);
    tau_i.assign(kNodes, zero);
    work.assign(kNodes, 0.0);
  }

  PairList<2, double> rows() const {
    return PairList<2, double>{offsets.data(), neighbor.data(), nullptr, nullptr, nullptr, nullptr};
  }
  NodeFields<2, double> nodes() const { return NodeFields<2, double>{x.data(), a.data(), nullptr}; }

  // Rows (self first) and the operators in the current configuration.
  void rebuild() {
    offsets.assign(1, 0);
    neighbor.clear();
    for (Index L = 0; L < kNodes; ++L) {
      neighbor.push_back(L);
      for (Index I = 0; I < kNodes; ++I)
        if (I != L && norm(x[I] - x[L]) < std::max(reach[L], reach[I]) + 0.1) neighbor.push_back(I);
      offsets.push_back(PairIndex(neighbor.size()));
    }
    neighbor.resize(neighbor.size() + kPairPrefetchDistance, 0);
    op.resize(kNodes);
    grad.resize(kNodes);
    OperatorFunctor<2, double> f{rows(), nodes(),   cell_map.data(), lo.data(),    hi.data(),      false,        0,
                                 1e-3,   op.data(), grad.data(),     reach.data(), nearest.data(), status.data()};
    for (Index L = 0; L < kNodes; ++L) f(L);
    if (ever.empty()) ever.assign(kNodes, 0);
    for (Index L = 0; L < kNodes; ++L) ever[L] |= status[L];
  }

  // One step: the operators at x, the stress stage with du, then x += du.
  void step() {
    rebuild();
    StressLaw law;
    law.kind = LawKind::elastic;
    law.K = kE / (3.0 * (1.0 - 2.0 * kNu));
    law.mu = kE / (2.0 * (1.0 + kNu));
    StressFunctor<2, double> s{rows(),         nodes(),      op.data(),        grad.data(),   du.data(), V0.data(),
                               lo.data(),      hi.data(),    cell_map.data(),  stress.data(), nullptr,   nullptr,
                               sigma_i.data(), tau_i.data(), work.data(),      nullptr,       law,       1.0,
                               false,          false,        recell_condition, false,         1.0};
    for (Index L = 0; L < kNodes; ++L) s(L);
    for (Index L = 0; L < kNodes; ++L) {
      x[L] += du[L];
      max_condition = std::max(max_condition, condition_number<2>(cell_map[L]));
    }
  }
};

M3 rotate(const M3& s, double angle) {
  M3 R = M3::identity();
  R.m[0][0] = R.m[1][1] = std::cos(angle);
  R.m[0][1] = -std::sin(angle);
  R.m[1][0] = std::sin(angle);
  return mul_transposed(R * s, R);
}

double max_abs(const M3& s) {
  double r = 0;
  for (auto& row : s.m)
    for (double v : row) r = std::max(r, std::fabs(v));
  return r;
}

}  // namespace

TEST(RkpmObjectivity, PrestressedCloudRotatedRigidlyBy90Degrees) {
  Cloud c(10.0);
  M3 sigma0;
  const double values[3][3] = {{1.0, 0.3, -0.2}, {0.3, -0.5, 0.4}, {-0.2, 0.4, 0.2}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) sigma0.m[i][j] = values[i][j];
  c.stress.assign(kNodes, sigma0);
  const int steps = 100;
  const double dtheta = 0.5 * math::pi<double> / steps;
  const V2 centre{{5.0, 5.0}};
  for (int n = 0; n < steps; ++n) {
    for (Index L = 0; L < kNodes; ++L) {  // du = (R_k - I)(x - c): exactly rigid
      const V2 r = c.x[L] - centre;
      c.du[L] = V2{{std::cos(dtheta) * r.v[0] - std::sin(dtheta) * r.v[1] - r.v[0],
                    std::sin(dtheta) * r.v[0] + std::cos(dtheta) * r.v[1] - r.v[1]}};
    }
    c.step();
  }
  const M3 expected = rotate(sigma0, steps * dtheta);
  double err = 0, gradient = 0;
  for (Index L = 0; L < kNodes; ++L) {
    err = std::max(err, max_abs(c.stress[L] - expected) / max_abs(sigma0));
    for (const M2& g : c.sigma_i[L].g)
      for (auto& row : g.m)
        for (double v : row) gradient = std::max(gradient, std::fabs(v));
  }
  std::printf("rigid rotation by 90 deg in 100 steps, %d nodes: max relative error %.3g, max |sigma^(i)| %.3g\n",
              kNodes, err, gradient);
  EXPECT_LE(err, 1e-12);       // rkpm.md 7.4
  EXPECT_LE(gradient, 1e-12);  // a linear motion has no strain gradient: NSNI stays silent
}

TEST(RkpmObjectivity, SimpleShearOfACloudReproducesTheMaterialPoint) {
  const int steps = 100;
  const double gamma_end = 2 * math::pi<double>, dgamma = gamma_end / steps;
  const double mu = kE / (2.0 * (1.0 + kNu));
  M3 result[2];
  double spread[2] = {0, 0}, cond[2] = {0, 0}, regularized_error[2] = {0, 0};
  int regularized[2] = {0, 0};
  const double kappas[2] = {10.0, 1e9};
  for (int run = 0; run < 2; ++run) {
    Cloud c(kappas[run]);
    for (int n = 0; n < steps; ++n) {
      for (Index L = 0; L < kNodes; ++L) c.du[L] = V2{{dgamma * c.x[L].v[1], 0.0}};  // y does not change
      c.step();
    }
    result[run] = c.stress[kNodes / 2];
    for (Index L = 0; L < kNodes; ++L) {
      const double e = max_abs(c.stress[L] - result[run]) / mu;
      if (c.ever[L] & 1u) {  // regularized in some step: the quasi-linear error, not exact
        regularized[run] += 1;
        regularized_error[run] = std::max(regularized_error[run], e);
      } else {
        spread[run] = std::max(spread[run], e);
      }
    }
    cond[run] = c.max_condition;
  }
  const double g = steps * dgamma;
  M3 exact = M3::zero();
  exact.m[0][0] = mu * (1 - std::cos(g));
  exact.m[1][1] = -mu * (1 - std::cos(g));
  exact.m[0][1] = exact.m[1][0] = mu * std::sin(g);
  const double err = max_abs(result[0] - exact) / mu;
  const double recell_effect = max_abs(result[0] - result[1]) / mu;
  std::printf(
      "simple shear to gamma = 2 pi in 100 steps: Dienes error %.4g mu, spread of the never-regularized "
      "nodes %.3g / %.3g mu, re-celled vs not %.3g mu, largest cond F_cell %.3g / %.3g; regularized in some "
      "step: %d / %d nodes, their largest difference %.3g / %.3g mu\n",
      err, spread[0], spread[1], recell_effect, cond[0], cond[1], regularized[0], regularized[1], regularized_error[0],
      regularized_error[1]);
  EXPECT_LE(err, 1e-3);  // rkpm.md 7.1 gate at 100 steps (material point: 5.17e-4 mu)
  EXPECT_LE(spread[0], 1e-10);
  EXPECT_LE(spread[1], 1e-10);
  EXPECT_LE(recell_effect, 1e-10);
  EXPECT_LE(regularized[0], kNodes / 5);  // the acute corners' rows and a few stretched supports
  EXPECT_LE(cond[0], 10.0 * 1.01);        // re-celled: kept at kappa_max
  EXPECT_GT(cond[1], 10.0);               // not re-celled: the cells did get distorted
}
