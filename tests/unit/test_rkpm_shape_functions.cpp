// RKPM shape-function kernels (kernels/rkpm/reproducing_kernel.hpp,
// kernels/rkpm/smoothing_cell.hpp, kernels/rkpm/node_operator.hpp) against
// rkpm.md 1.1-1.7, 3.1-3.2 and the unit targets of 7.1, on analytic
// properties only (no values copied from the code):
//   kernel         B-spline continuity, analytic kernel gradients (regular and
//                  singular) against central differences
//   reproduction   sum Psi = 1, sum Psi x_I = x on a +-0.2 dp perturbed cloud,
//                  2-D and 3-D, a~ = 1.5 and 2.0 (also with per-node supports)
//   implicit grad  Psi^(k)_I reproduces linear gradients, sum Psi^(k)_I = 0;
//                  Psi_I,ki annihilates linear fields, equals the central
//                  difference of Psi^(k)_I, and does NOT reproduce quadratic
//                  second derivatives with the linear basis (measured)
//   singular       Kronecker values 1e-6 a from a flagged node
//   quasi-linear   collinear and nearly collinear clouds, the three modes, the
//                  regulariser's reproduction error against its closed form,
//                  a node covered only by itself
//   cells          sum_f a_f = 0, sum_f (xbar_f - x_L) (x) a_f = V I for full,
//                  clipped, Nanson-mapped and re-celled cells; recell, cond
//   smoothed grad  OperatorFunctor on a host CSR list: sum_I V grad~Psi_I u_I
//                  = V grad u for linear u, sum_I grad~Psi_I = 0, also with
//                  clipped cells and singular boundary nodes, and its NSNI data
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "kernels/rkpm/node_operator.hpp"

using namespace mfsd;
using namespace mfsd::rkpm;

namespace {

template <int D>
using VecD = Vec<D, double>;
template <int D>
using MatD = Mat<D, double>;

constexpr double kDp = 0.37;  // a spacing that is not 1 or a power of 2
constexpr double kPi = 3.14159265358979323846;

template <int D>
VecD<D> origin() {
  VecD<D> o;
  const double c[3] = {1.3, -0.7, 2.1};
  for (int k = 0; k < D; ++k) o.v[k] = c[k];
  return o;
}

// n^D lattice nodes at spacing dp from `o`, each coordinate perturbed uniformly by +-amp dp.
template <int D>
std::vector<VecD<D>> perturbed_lattice(int n, double dp, double amp, const VecD<D>& o, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-amp, amp);
  int total = 1;
  for (int k = 0; k < D; ++k) total *= n;
  std::vector<VecD<D>> x(total);
  for (int i = 0; i < total; ++i) {
    int rest = i;
    for (int k = 0; k < D; ++k) {
      x[i].v[k] = o.v[k] + (double(rest % n) + u(rng)) * dp;
      rest /= n;
    }
  }
  return x;
}

// A uniform point of o + [lo, hi]^D dp.
template <int D>
VecD<D> random_point(const VecD<D>& o, double lo, double hi, double dp, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(lo, hi);
  VecD<D> x;
  for (int k = 0; k < D; ++k) x.v[k] = o.v[k] + u(rng) * dp;
  return x;
}

template <int D>
VecD<D> random_vector(std::mt19937& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  VecD<D> g;
  for (int k = 0; k < D; ++k) g.v[k] = scale * u(rng);
  return g;
}

// I + s U(-1, 1) with det >= 0.3.
template <int D>
MatD<D> random_map(std::mt19937& rng, double s) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (;;) {
    MatD<D> F = MatD<D>::identity();
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) F.m[a][b] += s * u(rng);
    if (det(F) >= 0.3) return F;
  }
}

template <int D>
double max_abs(const MatD<D>& A) {
  double e = 0;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) e = std::max(e, std::fabs(A.m[a][b]));
  return e;
}
template <int D>
double max_abs(const VecD<D>& v) {
  double e = 0;
  for (int a = 0; a < D; ++a) e = std::max(e, std::fabs(v.v[a]));
  return e;
}

// ---------------------------------------------------------------- RK values
// The RK values of every node at x (rkpm.md 1.3), M summed over all nodes
// with their own supports a_I, scaled basis abar.
template <int D>
struct RkEval {
  Solve how;
  int covering;
  MatD<D + 1> M;         // as summed, before solve_moments regularises it
  MatD<D + 1> M_solved;  // as solved: M + eta M_00 diag(0, 1, .., 1) in mode 0
  Vec<D + 1, double> b;
  std::vector<double> w;  // phi_a of each node
  std::vector<double> psi;
};

template <int D>
RkEval<D> rk_eval(const std::vector<VecD<D>>& nodes, const std::vector<double>& a, double abar, const VecD<D>& x,
                  int mode, double tau, int singular = -1) {
  const double inv_abar = 1.0 / abar;
  RkEval<D> r;
  MomentSum<D> ms, regular;  // regular: as OperatorFunctor, the regular kernels' moments for the floor
  r.w.resize(nodes.size());
  for (size_t I = 0; I < nodes.size(); ++I) {
    const VecD<D> y = x - nodes[I];
    r.w[I] = kernel<D>(y, a[I], int(I) == singular).w;
    ms.add(basis<D>(y, inv_abar), r.w[I]);
    regular.add(basis<D>(y, inv_abar), kernel<D>(y, a[I], false).w);
  }
  r.M = ms.M;
  r.covering = ms.covering;
  r.how = solve_moments<D>(ms.M, ms.covering, mode, tau, r.b, singular >= 0 ? &regular.M : nullptr);
  r.M_solved = ms.M;
  r.psi.resize(nodes.size());
  for (size_t I = 0; I < nodes.size(); ++I)
    r.psi[I] = r.w[I] > 0.0 ? shape_value<D, double>(r.b, x - nodes[I], inv_abar, r.w[I]) : 0.0;
  return r;
}

// |sum Psi - 1| and max_k |sum Psi_I x_I,k - x_k| / dp.
struct Reproduction {
  double unity = 0, linear = 0;
};
template <int D>
Reproduction reproduction(const std::vector<VecD<D>>& nodes, const std::vector<double>& psi, const VecD<D>& x,
                          double dp) {
  double s = 0;
  VecD<D> sx = VecD<D>::zero();
  for (size_t I = 0; I < nodes.size(); ++I) s += psi[I], sx += nodes[I] * psi[I];
  return {std::fabs(s - 1.0), max_abs(VecD<D>(sx - x)) / dp};
}

// The regulariser's linear reproduction error in closed form (rkpm.md 1.6).
// With M^ = M/M_00 = [[1, m^T], [m, A + m m^T]] (A the Schur complement of
// step 2), (M^ + eta diag(0, I)) b^ = e_1 gives b^_l = -(A + eta I)^-1 m and
//   sum_I Psi_I x_I - x = -eta abar (A + eta I)^-1 m,
// zero for eta = 0 and the Shepard limit -abar m (minus the kernel-weighted
// mean offset) for eta >> A. eta is read from the solved M.
struct Regularised {
  double eta, sigma_min;
  VecD<2> error;
};
Regularised regulariser_closed_form(const RkEval<2>& r, double abar) {
  const double M00 = r.M.m[0][0];
  const VecD<2> m{{r.M.m[0][1] / M00, r.M.m[0][2] / M00}};
  MatD<2> A;
  for (int p = 0; p < 2; ++p)
    for (int q = 0; q < 2; ++q) A.m[p][q] = r.M.m[p + 1][q + 1] / M00 - m.v[p] * m.v[q];
  Regularised g;
  g.eta = (r.M_solved.m[1][1] - r.M.m[1][1]) / M00;
  // smallest eigenvalue of the symmetric 2 x 2 A, as det / largest (no cancellation)
  const double half = 0.5 * (A.m[0][0] + A.m[1][1]);
  const double big = half + std::sqrt(std::max(0.0, half * half - det(A)));
  g.sigma_min = det(A) / big;
  g.error = inverse(MatD<2>(A + MatD<2>::diagonal(g.eta))) * m * (-g.eta * abar);
  return g;
}

// rkpm.md 1.3 / 7.1: reproduction at `points` random interior points.
template <int D>
Reproduction check_reproduction(int n, double support_factor, int points, bool varied_supports, unsigned seed) {
  std::mt19937 rng(seed);
  const auto nodes = perturbed_lattice<D>(n, kDp, 0.2, origin<D>(), rng);
  std::vector<double> a(nodes.size(), support_factor * kDp);
  std::uniform_real_distribution<double> vary(0.9, 1.1);
  if (varied_supports)
    for (double& ai : a) ai *= vary(rng);
  Reproduction worst;
  for (int p = 0; p < points; ++p) {
    // at least 2.2 dp inside the lattice: every point is covered by a full support
    const VecD<D> x = random_point<D>(origin<D>(), 2.2, n - 3.2, kDp, rng);
    const RkEval<D> r = rk_eval<D>(nodes, a, support_factor * kDp, x, 0, 1e-3);
    EXPECT_EQ(r.how, Solve::linear) << "the regulariser must be inactive at a well-covered point";
    const Reproduction e = reproduction<D>(nodes, r.psi, x, kDp);
    worst.unity = std::max(worst.unity, e.unity);
    worst.linear = std::max(worst.linear, e.linear);
  }
  std::printf("RK reproduction %dD a~ = %.2f%s: max |sum Psi - 1| = %.3g, max |sum Psi x_I - x|/dp = %.3g\n", D,
              support_factor, varied_supports ? " (a_I varied +-10%)" : "", worst.unity, worst.linear);
  EXPECT_LE(worst.unity, 1e-13);
  EXPECT_LE(worst.linear, 1e-13);
  return worst;
}

// ------------------------------------------------------ implicit gradient
template <int D>
struct Implicit {
  bool ok;
  double eta;
  ImplicitGradient<D, double> g;
  std::vector<KernelSample<D>> s;
  std::vector<Vec<D + 1, double>> h;
};

// The NSNI data at x (rkpm.md 1.5), regularised as OperatorFunctor does with tau.
template <int D>
Implicit<D> implicit_at(const std::vector<VecD<D>>& nodes, double a, const VecD<D>& x, double tau) {
  const double inv_abar = 1.0 / a;
  Implicit<D> r;
  MomentSum<D> ms;
  MomentDerivativeSum<D> dm;
  r.s.resize(nodes.size());
  r.h.resize(nodes.size());
  for (size_t I = 0; I < nodes.size(); ++I) {
    const VecD<D> y = x - nodes[I];
    r.s[I] = kernel<D>(y, a, false);
    r.h[I] = basis<D>(y, inv_abar);
    ms.add(r.h[I], r.s[I].w);
    if (r.s[I].w > 0.0) dm.add(r.h[I], r.s[I], inv_abar);
  }
  r.eta = regularize<D>(ms.M, tau);
  r.ok = implicit_gradient<D, double>(ms.M, dm, r.g);
  return r;
}

// Psi^(k)_I = -(1/abar) e_{k+1}^T M^-1 H phi (rkpm.md 1.5).
template <int D>
double implicit_value(const Implicit<D>& d, size_t I, int k, double inv_abar) {
  return -inv_abar * dot(d.g.inverse_row[k], d.h[I]) * d.s[I].w;
}

// ------------------------------------------------- operators on a host list
// Runs OperatorFunctor over a brute-force CSR list (every node in every
// row, itself first), as stage 5 of rkpm.md 5.2 does on its own list.
template <int D>
struct HostOperators {
  std::vector<VecD<D>> x;
  std::vector<double> a;
  std::vector<unsigned char> singular;
  std::vector<MatD<D>> F;
  std::vector<VecD<D>> lo, hi;
  std::vector<PairIndex> offsets;
  std::vector<Index> neighbor;
  std::vector<NodeOperator<D, double>> op;
  std::vector<ImplicitGradient<D, double>> nsni;
  std::vector<double> reach, nearest;
  std::vector<unsigned char> status;

  explicit HostOperators(std::vector<VecD<D>> nodes, double support)
      : x(std::move(nodes)),
        a(x.size(), support),
        singular(x.size(), 0),
        F(x.size(), MatD<D>::identity()),
        lo(x.size(), VecD<D>::constant(0.5 * kDp)),
        hi(x.size(), VecD<D>::constant(0.5 * kDp)) {}

  void build(bool box_cells, int mode, double tau) {
    const Index n = Index(x.size());
    offsets.assign(1, 0);
    neighbor.clear();
    for (Index L = 0; L < n; ++L) {
      neighbor.push_back(L);
      for (Index I = 0; I < n; ++I)
        if (I != L) neighbor.push_back(I);
      offsets.push_back(PairIndex(neighbor.size()));
    }
    neighbor.resize(neighbor.size() + kPairPrefetchDistance, 0);
    op.resize(n);
    nsni.resize(n);
    reach.assign(n, 0.0);
    nearest.assign(n, 0.0);
    status.assign(n, 0xff);
    OperatorFunctor<D, double> f;
    f.rows = PairList<D, double>{offsets.data(), neighbor.data(), nullptr, nullptr, nullptr, nullptr};
    f.nodes = NodeFields<D, double>{x.data(), a.data(), singular.data()};
    f.cell_map = F.data();
    f.cell_lo = lo.data();
    f.cell_hi = hi.data();
    f.box_cells = box_cells;
    f.quasi_linear = mode;
    f.tau = tau;
    f.op = op.data();
    f.nsni = nsni.data();
    f.reach = reach.data();
    f.nearest = nearest.data();
    f.status = status.data();
    for (Index L = 0; L < n; ++L) f(L);
  }

  // V_L grad~Psi_I(x_L) for every I (rkpm.md 3.1).
  std::vector<VecD<D>> smoothed(Index L) const {
    std::vector<VecD<D>> g(x.size());
    for (size_t I = 0; I < x.size(); ++I)
      g[I] =
          smoothed_gradient_volume<D, double>(op[L], Index(I), x[L] - x[I], a[I], singular[I] != 0, false, 0, nullptr);
    return g;
  }
};

struct GradientErrors {
  double linear = 0, sum = 0, moment = 0;  // relative to V |grad u|, V/dp, V
};

// sum_I (V grad~Psi_I) u(x_I) = V grad u (u linear), sum_I V grad~Psi_I = 0,
// sum_I (x_I - x_L) (x) V grad~Psi_I = V I (rkpm.md 3.1).
template <int D>
GradientErrors smoothed_gradient_errors(const HostOperators<D>& h, Index L, const VecD<D>& grad_u, double u0) {
  const std::vector<VecD<D>> g = h.smoothed(L);
  const double V = h.op[L].volume;
  VecD<D> gu = VecD<D>::zero(), gs = VecD<D>::zero();
  MatD<D> gx = MatD<D>::zero();
  for (size_t I = 0; I < g.size(); ++I) {
    gu += g[I] * (u0 + dot(grad_u, h.x[I]));
    gs += g[I];
    gx += outer(VecD<D>(h.x[I] - h.x[L]), g[I]);
  }
  GradientErrors e;
  e.linear = max_abs(VecD<D>(gu - grad_u * V)) / (V * norm(grad_u));
  e.sum = max_abs(gs) * kDp / V;
  e.moment = max_abs(MatD<D>(gx - MatD<D>::diagonal(V))) / V;
  return e;
}

// The cell identities of rkpm.md 3.1 for mapped faces of F: sum_f a_f = 0
// (relative to max |a_f|) and sum_f offset_f (x) a_f = V I (relative to V),
// and V = det F prod(lo + hi).
template <int D>
void check_cell(const MatD<D>& F, const VecD<D>& lo, const VecD<D>& hi, double& worst_sum, double& worst_moment) {
  const CellFaces<D> c = mapped_faces<D>(F, lo, hi);
  double V0 = 1;
  for (int k = 0; k < D; ++k) V0 *= lo.v[k] + hi.v[k];
  EXPECT_NEAR(c.volume, det(F) * V0, 1e-15 * std::fabs(det(F) * V0));
  VecD<D> s = VecD<D>::zero();
  MatD<D> m = MatD<D>::zero();
  double amax = 0;
  for (int f = 0; f < 2 * D; ++f) {
    s += c.area[f];
    m += outer(c.offset[f], c.area[f]);
    amax = std::max(amax, norm(c.area[f]));
  }
  const double es = max_abs(s) / amax, em = max_abs(MatD<D>(m - MatD<D>::diagonal(c.volume))) / c.volume;
  EXPECT_LE(es, 1e-14);
  EXPECT_LE(em, 1e-14);
  worst_sum = std::max(worst_sum, es);
  worst_moment = std::max(worst_moment, em);
}

}  // namespace

// ============================================================== rkpm.md 1.1
TEST(RkpmShapeFunctions, BsplineIsC2AndKernelGradientsMatchDifferences) {
  // phi, phi' and phi'' continuous at z = 1/2 and z = 1 (C2 cubic B-spline).
  const double e = 1e-9;
  EXPECT_NEAR(bspline(0.5 - e), bspline(0.5 + e), 1e-8);
  EXPECT_NEAR(bspline_derivative(0.5 - e), bspline_derivative(0.5 + e), 1e-8);
  EXPECT_NEAR(bspline(1.0 - e), 0.0, 1e-8);
  EXPECT_NEAR(bspline_derivative(1.0 - e), 0.0, 1e-8);
  EXPECT_EQ(bspline(1.0), 0.0);
  EXPECT_EQ(bspline(1.5), 0.0);
  EXPECT_NEAR(bspline(0.0), 2.0 / 3.0, 1e-16);
  // phi'' from one-sided differences of phi': 4 on both sides of 1/2, 0 at 1-.
  const double h2 = 1e-7;
  EXPECT_NEAR((bspline_derivative(0.5) - bspline_derivative(0.5 - h2)) / h2, 4.0, 1e-5);
  EXPECT_NEAR((bspline_derivative(0.5 + h2) - bspline_derivative(0.5)) / h2, 4.0, 1e-5);
  EXPECT_NEAR((bspline_derivative(1.0 - h2) - bspline_derivative(1.0 - 2 * h2)) / h2, 0.0, 1e-5);
  // phi' is the derivative of phi on both branches.
  for (double z : {0.1, 0.3, 0.49, 0.51, 0.7, 0.95}) {
    const double h = 1e-6;
    EXPECT_NEAR(bspline_derivative(z), (bspline(z + h) - bspline(z - h)) / (2 * h), 1e-8) << z;
  }
  // Strict support r < a (rkpm.md 1.2).
  EXPECT_EQ((kernel<2>(VecD<2>{{1.0, 0.0}}, 1.0, false).w), 0.0);
  // Analytic gradients of the regular and singular kernel (rkpm.md 1.1, 1.7).
  std::mt19937 rng(11);
  double worst = 0;
  for (int t = 0; t < 200; ++t) {
    const double a = 0.8;
    VecD<3> y = random_vector<3>(rng, 0.6);
    if (norm(y) < 0.05 || std::fabs(norm(y) / a - 0.5) < 1e-3 || norm(y) > 0.99 * a) continue;
    for (bool sing : {false, true}) {
      const KernelSample<3> s = kernel<3>(y, a, sing);
      const double z = norm(y) / a;
      // Round-off of the polynomial, whose terms are O(1) (4/3 - 4z + ...
      // cancels towards z = 1): the compiler may fuse its multiply-adds
      // differently in the kernel and here, so the bound is absolute
      // (measured up to 3.9e-16 / z^2).
      EXPECT_NEAR(s.w, sing ? bspline(z) / (z * z) : bspline(z), 2e-15 / (sing ? z * z : 1.0));
      const double h = 1e-6 * a;
      for (int k = 0; k < 3; ++k) {
        VecD<3> yp = y, ym = y;
        yp.v[k] += h, ym.v[k] -= h;
        const double fd = (kernel<3>(yp, a, sing).w - kernel<3>(ym, a, sing).w) / (2 * h);
        const double err = std::fabs(s.gradient.v[k] - fd) / (norm(s.gradient) + 1.0 / a);
        worst = std::max(worst, err);
        EXPECT_LE(err, 1e-7) << "component " << k << " singular " << sing;
      }
    }
  }
  std::printf("kernel gradient vs central difference: max relative error %.3g\n", worst);
}

// ============================================================== rkpm.md 1.3
TEST(RkpmShapeFunctions, ReproductionOnPerturbedCloud2d) {
  for (double f : {1.5, 2.0}) check_reproduction<2>(12, f, 400, false, 2024);
  check_reproduction<2>(12, 1.75, 200, true, 7);
}

TEST(RkpmShapeFunctions, ReproductionOnPerturbedCloud3d) {
  for (double f : {1.5, 2.0}) check_reproduction<3>(8, f, 150, false, 2025);
  check_reproduction<3>(8, 1.75, 80, true, 8);
}

// The scaling abar leaves Psi unchanged (rkpm.md 1.3).
TEST(RkpmShapeFunctions, BasisScalingLeavesShapeFunctionsUnchanged) {
  std::mt19937 rng(5);
  const auto nodes = perturbed_lattice<2>(10, kDp, 0.2, origin<2>(), rng);
  const std::vector<double> a(nodes.size(), 2.0 * kDp);
  double worst = 0;
  for (int p = 0; p < 50; ++p) {
    const VecD<2> x = random_point<2>(origin<2>(), 2.2, 6.8, kDp, rng);
    const RkEval<2> r1 = rk_eval<2>(nodes, a, 2.0 * kDp, x, 0, 1e-3);
    const RkEval<2> r2 = rk_eval<2>(nodes, a, 0.7 * kDp, x, 0, 1e-3);
    ASSERT_EQ(r1.how, Solve::linear);
    ASSERT_EQ(r2.how, Solve::linear);
    for (size_t I = 0; I < nodes.size(); ++I) worst = std::max(worst, std::fabs(r1.psi[I] - r2.psi[I]));
  }
  std::printf("RK basis scaling abar = 2 dp vs 0.7 dp: max |dPsi| = %.3g\n", worst);
  EXPECT_LE(worst, 1e-14);
}

// ============================================================== rkpm.md 1.5
namespace {
template <int D>
void check_implicit_gradient(int n, double support_factor, int points, unsigned seed) {
  std::mt19937 rng(seed);
  const auto nodes = perturbed_lattice<D>(n, kDp, 0.2, origin<D>(), rng);
  const double a = support_factor * kDp, inv_abar = 1.0 / a;
  double e_grad = 0, e_sum = 0, e_lin2 = 0, e_fd = 0, e_quad = 0, e_quad_identity = 0, e_q0 = 0, asym = 0;
  for (int p = 0; p < points; ++p) {
    const VecD<D> x = random_point<D>(origin<D>(), 2.2, n - 3.2, kDp, rng);
    const Implicit<D> d = implicit_at<D>(nodes, a, x, 1e-3);
    ASSERT_TRUE(d.ok);
    EXPECT_EQ(d.eta, 0.0) << "regulariser active at a well-covered point";
    const VecD<D> grad_u = random_vector<D>(rng);
    const double u0 = 0.37;
    // Implicit gradient: sum Psi^(k) u_I = du/dx_k, sum Psi^(k) = 0.
    for (int k = 0; k < D; ++k) {
      double gu = 0, s = 0;
      for (size_t I = 0; I < nodes.size(); ++I) {
        const double v = implicit_value<D>(d, I, k, inv_abar);
        gu += v * (u0 + dot(grad_u, nodes[I]));
        s += v;
      }
      e_grad = std::max(e_grad, std::fabs(gu - grad_u.v[k]) / norm(grad_u));
      e_sum = std::max(e_sum, std::fabs(s) * kDp);
    }
    // Psi_I,ki, and Psi^(k)_I at x +- h e_i (central differences, step 1e-6 dp).
    std::vector<MatD<D>> second(nodes.size());
    double scale = 0;
    for (size_t I = 0; I < nodes.size(); ++I) {
      second[I] = implicit_second_derivatives<D, double>(d.g, d.h[I], d.s[I], inv_abar);
      scale = std::max(scale, max_abs(second[I]));
    }
    const double hfd = 1e-6 * kDp;
    for (int i = 0; i < D; ++i) {
      VecD<D> xp = x, xm = x;
      xp.v[i] += hfd, xm.v[i] -= hfd;
      const Implicit<D> dp = implicit_at<D>(nodes, a, xp, 1e-3), dm = implicit_at<D>(nodes, a, xm, 1e-3);
      for (int k = 0; k < D; ++k) {
        // derivative of the implicit gradient against its central difference
        for (size_t I = 0; I < nodes.size(); ++I) {
          const double fd = (implicit_value<D>(dp, I, k, inv_abar) - implicit_value<D>(dm, I, k, inv_abar)) / (2 * hfd);
          e_fd = std::max(e_fd, std::fabs(second[I].m[k][i] - fd) / scale);
          asym = std::max(asym, std::fabs(second[I].m[k][i] - second[I].m[i][k]) / scale);
        }
        // linear u: sum Psi_I,ki u_I = 0
        double lin = 0;
        for (size_t I = 0; I < nodes.size(); ++I) lin += second[I].m[k][i] * (u0 + dot(grad_u, nodes[I]));
        e_lin2 = std::max(e_lin2, std::fabs(lin) / (norm(grad_u) / kDp));
        // quadratic u(x') = (x' - x)_m (x' - x)_n, u(x_I) = y_m y_n,
        // d2u/dx_k dx_i = d_mk d_ni + d_mi d_nk. The linear basis only makes
        // the implicit gradient exact for linear fields: at any x',
        //   sum_I Psi^(k)_I(x') u(x_I) = du/dx_k(x') + Q_kmn(x'),
        //   Q_kmn(x') = sum_I Psi^(k)_I(x') (x' - x_I)_m (x' - x_I)_n,
        // (exact algebra with sum Psi^(k)_I = 0, sum Psi^(k)_I (x' - x_I) = -e_k),
        // an O(h) error whose derivative is O(1): Psi_I,ki gives the second
        // derivative plus dQ_kmn/dx_i, not the second derivative.
        for (int m = 0; m < D; ++m)
          for (int nn = 0; nn < D; ++nn) {
            double q = 0, Q0 = 0, Qp = 0, Qm = 0;
            for (size_t I = 0; I < nodes.size(); ++I) {
              const VecD<D> y = x - nodes[I], yp = xp - nodes[I], ym = xm - nodes[I];
              q += second[I].m[k][i] * y.v[m] * y.v[nn];
              Q0 += implicit_value<D>(d, I, k, inv_abar) * y.v[m] * y.v[nn];
              Qp += implicit_value<D>(dp, I, k, inv_abar) * yp.v[m] * yp.v[nn];
              Qm += implicit_value<D>(dm, I, k, inv_abar) * ym.v[m] * ym.v[nn];
            }
            const double exact = double(m == k && nn == i) + double(m == i && nn == k);
            const double dQ = (Qp - Qm) / (2 * hfd);
            e_quad = std::max(e_quad, std::fabs(q - exact));
            e_quad_identity = std::max(e_quad_identity, std::fabs(q - exact - dQ));
            e_q0 = std::max(e_q0, std::fabs(Q0) / kDp);
          }
      }
    }
  }
  std::printf(
      "implicit gradient %dD a~ = %.2f: linear gradient %.3g, sum Psi^(k) dp %.3g; Psi_I,ki: linear %.3g (x dp/|g|), "
      "vs central difference %.3g, asymmetry %.3g; quadratic: second-derivative error %.3g, minus dQ/dx_i %.3g, "
      "implicit gradient error |Q|/dp %.3g\n",
      D, support_factor, e_grad, e_sum, e_lin2, e_fd, asym, e_quad, e_quad_identity, e_q0);
  EXPECT_LE(e_grad, 1e-12);
  EXPECT_LE(e_sum, 1e-12);
  EXPECT_LE(e_lin2, 1e-10);
  EXPECT_LE(e_fd, 1e-6);
  // the second-derivative error of the quadratic is exactly dQ/dx_i ...
  EXPECT_LE(e_quad_identity, 1e-6 * std::max(1.0, e_quad));
  // ... and O(1): the linear basis does not reproduce quadratic second derivatives
  EXPECT_GT(e_quad, 0.1);
}
}  // namespace

TEST(RkpmImplicitGradient, LinearConsistencyAndDerivative2d) {
  for (double f : {1.5, 2.0}) check_implicit_gradient<2>(12, f, 60, 31);
}
TEST(RkpmImplicitGradient, LinearConsistencyAndDerivative3d) {
  for (double f : {1.5, 2.0}) check_implicit_gradient<3>(8, f, 20, 32);
}

// ============================================================== rkpm.md 1.7
// Psi at `z` a from the flagged node J in 16 directions: worst |1 - Psi_J|,
// max |Psi_I|, |sum Psi - 1|, linear error / dp, and the mismatch of the
// linear error against the regulariser's closed form (relative to |x - x_J|).
namespace {
struct SingularErrors {
  double kron = 0, other = 0, unity = 0, linear = 0, closed_form = 0;
  int regularised = 0;
};
SingularErrors singular_errors(const std::vector<VecD<2>>& nodes, int J, double a, double z, double tau) {
  const std::vector<double> as(nodes.size(), a);
  SingularErrors e;
  for (int t = 0; t < 16; ++t) {
    const double th = 2 * kPi * t / 16 + 0.1;
    const VecD<2> x = nodes[J] + VecD<2>{{std::cos(th), std::sin(th)}} * (z * a);
    const RkEval<2> r = rk_eval<2>(nodes, as, a, x, 0, tau, J);
    EXPECT_NE(r.how, Solve::failed);
    if (r.how == Solve::regularized) ++e.regularised;
    e.kron = std::max(e.kron, std::fabs(1.0 - r.psi[J]));
    for (size_t I = 0; I < nodes.size(); ++I)
      if (int(I) != J) e.other = std::max(e.other, std::fabs(r.psi[I]));
    const Reproduction rp = reproduction<2>(nodes, r.psi, x, kDp);
    e.unity = std::max(e.unity, rp.unity);
    e.linear = std::max(e.linear, rp.linear);
    VecD<2> err = VecD<2>::zero();
    for (size_t I = 0; I < nodes.size(); ++I) err += (nodes[I] - x) * r.psi[I];
    const Regularised g = regulariser_closed_form(r, a);
    e.closed_form = std::max(e.closed_form, norm(VecD<2>(err - g.error)) / (z * a));
  }
  return e;
}

std::vector<VecD<2>> lattice_2d(int n, double amp, unsigned seed) {
  std::mt19937 rng(seed);
  return perturbed_lattice<2>(n, kDp, amp, origin<2>(), rng);
}
}  // namespace

// At 1e-6 a from a flagged node (rkpm.md 1.7, 7.1). Two solves:
//  - tau = 0 (the plain linear solve, what rkpm.md 1.7 describes:
//    "reproduction is unaffected"): linear reproduction to round-off; the
//    Kronecker defect is O(z): the other nodes must carry the first moment
//    Psi_J y_J of the flagged node, |Psi_I| ~ c z with c = 0.74 (lattice,
//    a~ = 1.5) .. 1.19 (perturbed cloud, a~ = 1.5), so the 1e-6 target holds
//    on the lattice and is exceeded by 19 % on the perturbed cloud at a~ = 1.5;
//  - the default tau = 1e-3 (the production path): the singular weight
//    phi/z^2 dominates M_00, the covariance floor of M/M_00 is ~1e-12 < tau
//    and the regulariser switches on (up to z ~ 0.05-0.1, see the disabled
//    test below): the values are near-Shepard, Kronecker to 1e-12, sum Psi = 1
//    exact, but the linear reproduction error is the regulariser's closed
//    form, about |x - x_J| (the Shepard limit), not round-off.
TEST(RkpmSingularKernel, KroneckerValuesNearAFlaggedNode) {
  const double z = 1e-6;
  const int J = 4 + 10 * 5;  // an interior node
  for (double amp : {0.0, 0.2})
    for (double f : {1.5, 2.0}) {
      const auto nodes = lattice_2d(10, amp, 41);
      const double a = f * kDp;
      const SingularErrors plain = singular_errors(nodes, J, a, z, 0.0);
      const SingularErrors dflt = singular_errors(nodes, J, a, z, 1e-3);
      for (const SingularErrors* e : {&plain, &dflt})
        std::printf(
            "singular kernel, %s, a~ = %.1f, z = 1e-6, tau = %s: regularised %d/16, |1 - Psi_J| = %.3g, max |Psi_I| = "
            "%.3g, |sum Psi - 1| = %.3g, linear error/dp = %.3g, closed-form mismatch %.3g\n",
            amp > 0 ? "perturbed cloud" : "lattice", f, e == &plain ? "0   " : "1e-3", e->regularised, e->kron,
            e->other, e->unity, e->linear, e->closed_form);
      // plain linear solve
      EXPECT_EQ(plain.regularised, 0);
      EXPECT_LE(plain.unity, 1e-13);
      EXPECT_LE(plain.linear, 1e-13);
      EXPECT_LE(plain.kron, 1e-6);
      EXPECT_LE(plain.other, amp > 0 ? 1.5e-6 : 1e-6);  // O(z): see above
      // default regulariser, its floor judged on the regular kernels' moments
      // (reproducing_kernel.hpp, regularize): the plain solve's values
      EXPECT_EQ(dflt.regularised, 0);
      EXPECT_LE(dflt.kron, 1e-6);
      EXPECT_LE(dflt.other, amp > 0 ? 1.5e-6 : 1e-6);
      EXPECT_LE(dflt.unity, 1e-13);
      EXPECT_LE(dflt.linear, 1e-13);
    }
}

// rkpm.md 1.7: reproduction is unaffected by the singular kernel, also with
// the default quasi-linear setting (regularize, tau = 1e-3, rkpm.md 1.6).
// With the floor sigma_min judged on M/M_00 itself it was not, within
// z < ~0.1 of a flagged node (the singular weight phi/z^2 made the cloud look
// degenerate): linear error 1.5e-6 / 2e-6 dp at z = 1e-6, 1.5e-2 / 2e-2 dp at
// z = 1e-2, up to 6e-2 dp at z = 0.05 (lattice and perturbed cloud,
// a~ = 1.5 / 2.0). The floor now comes from the regular kernels' moments.
TEST(RkpmSingularKernel, LinearReproductionWithDefaultRegulariser) {
  const int J = 4 + 10 * 5;
  for (double amp : {0.0, 0.2})
    for (double f : {1.5, 2.0})
      for (double z : {1e-6, 1e-4, 1e-2, 5e-2}) {
        const SingularErrors e = singular_errors(lattice_2d(10, amp, 41), J, f * kDp, z, 1e-3);
        std::printf(
            "singular kernel, tau = 1e-3, amp %.1f, a~ = %.1f, z = %g: regularised %d/16, linear error/dp %.3g\n", amp,
            f, z, e.regularised, e.linear);
        EXPECT_LE(e.linear, 1e-13) << "z = " << z;
      }
}

// ============================================================== rkpm.md 1.6
TEST(RkpmQuasiLinear, CollinearCloudModes) {
  std::mt19937 rng(51);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  const VecD<2> t{{std::cos(0.3), std::sin(0.3)}};
  std::vector<VecD<2>> nodes;
  for (int i = 0; i < 20; ++i) nodes.push_back(origin<2>() + t * ((i + u(rng)) * kDp));
  const double a = 2.0 * kDp;
  const std::vector<double> as(nodes.size(), a);
  double e_unity = 0, e_lin = 0;
  std::uniform_real_distribution<double> s(3.0, 16.0);
  for (int p = 0; p < 100; ++p) {
    const VecD<2> x = origin<2>() + t * (s(rng) * kDp);
    const RkEval<2> r0 = rk_eval<2>(nodes, as, a, x, 0, 1e-3);
    EXPECT_EQ(r0.how, Solve::regularized);
    for (double v : r0.psi) ASSERT_TRUE(std::isfinite(v));
    const Reproduction e = reproduction<2>(nodes, r0.psi, x, kDp);
    e_unity = std::max(e_unity, e.unity);
    e_lin = std::max(e_lin, e.linear);
    // mode 1: Shepard, b = [1/sum phi, 0, 0]
    const RkEval<2> r1 = rk_eval<2>(nodes, as, a, x, 1, 1e-3);
    EXPECT_EQ(r1.how, Solve::shepard);
    double sw = 0;
    for (double w : r1.w) sw += w;
    EXPECT_NEAR(r1.b.v[0], 1.0 / sw, 1e-15 / sw);
    EXPECT_EQ(r1.b.v[1], 0.0);
    EXPECT_EQ(r1.b.v[2], 0.0);
    for (size_t I = 0; I < nodes.size(); ++I) EXPECT_NEAR(r1.psi[I], r1.w[I] / sw, 1e-15);
    // mode 2: off
    const RkEval<2> r2 = rk_eval<2>(nodes, as, a, x, 2, 1e-3);
    EXPECT_EQ(r2.how, Solve::failed);
  }
  std::printf("collinear cloud, regularised (tau 1e-3): max |sum Psi - 1| = %.3g, linear error/dp = %.3g\n", e_unity,
              e_lin);
  EXPECT_LE(e_unity, 1e-14);
}

// rkpm.md 1.6: the regulariser's linear reproduction error on a nearly
// collinear cloud (20 nodes along a tilted line, +-0.2 dp along it, +-1e-9 dp
// across it, so sigma_min ~ 1e-19 << tau and eta = tau at every point;
// evaluation points on the line). The error is checked against the closed
// form of regulariser_closed_form (eta = max(0, tau - sigma_min) with
// sigma_min computed here) and its growth with tau is measured against the
// values rkpm.md 1.6 quotes (5e-7 h, 5e-4 h, 3e-2 h for eta = 1e-6, 1e-3,
// 1e-1): the same order of magnitude; measured, the mean over 200 points at
// a~ = 1.5 is 5.5e-7, 5.4e-4, 2.3e-2 dp, the worst 2.0e-6, 2.0e-3, 7.9e-2 dp
// (the quoted cloud is not specified): asserted within a factor of 3 (mean)
// and 5 (worst).
TEST(RkpmQuasiLinear, RegulariserErrorGrowsWithTau) {
  std::mt19937 rng(52);
  std::uniform_real_distribution<double> u(-0.2, 0.2), perp(-1e-9, 1e-9);
  const VecD<2> t{{std::cos(0.3), std::sin(0.3)}}, nrm{{-std::sin(0.3), std::cos(0.3)}};
  std::vector<VecD<2>> nodes;
  for (int i = 0; i < 20; ++i) nodes.push_back(origin<2>() + t * ((i + u(rng)) * kDp) + nrm * (perp(rng) * kDp));
  std::uniform_real_distribution<double> s(3.0, 16.0);
  std::vector<VecD<2>> points;
  for (int p = 0; p < 200; ++p) points.push_back(origin<2>() + t * (s(rng) * kDp));
  const double taus[3] = {1e-6, 1e-3, 1e-1}, quoted[3] = {5e-7, 5e-4, 3e-2};
  for (double f : {1.5, 2.0}) {
    const double a = f * kDp;
    const std::vector<double> as(nodes.size(), a);
    double worst[3] = {0, 0, 0}, mean[3] = {0, 0, 0}, across[3] = {0, 0, 0};
    double mismatch = 0, eta_error = 0, sigma_max = 0;
    for (int it = 0; it < 3; ++it) {
      for (const VecD<2>& x : points) {
        const RkEval<2> r = rk_eval<2>(nodes, as, a, x, 0, taus[it]);
        ASSERT_EQ(r.how, Solve::regularized);
        VecD<2> err = VecD<2>::zero();
        for (size_t I = 0; I < nodes.size(); ++I) err += (nodes[I] - x) * r.psi[I];
        const Regularised g = regulariser_closed_form(r, a);
        sigma_max = std::max(sigma_max, g.sigma_min);
        eta_error = std::max(eta_error, std::fabs(g.eta - std::max(0.0, taus[it] - g.sigma_min)) / taus[it]);
        mismatch = std::max(mismatch, norm(VecD<2>(err - g.error)) / norm(g.error));
        worst[it] = std::max(worst[it], norm(err) / kDp);
        mean[it] += norm(err) / kDp / double(points.size());
        across[it] = std::max(across[it], std::fabs(dot(err, nrm)) / kDp);
      }
      std::printf(
          "nearly collinear cloud a~ = %.1f, tau = %g: linear error max %.3g dp, mean %.3g dp, across the line %.3g "
          "dp (rkpm.md quotes %g h)\n",
          f, taus[it], worst[it], mean[it], across[it], quoted[it]);
    }
    std::printf(
        "  sigma_min <= %.3g, eta vs max(0, tau - sigma_min) %.3g, closed-form mismatch %.3g, "
        "ratios to quoted %.2f %.2f %.2f\n",
        sigma_max, eta_error, mismatch, worst[0] / quoted[0], worst[1] / quoted[1], worst[2] / quoted[2]);
    EXPECT_LE(sigma_max, 1e-15);
    EXPECT_LE(eta_error, 1e-9);  // eta read back from M + eta M_00: 1e-16 M_11 / (eta M_00)
    EXPECT_LE(mismatch, 1e-6);
    EXPECT_GT(worst[1], worst[0]);
    EXPECT_GT(worst[2], worst[1]);
    // linear in eta while eta << A's non-degenerate eigenvalue: the ratio is
    // 1000 (lambda + 1e-6)/(lambda + 1e-3) per point, a little under 1000
    EXPECT_GT(worst[1] / worst[0], 800.0);
    EXPECT_LE(worst[1] / worst[0], 1000.0 * (1 + 1e-6));
    for (int it = 0; it < 3; ++it) {
      EXPECT_GT(worst[it], 0.2 * quoted[it]) << "tau " << taus[it];
      EXPECT_LT(worst[it], 5.0 * quoted[it]) << "tau " << taus[it];
      EXPECT_GT(mean[it], quoted[it] / 3) << "tau " << taus[it];
      EXPECT_LT(mean[it], 3 * quoted[it]) << "tau " << taus[it];
    }
  }
}

TEST(RkpmQuasiLinear, NodeCoveredOnlyByItselfGetsOne) {
  const std::vector<VecD<3>> nodes = {origin<3>()};
  const std::vector<double> as = {2.0 * kDp};
  std::mt19937 rng(53);
  for (int p = 0; p < 20; ++p) {
    const VecD<3> x = p == 0 ? nodes[0] : nodes[0] + random_vector<3>(rng, 0.5 * kDp);
    for (int mode : {0, 1}) {
      const RkEval<3> r = rk_eval<3>(nodes, as, 2.0 * kDp, x, mode, 1e-3);
      EXPECT_EQ(r.how, mode == 0 ? Solve::regularized : Solve::shepard);
      EXPECT_NEAR(r.psi[0], 1.0, 1e-13) << "mode " << mode;
    }
    EXPECT_EQ((rk_eval<3>(nodes, as, 2.0 * kDp, x, 2, 1e-3).how), Solve::failed);
  }
  // Through OperatorFunctor: Psi = 1 at the node, grad~Psi = 0 (a free fragment).
  HostOperators<3> h(nodes, 2.0 * kDp);
  h.build(false, 0, 1e-3);
  EXPECT_EQ(h.status[0], 1u | 4u);
  EXPECT_NEAR((shape_at<3, double>(h.op[0], 6, 0, VecD<3>::zero(), h.a[0], false, false)), 1.0, 1e-15);
  const auto g = h.smoothed(0);
  EXPECT_LE(max_abs(g[0]), 1e-15 * h.op[0].volume / kDp);
}

// ========================================================== rkpm.md 3.1-3.2
namespace {
template <int D>
void check_cells(unsigned seed) {
  std::mt19937 rng(seed);
  double es = 0, em = 0;
  for (int t = 0; t < 200; ++t) {
    // full cell, then random clipping of each side
    VecD<D> lo = VecD<D>::constant(0.5 * kDp), hi = lo;
    if (t > 0)
      for (int k = 0; k < D; ++k) {
        if (rng() % 3 == 0)
          lo.v[k] = 0;
        else if (rng() % 3 == 0)
          hi.v[k] = 0;
      }
    check_cell<D>(MatD<D>::identity(), lo, hi, es, em);
    const MatD<D> F = random_map<D>(rng, 0.4);
    check_cell<D>(F, lo, hi, es, em);
    // recell: det kept, F' = J^(1/d) R with R the polar rotation of F
    const MatD<D> Fr = recell<D>(F);
    const double J = det(F);
    EXPECT_NEAR(det(Fr), J, 1e-14 * J);
    const MatD<D> R = Fr * (1.0 / std::pow(J, 1.0 / D));
    EXPECT_LE(max_abs(MatD<D>(transpose(R) * R - MatD<D>::identity())), 1e-14);
    EXPECT_NEAR(det(R), 1.0, 1e-14);
    const MatD<D> U = transpose(R) * F;  // the stretch: symmetric positive definite
    EXPECT_LE(max_abs(MatD<D>(U - transpose(U))), 1e-14 * max_abs(F));
    const SymmetricEigen<D, double> eu = eigen_symmetric(U);
    for (int k = 0; k < D; ++k) EXPECT_GT(eu.values.v[k], 0.0);
    EXPECT_NEAR(condition_number<D>(Fr), 1.0, 1e-13);
    check_cell<D>(Fr, lo, hi, es, em);
    // box cells: J^(1/d) I
    const MatD<D> B = box_map<D>(F);
    EXPECT_NEAR(det(B), J, 1e-14 * J);
    EXPECT_LE(max_abs(MatD<D>(B - MatD<D>::diagonal(B.m[0][0]))), 0.0);
    check_cell<D>(B, lo, hi, es, em);
  }
  std::printf(
      "cells %dD (full, clipped, mapped, re-celled, box): max |sum a_f|/|a| = %.3g, max |sum dx (x) a - VI|/V = %.3g\n",
      D, es, em);
}
}  // namespace

TEST(RkpmSmoothingCell, CellIdentitiesAndRecell) {
  check_cells<2>(61);
  check_cells<3>(62);
  MatD<2> A2 = MatD<2>::zero();
  A2.m[0][0] = 1, A2.m[1][1] = 4;
  EXPECT_NEAR(condition_number<2>(A2), 4.0, 1e-15 * 4);
  MatD<3> A3 = MatD<3>::zero();
  A3.m[0][0] = 2, A3.m[1][1] = 1, A3.m[2][2] = 4;
  EXPECT_NEAR(condition_number<3>(A3), 4.0, 1e-15 * 4);
  // a rotation does not change the condition number
  MatD<2> R;
  R.m[0][0] = std::cos(0.7), R.m[0][1] = -std::sin(0.7), R.m[1][0] = std::sin(0.7), R.m[1][1] = std::cos(0.7);
  EXPECT_NEAR(condition_number<2>(R * A2), 4.0, 1e-14 * 4);
  // mapped face geometry: offsets F dX, areas cof(F) A0 of a full cell (rkpm.md 3.2)
  std::mt19937 rng(63);
  const MatD<3> F = random_map<3>(rng, 0.4);
  const CellFaces<3> c = mapped_faces<3>(F, VecD<3>::constant(0.5 * kDp), VecD<3>::constant(0.5 * kDp));
  const MatD<3> cof = inverse(transpose(F)) * det(F);
  for (int k = 0; k < 3; ++k)
    for (int s = 0; s < 2; ++s) {
      VecD<3> e = VecD<3>::zero();
      e.v[k] = s ? 1.0 : -1.0;
      EXPECT_LE(max_abs(VecD<3>(c.offset[2 * k + s] - F * e * (0.5 * kDp))), 1e-15);
      EXPECT_LE(max_abs(VecD<3>(c.area[2 * k + s] - cof * e * (kDp * kDp))), 1e-15);
    }
}

// ============================================================== rkpm.md 3.1
TEST(RkpmSmoothedGradient, LinearExactnessThroughOperatorFunctor2d) {
  std::mt19937 rng(71);
  const int n = 10;
  const auto nodes = perturbed_lattice<2>(n, kDp, 0.2, origin<2>(), rng);
  for (double f : {1.5, 2.0}) {
    for (int variant = 0; variant < 3; ++variant) {  // F = I; mapped random F; box cells of random F
      HostOperators<2> h(nodes, f * kDp);
      if (variant > 0)
        for (auto& F : h.F) F = random_map<2>(rng, 0.15);
      h.build(variant == 2, 0, 1e-3);
      GradientErrors worst;
      for (int j = 3; j < n - 3; ++j)
        for (int i = 3; i < n - 3; ++i) {
          const Index L = Index(i + n * j);
          EXPECT_EQ(h.status[L], 0u);
          const VecD<2> grad_u = random_vector<2>(rng);
          const GradientErrors e = smoothed_gradient_errors<2>(h, L, grad_u, 0.3);
          worst.linear = std::max(worst.linear, e.linear);
          worst.sum = std::max(worst.sum, e.sum);
          worst.moment = std::max(worst.moment, e.moment);
          MatD<2> F = h.F[L];
          if (variant == 2) F = box_map<2>(F);
          EXPECT_NEAR(h.op[L].volume, det(F) * kDp * kDp, 1e-15 * kDp * kDp);
          double rmax = 0;
          for (int fc = 0; fc < 4; ++fc) rmax = std::max(rmax, norm(h.op[L].offset[fc]));
          EXPECT_NEAR(h.reach[L], f * kDp + rmax, 1e-15);
        }
      std::printf(
          "smoothed gradient 2D a~ = %.1f, %s cells: sum V grad~Psi u_I vs V grad u %.3g, |sum grad~Psi| dp %.3g, "
          "sum (x_I - x_L) (x) V grad~Psi vs V I %.3g\n",
          f,
          variant == 0   ? "full"
          : variant == 1 ? "mapped"
                         : "box",
          worst.linear, worst.sum, worst.moment);
      EXPECT_LE(worst.linear, 1e-12);
      EXPECT_LE(worst.sum, 1e-12);
      EXPECT_LE(worst.moment, 1e-12);
    }
  }
}

TEST(RkpmSmoothedGradient, LinearExactnessThroughOperatorFunctor3d) {
  std::mt19937 rng(72);
  const int n = 7;
  const auto nodes = perturbed_lattice<3>(n, kDp, 0.2, origin<3>(), rng);
  for (double f : {1.5, 2.0}) {
    HostOperators<3> h(nodes, f * kDp);
    for (auto& F : h.F) F = random_map<3>(rng, 0.15);
    h.build(false, 0, 1e-3);
    GradientErrors worst;
    for (int k = 3; k < n - 3; ++k)
      for (int j = 2; j < n - 2; ++j)
        for (int i = 2; i < n - 2; ++i) {
          const Index L = Index(i + n * (j + n * k));
          EXPECT_EQ(h.status[L], 0u);
          const GradientErrors e = smoothed_gradient_errors<3>(h, L, random_vector<3>(rng), -0.2);
          worst.linear = std::max(worst.linear, e.linear);
          worst.sum = std::max(worst.sum, e.sum);
          worst.moment = std::max(worst.moment, e.moment);
        }
    std::printf("smoothed gradient 3D a~ = %.1f, mapped cells: linear %.3g, sum %.3g, moment %.3g\n", f, worst.linear,
                worst.sum, worst.moment);
    EXPECT_LE(worst.linear, 1e-12);
    EXPECT_LE(worst.sum, 1e-12);
    EXPECT_LE(worst.moment, 1e-12);
  }
}

// A lattice with its bottom row on the boundary: clipped half cells there,
// the bottom row flagged singular (rkpm.md 1.7, 3.2). The clipped face of a
// bottom node is centred on the node: Kronecker values (the guard branch).
// Also the functor's NSNI data (regular kernel for all nodes, rkpm.md 1.7).
TEST(RkpmSmoothedGradient, ClippedCellsWithSingularBoundaryNodes) {
  std::mt19937 rng(73);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  const int n = 10;
  std::vector<VecD<2>> nodes;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      nodes.push_back(origin<2>() + VecD<2>{{(i + (j > 0 ? u(rng) : 0.0)) * kDp, (j + (j > 0 ? u(rng) : 0.0)) * kDp}});
  for (double f : {1.5, 2.0}) {
    HostOperators<2> h(nodes, f * kDp);
    for (int i = 0; i < n; ++i) h.singular[i] = 1, h.lo[i].v[1] = 0.0;
    h.build(false, 0, 1e-3);
    GradientErrors worst;
    double e_grad = 0, e_lin2 = 0;
    int regularised = 0;
    for (int j = 0; j < 4; ++j)
      for (int i = 3; i < n - 3; ++i) {
        const Index L = Index(i + n * j);
        if (h.status[L] & 1u) ++regularised;
        EXPECT_EQ(h.status[L] & 2u, 0u);
        EXPECT_EQ(h.op[L].kronecker[2], j == 0 ? L : kNoKronecker) << "clipped face -y";
        const GradientErrors e = smoothed_gradient_errors<2>(h, L, random_vector<2>(rng), 1.1);
        worst.linear = std::max(worst.linear, e.linear);
        worst.sum = std::max(worst.sum, e.sum);
        worst.moment = std::max(worst.moment, e.moment);
        // NSNI data of the functor at x_L
        const VecD<2> grad_u = random_vector<2>(rng);
        const double inv_abar = 1.0 / h.a[L];
        for (int k = 0; k < 2; ++k) {
          double gu = 0;
          double lin[2] = {0, 0};
          for (size_t I = 0; I < nodes.size(); ++I) {
            const VecD<2> y = nodes[L] - nodes[I];
            const KernelSample<2> s = kernel<2>(y, h.a[I], false);
            const Vec<3, double> hb = basis<2>(y, inv_abar);
            const double uI = 0.4 + dot(grad_u, nodes[I]);
            gu += -inv_abar * dot(h.nsni[L].inverse_row[k], hb) * s.w * uI;
            const MatD<2> sd = implicit_second_derivatives<2, double>(h.nsni[L], hb, s, inv_abar);
            for (int i2 = 0; i2 < 2; ++i2) lin[i2] += sd.m[k][i2] * uI;
          }
          e_grad = std::max(e_grad, std::fabs(gu - grad_u.v[k]) / norm(grad_u));
          for (double v : lin) e_lin2 = std::max(e_lin2, std::fabs(v) * kDp / norm(grad_u));
        }
      }
    std::printf(
        "clipped cells, singular bottom row a~ = %.1f: linear %.3g, sum %.3g, moment %.3g; %d of %d nodes "
        "regularised; NSNI gradient %.3g, Psi_I,ki on linear u %.3g\n",
        f, worst.linear, worst.sum, worst.moment, regularised, 4 * (n - 6), e_grad, e_lin2);
    EXPECT_LE(worst.linear, 1e-12);
    EXPECT_LE(worst.sum, 1e-12);
    EXPECT_LE(worst.moment, 1e-12);
    EXPECT_LE(e_grad, 1e-12);
    EXPECT_LE(e_lin2, 1e-10);
  }
}

// rkpm.md 7.1: sum grad~Psi = 0 to round-off on a collinear cloud (regularised at every point).
TEST(RkpmSmoothedGradient, CollinearCloudKeepsZeroGradientSum) {
  std::mt19937 rng(74);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  std::vector<VecD<2>> nodes;
  for (int i = 0; i < 16; ++i) nodes.push_back(origin<2>() + VecD<2>{{(i + u(rng)) * kDp, 0.0}});
  HostOperators<2> h(nodes, 2.0 * kDp);
  h.build(false, 0, 1e-3);
  double worst = 0;
  for (Index L = 2; L < 14; ++L) {
    EXPECT_EQ(h.status[L] & 1u, 1u);
    const auto g = h.smoothed(L);
    VecD<2> s = VecD<2>::zero();
    for (const auto& gi : g) {
      ASSERT_TRUE(std::isfinite(gi.v[0]) && std::isfinite(gi.v[1]));
      s += gi;
    }
    worst = std::max(worst, max_abs(s) * kDp / h.op[L].volume);
  }
  std::printf("collinear cloud, regularised operators: max |sum V grad~Psi| dp/V = %.3g\n", worst);
  EXPECT_LE(worst, 1e-14);
}
