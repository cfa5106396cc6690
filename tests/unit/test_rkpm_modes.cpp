// RKPM spurious-mode test (rkpm.md 7.3, the `nsni` gate; 3.3-3.5, 5.3), at
// the kernel level: the production functors driven on host arrays as
// host/solver/rkpm/rkpm_solver.hpp drives them, no solver.
//   model  free-free plane-strain square [0, 10]^2, 11 x 11 vertex-centred
//          nodes, dp = 1, E = 1, nu = 0.3, rho = 1, linear elastic; lattice
//          cells (half on edges, quarter at corners, surface bits on the
//          clipped sides), sphere cubic B-spline a = a~ dp (the code has only
//          spheres; the spec's table is for boxes), mapped cells, VC on,
//          quasi-linear `regularize` (never active here), row-sum mass; a
//          brute-force CSR list (nodes within a + 0.75 dp, self first; all
//          nodes give the same K to the last digit)
//   K      OperatorFunctor once, at the reference configuration (F_cell = I);
//          per dof j, StressFunctor (fresh F_cell = I, sigma = 0, sigma^(i) =
//          0) and ForceFunctor (dt = 0, `internal_force`) with du = +-eps e_j,
//          eps = 1e-6 dp: K(:, j) = (f_int(+) - f_int(-))/(2 eps), the
//          small-strain stiffness K = d f_int/du (M a = -f_int); M_I from the
//          same ForceFunctor call. eps = 1e-3 dp gives the same 5 digits.
//   modes  omega^2 of M^-1/2 K M^-1/2 (242 dofs, symmetrized K) by a cyclic
//          Jacobi solver written here (eigen residual <= 6e-16 |A|)
//
// Measured (fp64; 1.2 s for the whole file in an -O2 build on a shared 2-core
// machine, 2.6 s as ctest's one process per TEST; K 0.1 s, modes 0.2 s a case):
//   lowest five non-rigid omega^2                    omega^2_max  2/omega_max
//   SNNI       a~ = 2.0  0.01301 0.01301 0.01761 0.02554 0.02554   2.5538   1.452 dp/c_d
//   SNNI+NSNI  a~ = 2.0  0.05800 0.06258 0.06258 0.07177 0.08898   3.2214   1.293
//   SNNI       a~ = 1.5  0.03152 0.03152 0.05613 0.06209 0.06209   3.2630   1.285
//   SNNI+NSNI  a~ = 1.5  0.06381 0.07340 0.07340 0.07876 0.10458  13.1155   0.641
// against rkpm.md 7.3's box-support table: SNNI a~ = 2 -2.2 %, -2.2 %, -1.1 %;
// NSNI a~ = 2 +0.5 .. +0.8 %; NSNI a~ = 1.5 +1.3, +2.2, +2.2, +0.6, +2.2 %
// (FE reference 0.0597). The critical steps are rkpm.md 5.3's sphere row
// (1.45, 1.29, 1.29, 0.64).
//   - rigid modes: three, |omega^2| <= 2.3e-16 omega^2_max; the next >= 4.9e-3
//   - |K - K^T|/|K| = 1.0e-14 (SNNI a~ 2), 2.3e-14 (NSNI 2), 2.0e-14 (SNNI
//     1.5), 7.6e-14 (NSNI 1.5); |K(VC on) - K(VC off)|/|K| = 6e-17 (xi = 0)
//   - sum M_I = 100 rho dp^2 to 1e-12; smallest M_I (corner) 0.431 (a~ 2),
//     0.315 (a~ 1.5) rho dp^2 (rkpm.md 3.3: 0.32)
//   - lowest non-rigid mode, neighbour alternation A = -sum u_I u_J /
//     sum (u_I^2 + u_J^2)/2 per component and lattice direction (+1 every
//     neighbour opposite, -1 constant): SNNI a~ 2 A = +0.89 .. +0.95 for both
//     components along both directions (checkerboard with a smooth envelope;
//     correlation with (-1)^(i+j) 0.49 (u_x), 0.71 (u_y)); SNNI a~ 1.5 u_x
//     alternates along y (+0.88) and u_y along x (+0.95), each smooth along
//     the other direction (-0.77, -0.99): a transverse alternation, which the
//     face-point difference across a cell does not see; with NSNI all four
//     A = -0.94 .. -1.00 (smooth) at both a~
//   - Rayleigh quotient u^T K u / u^T M u, SNNI -> SNNI+NSNI: linear shear
//     u = (y - 5, 0) 0.043766 -> 0.043766 (a~ 2; 0.044697 at 1.5; NSNI's
//     term vanishes on linear fields, change 4e-16); sine shear
//     u = (sin(pi (y - 5)/10), 0): 0.036529 -> 0.036814 (+0.78 %) at a~ 2
//     (rkpm.md 3.5: 0.0367 -> 0.0370), 0.036830 -> 0.038699 (+5.07 %) at 1.5
// Gates: rigid modes < 1e-8 omega^2_max; asymmetry <= 1e-10; NSNI lowest
// >= 0.055 (a~ 2 and 1.5); SNNI lowest <= 0.02 (a~ 2) and <= 0.6 x NSNI's
// lowest (a~ 1.5: spurious too, 0.0315, though above the a~ 2 gate); SNNI's
// lowest mode sign-alternating (largest A of a component carrying >= 10 % of
// the mode > 0.8), NSNI's smooth (< 0); Rayleigh quotients: linear shear
// unchanged to 1e-9, sine shear within 5 % (a~ 2) and 6 % (a~ 1.5);
// regression +-2 % on the table above and the critical steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "kernels/rkpm/internal_force.hpp"

using namespace mfsd;
using namespace mfsd::rkpm;

namespace {

using V2 = Vec<2, double>;
using M2 = Mat<2, double>;

constexpr int kSide = 11;  // nodes per side: the square [0, 10]^2 at dp = 1
constexpr int kNodes = kSide * kSide;
constexpr int kDofs = 2 * kNodes;
constexpr double kDp = 1.0;
constexpr double kE = 1.0, kNu = 0.3, kRho = 1.0;
constexpr double kEps = 1e-6 * kDp;  // central-difference step of K
constexpr double kPi = 3.14159265358979323846;

// ------------------------------------------------------------------ eigen
// Cyclic Jacobi on a dense symmetric n x n matrix (row-major): A is
// destroyed, w gets the eigenvalues, V (where given) the eigenvectors in its
// rows (V A0 V^T = diag w). Sweeps until the off-diagonal norm is below 1e-15
// of the norm (12-13 sweeps here), skipping entries below 1e-18 of it.
void jacobi_eigen(std::vector<double>& A, int n, std::vector<double>& w, std::vector<double>* V) {
  if (V) {
    V->assign(size_t(n) * n, 0.0);
    for (int k = 0; k < n; ++k) (*V)[size_t(k) * n + k] = 1.0;
  }
  auto at = [&](int r, int c) -> double& { return A[size_t(r) * n + c]; };
  double total = 0;
  for (double a : A) total += a * a;
  const double skip = 1e-18 * std::sqrt(total);
  for (int sweep = 0; sweep < 60; ++sweep) {
    double off = 0;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) off += at(p, q) * at(p, q);
    if (off <= 1e-30 * total) break;
    for (int p = 0; p < n - 1; ++p)
      for (int q = p + 1; q < n; ++q) {
        const double apq = at(p, q), app = at(p, p), aqq = at(q, q);
        if (std::fabs(apq) < skip) continue;  // negligible: leaves the off-diagonal norm below the target
        const double theta = (aqq - app) / (2.0 * apq);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        // A <- J^T A J, J the rotation in the (p, q) plane with J_pq = s:
        // rows p and q (contiguous), then the columns by symmetry.
        double* rp = A.data() + size_t(p) * n;
        double* rq = A.data() + size_t(q) * n;
        for (int k = 0; k < n; ++k) {
          const double apk = rp[k], aqk = rq[k];
          rp[k] = c * apk - s * aqk;
          rq[k] = s * apk + c * aqk;
        }
        for (int k = 0; k < n; ++k) at(k, p) = rp[k], at(k, q) = rq[k];
        at(p, p) = app - t * apq;  // the 2 x 2 block in closed form
        at(q, q) = aqq + t * apq;
        at(p, q) = at(q, p) = 0.0;
        if (V) {
          double* vp = V->data() + size_t(p) * n;
          double* vq = V->data() + size_t(q) * n;
          for (int k = 0; k < n; ++k) {
            const double a = vp[k], b = vq[k];
            vp[k] = c * a - s * b;
            vq[k] = s * a + c * b;
          }
        }
      }
  }
  w.resize(n);
  for (int k = 0; k < n; ++k) w[k] = at(k, k);
}

// ------------------------------------------------------------------ model
// The free-free square: nodes, lattice cells, a brute-force CSR list, the
// operators of the reference configuration and K, M by the production
// functors, as host/solver/rkpm/rkpm_solver.hpp drives them.
struct Square {
  double factor;  // a~
  bool nsni;
  bool vc;  // variational correction (rkpm.md 3.4)
  std::vector<V2> x;
  std::vector<double> a, V0, mass, rho0;
  std::vector<V2> lo, hi;
  std::vector<unsigned char> surface, status;
  std::vector<PairIndex> offsets;
  std::vector<Index> neighbor;
  std::vector<NodeOperator<2, double>> op;
  std::vector<ImplicitGradient<2, double>> grad;
  std::vector<double> reach, nearest;
  std::vector<double> K, M;  // K: kDofs x kDofs (row-major, K_ij = d f_int_i / d u_j); M per dof
  double asymmetry = 0;      // |K - K^T|_F / |K|_F before symmetrizing
  long regularized = 0;      // nodes with a regularized evaluation point

  bool box = false;  // box supports (tensor-product kernel), else spheres

  Square(double f, bool with_nsni, bool with_vc = true, bool with_box = false)
      : factor(f), nsni(with_nsni), vc(with_vc), box(with_box) {
    for (int j = 0; j < kSide; ++j)
      for (int i = 0; i < kSide; ++i) {
        x.push_back(V2{{i * kDp, j * kDp}});
        V2 l, h;
        unsigned char bits = 0;
        const int idx[2] = {i, j};
        for (int k = 0; k < 2; ++k) {
          l.v[k] = idx[k] == 0 ? 0.0 : 0.5 * kDp;  // clipped to 0 on the body's surface (rkpm.md 3.2)
          h.v[k] = idx[k] == kSide - 1 ? 0.0 : 0.5 * kDp;
          if (idx[k] == 0) bits |= 1u << (2 * k);  // face 2k: -e_k
          if (idx[k] == kSide - 1) bits |= 1u << (2 * k + 1);
        }
        lo.push_back(l);
        hi.push_back(h);
        surface.push_back(bits);
        V0.push_back((l.v[0] + h.v[0]) * (l.v[1] + h.v[1]));
        mass.push_back(kRho * V0.back());
        rho0.push_back(kRho);
      }
    a.assign(kNodes, factor * kDp);
    // Rows: every node within a + cell reach (<= 0.56 dp) + skin of node L,
    // itself first (rkpm.md 2); radius a + 0.75 dp.
    const double radius = factor * kDp * kernel_reach_factor<2>(box) + 0.75 * kDp;
    offsets.assign(1, 0);
    for (Index L = 0; L < kNodes; ++L) {
      neighbor.push_back(L);
      for (Index I = 0; I < kNodes; ++I)
        if (I != L && norm(x[I] - x[L]) < radius) neighbor.push_back(I);
      offsets.push_back(PairIndex(neighbor.size()));
    }
    neighbor.resize(neighbor.size() + kPairPrefetchDistance, 0);
    build_operators();
    build_stiffness();
  }

  PairList<2, double> rows() const {
    return PairList<2, double>{offsets.data(), neighbor.data(), nullptr, nullptr, nullptr, nullptr};
  }
  NodeFields<2, double> nodes() const { return NodeFields<2, double>{x.data(), a.data(), nullptr, box}; }

  // Stage 5 at the reference configuration (F_cell = I).
  void build_operators() {
    const std::vector<M2> F(kNodes, M2::identity());
    op.resize(kNodes);
    grad.resize(kNodes);
    reach.assign(kNodes, 0.0);
    nearest.assign(kNodes, 0.0);
    status.assign(kNodes, 0);
    OperatorFunctor<2, double> f{rows(),
                                 nodes(),
                                 F.data(),
                                 lo.data(),
                                 hi.data(),
                                 false,  // mapped cells
                                 0,      // quasi_linear: regularize
                                 1e-3,   // tau
                                 op.data(),
                                 nsni ? grad.data() : nullptr,
                                 reach.data(),
                                 nearest.data(),
                                 status.data()};
    for (Index L = 0; L < kNodes; ++L) f(L);
    for (unsigned char s : status) regularized += (s & 1u) ? 1 : 0;
  }

  // f_int for the increment du from the reference state (zero stress), by
  // the stress and force stages with fresh state; M_I from the same call.
  std::vector<double> internal_force(const std::vector<V2>& du, std::vector<double>* lumped) const {
    std::vector<M2> cell_map(kNodes, M2::identity());
    std::vector<Mat<3, double>> stress(kNodes, Mat<3, double>::zero());
    StressGradient<2, double> zero_gradient;
    for (auto& g : zero_gradient.g) g = M2::zero();
    std::vector<StressGradient<2, double>> sigma_i(kNodes, zero_gradient), tau_i(kNodes, zero_gradient);
    std::vector<double> work(kNodes, 0.0);
    StressLaw law;
    law.kind = LawKind::elastic;
    law.K = kE / (3.0 * (1.0 - 2.0 * kNu));
    law.mu = kE / (2.0 * (1.0 + kNu));
    StressFunctor<2, double> s{rows(),
                               nodes(),
                               op.data(),
                               nsni ? grad.data() : nullptr,
                               du.data(),
                               V0.data(),
                               lo.data(),
                               hi.data(),
                               cell_map.data(),
                               stress.data(),
                               nullptr,  // plastic strain
                               nullptr,  // damage
                               nsni ? sigma_i.data() : nullptr,
                               nsni ? tau_i.data() : nullptr,
                               work.data(),
                               nullptr,  // plastic work
                               law,
                               1.0,    // nsni_scale
                               true,   // tangent moduli (elastic here: the same)
                               true,   // consistent moduli (elastic here: the same)
                               1e9,    // recell_condition
                               false,  // mapped cells
                               1.0};   // dt
    for (Index L = 0; L < kNodes; ++L) s(L);
    std::vector<V2> f(kNodes), velocity(kNodes, V2::zero()), acceleration(kNodes, V2::zero());
    std::vector<double> M(kNodes), Mv(kNodes);
    ForceFunctor<2, double> force{rows(),
                                  nodes(),
                                  op.data(),
                                  nsni ? grad.data() : nullptr,
                                  nsni ? tau_i.data() : nullptr,
                                  stress.data(),
                                  nullptr,  // damage
                                  DamageLaw{},
                                  surface.data(),
                                  status.data(),
                                  mass.data(),
                                  M.data(),
                                  Mv.data(),
                                  rho0.data(),
                                  velocity.data(),
                                  acceleration.data(),
                                  nullptr,  // damping work
                                  V2::zero(),
                                  vc,    // variational correction
                                  true,  // row-sum mass
                                  0.0,   // alpha_d
                                  0.0,   // dt: no velocity update
                                  f.data()};
    for (Index I = 0; I < kNodes; ++I) force(I);
    if (lumped) *lumped = M;
    std::vector<double> out(kDofs);
    for (int I = 0; I < kNodes; ++I)
      for (int c = 0; c < 2; ++c) out[2 * I + c] = f[I].v[c];
    return out;
  }

  void build_stiffness() {
    K.assign(size_t(kDofs) * kDofs, 0.0);
    std::vector<double> lumped;
    std::vector<V2> du(kNodes, V2::zero());
    internal_force(du, &lumped);
    M.resize(kDofs);
    for (int I = 0; I < kNodes; ++I) M[2 * I] = M[2 * I + 1] = lumped[I];
    for (int j = 0; j < kDofs; ++j) {
      du[j / 2].v[j % 2] = kEps;
      const std::vector<double> fp = internal_force(du, nullptr);
      du[j / 2].v[j % 2] = -kEps;
      const std::vector<double> fm = internal_force(du, nullptr);
      du[j / 2].v[j % 2] = 0.0;
      for (int i = 0; i < kDofs; ++i) K[size_t(i) * kDofs + j] = (fp[i] - fm[i]) / (2.0 * kEps);
    }
    double num = 0, den = 0;
    for (int i = 0; i < kDofs; ++i)
      for (int j = 0; j < kDofs; ++j) {
        const double d = K[size_t(i) * kDofs + j] - K[size_t(j) * kDofs + i];
        num += d * d;
        den += K[size_t(i) * kDofs + j] * K[size_t(i) * kDofs + j];
      }
    asymmetry = std::sqrt(num / den);
    for (int i = 0; i < kDofs; ++i)
      for (int j = i + 1; j < kDofs; ++j) {
        const double s = 0.5 * (K[size_t(i) * kDofs + j] + K[size_t(j) * kDofs + i]);
        K[size_t(i) * kDofs + j] = K[size_t(j) * kDofs + i] = s;
      }
  }

  // u^T K u / u^T M u.
  double rayleigh(const std::vector<double>& u) const {
    double num = 0, den = 0;
    for (int i = 0; i < kDofs; ++i) {
      double Ku = 0;
      for (int j = 0; j < kDofs; ++j) Ku += K[size_t(i) * kDofs + j] * u[j];
      num += u[i] * Ku;
      den += u[i] * M[i] * u[i];
    }
    return num / den;
  }
};

struct Modes {
  std::vector<double> omega2;               // ascending
  std::vector<std::vector<double>> shapes;  // displacement u = M^-1/2 v of each, same order
  double residual = 0;                      // max_k |A v_k - w_k v_k| / |A|_F over the eight lowest and the top
};

// omega^2 of M^-1/2 K M^-1/2 and the mode shapes.
Modes solve_modes(const Square& sq) {
  std::vector<double> A(size_t(kDofs) * kDofs);
  for (int i = 0; i < kDofs; ++i)
    for (int j = 0; j < kDofs; ++j)
      A[size_t(i) * kDofs + j] = sq.K[size_t(i) * kDofs + j] / std::sqrt(sq.M[i] * sq.M[j]);
  const std::vector<double> A0 = A;
  std::vector<double> w, V;
  jacobi_eigen(A, kDofs, w, &V);
  std::vector<int> order(kDofs);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int p, int q) { return w[p] < w[q]; });
  Modes m;
  for (int k : order) {
    m.omega2.push_back(w[k]);
    std::vector<double> u(kDofs);
    for (int i = 0; i < kDofs; ++i) u[i] = V[size_t(k) * kDofs + i] / std::sqrt(sq.M[i]);
    m.shapes.push_back(u);
  }
  double norm_A = 0;
  for (double a : A0) norm_A += a * a;
  norm_A = std::sqrt(norm_A);
  for (int r = 0; r < kDofs; ++r) {
    if (r >= 8 && r != kDofs - 1) continue;
    const int k = order[r];
    double e = 0;
    for (int i = 0; i < kDofs; ++i) {
      double Av = 0;
      for (int j = 0; j < kDofs; ++j) Av += A0[size_t(i) * kDofs + j] * V[size_t(k) * kDofs + j];
      e += (Av - w[k] * V[size_t(k) * kDofs + i]) * (Av - w[k] * V[size_t(k) * kDofs + i]);
    }
    m.residual = std::max(m.residual, std::sqrt(e) / norm_A);
  }
  return m;
}

// How a mode alternates from node to node: per displacement component c and
// lattice direction d, A_dc = -sum u_Ic u_Jc / sum (u_Ic^2 + u_Jc^2)/2 over
// the neighbour pairs (I, J) along d (+1: every neighbour opposite, -1: a
// constant; smooth modes are close to -1). `most` is the largest A_dc of the
// components that carry at least 10 % of the mode. Also the correlation of
// u_x and u_y with the checkerboard (-1)^(i+j).
struct Alternation {
  double A[2][2];  // [direction][component]
  double most;
  double checker[2];
};
Alternation alternation(const std::vector<double>& u) {
  double num[2][2] = {{0, 0}, {0, 0}}, den[2][2] = {{0, 0}, {0, 0}}, chk[2] = {0, 0}, sq[2] = {0, 0};
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) {
      const int I = i + kSide * j;
      const double s = (i + j) % 2 ? -1.0 : 1.0;
      for (int c = 0; c < 2; ++c) chk[c] += s * u[2 * I + c], sq[c] += u[2 * I + c] * u[2 * I + c];
      for (int d = 0; d < 2; ++d) {
        const int i2 = i + (d == 0), j2 = j + (d == 1);
        if (i2 >= kSide || j2 >= kSide) continue;
        const int J = i2 + kSide * j2;
        for (int c = 0; c < 2; ++c) {
          num[d][c] -= u[2 * I + c] * u[2 * J + c];
          den[d][c] += 0.5 * (u[2 * I + c] * u[2 * I + c] + u[2 * J + c] * u[2 * J + c]);
        }
      }
    }
  Alternation r;
  r.most = -1.0;
  for (int c = 0; c < 2; ++c) {
    r.checker[c] = std::fabs(chk[c]) / std::sqrt(kNodes * sq[c]);
    for (int d = 0; d < 2; ++d) {
      r.A[d][c] = num[d][c] / den[d][c];
      if (sq[c] >= 0.1 * (sq[0] + sq[1])) r.most = std::max(r.most, r.A[d][c]);
    }
  }
  return r;
}

// Smooth fields: the linear shear u = (y - 5, 0) and the sine shear u = (sin(pi (y - 5)/10), 0).
std::vector<double> linear_shear() {
  std::vector<double> u(kDofs, 0.0);
  for (int I = 0; I < kNodes; ++I) u[2 * I] = (I / kSide) * kDp - 5.0;
  return u;
}
std::vector<double> sine_shear() {
  std::vector<double> u(kDofs, 0.0);
  for (int I = 0; I < kNodes; ++I) u[2 * I] = std::sin(kPi * ((I / kSide) * kDp - 5.0) / 10.0);
  return u;
}

// One of the four cases: K built on first use, the modes on first use
// (gtest_discover_tests runs each TEST in its own process: the tests that
// need only K do not pay for the eigen solves).
struct Case {
  double factor;
  bool nsni;
  std::shared_ptr<Square> k;
  std::shared_ptr<Modes> modes;
  const Square& square() {
    if (!k) {
      const auto t0 = std::chrono::steady_clock::now();
      k = std::make_shared<Square>(factor, nsni);
      std::printf("a~ = %.1f %-9s K in %.2f s\n", factor, nsni ? "SNNI+NSNI" : "SNNI",
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    return *k;
  }
  const Modes& m() {
    if (!modes) {
      const Square& sq = square();
      const auto t0 = std::chrono::steady_clock::now();
      modes = std::make_shared<Modes>(solve_modes(sq));
      std::printf("a~ = %.1f %-9s modes in %.2f s\n", factor, nsni ? "SNNI+NSNI" : "SNNI",
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    return *modes;
  }
};

std::vector<Case>& cases() {
  static std::vector<Case> all{{2.0, false, {}, {}}, {2.0, true, {}, {}}, {1.5, false, {}, {}}, {1.5, true, {}, {}}};
  return all;
}

Case& get(double factor, bool nsni) {
  for (Case& c : cases())
    if (c.factor == factor && c.nsni == nsni) return c;
  throw std::logic_error("no such case");
}

const char* name(const Case& c) { return c.nsni ? "SNNI+NSNI" : "SNNI"; }

// The critical step 2/omega_max in units of dp/c_d, c_d = sqrt((lambda + 2 mu)/rho) (rkpm.md 5.3).
double critical_step(Case& c) {
  const double K = kE / (3.0 * (1.0 - 2.0 * kNu)), mu = kE / (2.0 * (1.0 + kNu));
  return 2.0 / std::sqrt(c.m().omega2.back()) * std::sqrt((K + 4.0 * mu / 3.0) / kRho) / kDp;
}

// ------------------------------------------------------------------ tests
// rkpm.md 7.3: three rigid modes ~ 0; K symmetric (SNNI + VC on conforming
// cells: xi = 0; NSNI: the same Psi_I,ki in the strain gradient and the
// force); the row-sum mass sums to the body's mass (partition of unity).
TEST(RkpmModes, RigidModesSymmetryMass) {
  for (Case& c : cases()) {
    const Square& sq = c.square();
    const Modes& m = c.m();
    const auto& w = m.omega2;
    const double top = w.back();
    double total = 0, lowest = 1e300;
    for (int I = 0; I < kNodes; ++I) total += sq.M[2 * I], lowest = std::min(lowest, sq.M[2 * I]);
    std::printf(
        "a~ = %.1f %-9s |K - K^T|/|K| = %.2e, rigid omega^2/max %.1e %.1e %.1e, first non-rigid/max %.2e; "
        "sum M_I = %.12f, min M_I = %.4f rho dp^2, regularized nodes %ld, eigen residual %.1e\n",
        c.factor, name(c), sq.asymmetry, w[0] / top, w[1] / top, w[2] / top, w[3] / top, total, lowest, sq.regularized,
        m.residual);
    EXPECT_LE(m.residual, 1e-12);
    EXPECT_LE(sq.asymmetry, 1e-10);
    for (int k = 0; k < 3; ++k) EXPECT_LE(std::fabs(w[k]), 1e-8 * top) << "rigid mode " << k;
    EXPECT_GE(w[3], 1e-3 * top);
    EXPECT_NEAR(total, kRho * 100.0, 1e-11);
    EXPECT_GE(lowest, 0.1 * kRho * 0.25);  // above the guard (rkpm.md 3.3): the corner's m = rho dp^2/4
    EXPECT_EQ(sq.regularized, 0);
  }
}

// rkpm.md 7.3 gates: SNNI alone has spurious, node-to-node sign-alternating
// low modes; NSNI lifts them above the physical lowest. Then the regression
// (+-2 %) on the measured sphere-support table (rkpm.md 7.3 lists box
// supports) and on the critical steps of rkpm.md 5.3 (sphere row).
TEST(RkpmModes, NsniRemovesSpuriousModes) {
  for (Case& c : cases()) {
    const Modes& m = c.m();
    const auto& w = m.omega2;
    const Alternation a = alternation(m.shapes[3]);
    std::printf(
        "a~ = %.1f %-9s lowest non-rigid omega^2: %.5f %.5f %.5f %.5f %.5f (max %.4f, 2/omega_max = %.4f dp/c_d)\n"
        "    lowest mode: alternation along x (u_x %+.3f, u_y %+.3f), along y (u_x %+.3f, u_y %+.3f); "
        "checkerboard correlation u_x %.3f, u_y %.3f\n",
        c.factor, name(c), w[3], w[4], w[5], w[6], w[7], w.back(), critical_step(c), a.A[0][0], a.A[0][1], a.A[1][0],
        a.A[1][1], a.checker[0], a.checker[1]);
    if (c.nsni)
      EXPECT_LT(a.most, 0.0) << name(c) << " a~ = " << c.factor;  // smooth
    else
      EXPECT_GT(a.most, 0.8) << name(c) << " a~ = " << c.factor;  // sign-alternating
  }
  const double snni2 = get(2.0, false).m().omega2[3], nsni2 = get(2.0, true).m().omega2[3];
  const double snni15 = get(1.5, false).m().omega2[3], nsni15 = get(1.5, true).m().omega2[3];
  EXPECT_LE(snni2, 0.02);
  EXPECT_GE(nsni2, 0.055);
  EXPECT_GE(nsni15, 0.055);
  EXPECT_LE(snni15, 0.6 * nsni15);  // a~ = 1.5: spurious too, though above the a~ = 2 gate

  struct Row {
    double factor;
    bool nsni;
    double omega2[5];
    double step;
  };
  const Row rows[] = {
      {2.0, false, {0.01301, 0.01301, 0.01761, 0.02554, 0.02554}, 1.45},
      {2.0, true, {0.05800, 0.06258, 0.06258, 0.07177, 0.08898}, 1.29},
      {1.5, false, {0.03152, 0.03152, 0.05613, 0.06209, 0.06209}, 1.29},
      {1.5, true, {0.06381, 0.07340, 0.07340, 0.07876, 0.10458}, 0.64},
  };
  for (const Row& r : rows) {
    Case& c = get(r.factor, r.nsni);
    for (int k = 0; k < 5; ++k)
      EXPECT_NEAR(c.m().omega2[3 + k], r.omega2[k], 0.02 * r.omega2[k]) << name(c) << " a~ = " << r.factor << " " << k;
    EXPECT_NEAR(critical_step(c), r.step, 0.02 * r.step) << name(c) << " a~ = " << r.factor;
  }
}

// Box supports (`support_shape: box`, the tensor-product cubic B-spline of
// reach a sqrt 2): rkpm.md 7.3's table itself. Measured (fp64):
//   SNNI a~ = 2       0.01328 0.01328 0.01776 (0.02412 0.02412)   rkpm.md 0.0133 0.0133 0.0178
//   SNNI+NSNI a~ = 2  0.05771 0.06210 0.06210 0.07132 0.08845     0.0577 0.0621 0.0621 0.0713 0.0884
//   SNNI+NSNI a~ 1.5  0.06304 0.07185 0.07185 0.07827 0.10226     0.0630 0.0718 0.0718 0.0783 0.1023
// every value within 0.2 % of the table (its rounding); gate 0.5 %.
TEST(RkpmModes, BoxSupportsReproduceTheTable) {
  struct Row {
    double factor;
    bool nsni;
    int count;
    double omega2[5];
  };
  const Row rows[] = {
      {2.0, false, 3, {0.0133, 0.0133, 0.0178, 0, 0}},
      {2.0, true, 5, {0.0577, 0.0621, 0.0621, 0.0713, 0.0884}},
      {1.5, true, 5, {0.0630, 0.0718, 0.0718, 0.0783, 0.1023}},
  };
  for (const Row& r : rows) {
    const Square sq(r.factor, r.nsni, true, true);
    const Modes m = solve_modes(sq);
    const auto& w = m.omega2;
    std::printf("box a~ = %.1f %-9s omega^2: rigid %.1e %.1e %.1e; lowest non-rigid %.5f %.5f %.5f %.5f %.5f\n",
                r.factor, r.nsni ? "SNNI+NSNI" : "SNNI", w[0] / w.back(), w[1] / w.back(), w[2] / w.back(), w[3], w[4],
                w[5], w[6], w[7]);
    for (int k = 0; k < 3; ++k) EXPECT_LE(std::fabs(w[k]), 1e-8 * w.back()) << "rigid mode " << k;
    EXPECT_LE(sq.asymmetry, 1e-10);
    for (int k = 0; k < r.count; ++k)
      EXPECT_NEAR(w[3 + k], r.omega2[k], 0.005 * r.omega2[k]) << "box a~ = " << r.factor << " mode " << k;
  }
}

// Smooth fields barely feel NSNI: the linear shear (y - 5, 0) not at all
// (Psi_I,ki annihilates linear fields), the sine shear sin(pi (y - 5)/10)
// (rkpm.md 3.5: 0.0367 -> 0.0370) by less than 5 % at a~ = 2.
TEST(RkpmModes, SmoothModesBarelyMove) {
  for (double f : {2.0, 1.5}) {
    const Square &snni = get(f, false).square(), &nsni = get(f, true).square();
    const double l0 = snni.rayleigh(linear_shear()), l1 = nsni.rayleigh(linear_shear());
    const double s0 = snni.rayleigh(sine_shear()), s1 = nsni.rayleigh(sine_shear());
    std::printf(
        "a~ = %.1f Rayleigh quotient, SNNI -> SNNI+NSNI: linear shear %.6f -> %.6f (%+.1e), sine shear %.6f -> "
        "%.6f (%+.2f %%)\n",
        f, l0, l1, l1 / l0 - 1.0, s0, s1, 100.0 * (s1 / s0 - 1.0));
    EXPECT_NEAR(l1 / l0, 1.0, 1e-9);
    EXPECT_NEAR(s1 / s0, 1.0, f == 2.0 ? 0.05 : 0.06);
  }
}

// xi_I = 0 on the conforming lattice cells (rkpm.md 3.4): the correction
// leaves K unchanged.
TEST(RkpmModes, VariationalCorrectionVanishesOnLatticeCells) {
  const Square& on = get(2.0, true).square();
  const Square off(2.0, true, false);
  double num = 0, den = 0;
  for (size_t k = 0; k < on.K.size(); ++k) num += (on.K[k] - off.K[k]) * (on.K[k] - off.K[k]), den += on.K[k] * on.K[k];
  std::printf("a~ = 2.0 SNNI+NSNI: |K(VC on) - K(VC off)|/|K| = %.1e\n", std::sqrt(num / den));
  EXPECT_LE(std::sqrt(num / den), 1e-12);
}

}  // namespace
