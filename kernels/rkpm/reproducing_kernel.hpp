// Reproducing-kernel shape functions with a linear basis (seed 004 eq. 13-19;
// Liu, Jun, Zhang 1995), the pieces every RKPM stage evaluates, in double:
//   kernel        cubic B-spline on a sphere of radius a, or the boundary
//                 singular kernel phi/z^alpha of an essential-boundary node
//                 (Chen & Wang 2000; rkpm.md 1.1, 1.7)
//   MomentSum     M(x) = sum_I H H^T phi_a, H = [1, (x - x_I)/abar] (eq. 19)
//   solve_moments b = M^-1 H0 with the quasi-linear fallback (rkpm.md 1.6)
//   value         Psi_I(x) = b^T H(x - x_I) phi_a(x - x_I) (eq. 18)
//   ImplicitGradient  rows of M^-1 and (M^-1)_,i at a node for NSNI's
//                 second derivatives (rkpm.md 1.5)
// Offsets y = x - x_I are formed before any sum (never absolute coordinates).
#pragma once
#include "kernels/core/eigen_symmetric.hpp"
#include "kernels/core/small_solve.hpp"

namespace mfsd::rkpm {

// Cubic B-spline phi(z), z = r/a (rkpm.md 1.1; normalisation irrelevant).
MFSD_HD inline double bspline(double z) {
  if (z <= 0.5) return 2.0 / 3.0 - 4.0 * z * z + 4.0 * z * z * z;
  if (z < 1.0) return 4.0 / 3.0 - 4.0 * z + 4.0 * z * z - 4.0 * z * z * z / 3.0;
  return 0.0;
}
MFSD_HD inline double bspline_derivative(double z) {
  if (z <= 0.5) return -8.0 * z + 12.0 * z * z;
  if (z < 1.0) return -4.0 + 8.0 * z - 4.0 * z * z;
  return 0.0;
}

// The singular kernel's exponent alpha (rkpm.md 1.7: phi/z^2).
constexpr double kSingularExponent = 2.0;
// Below this z an evaluation point sits on a singular node: Kronecker values.
constexpr double kSingularGuard = 1e-10;

template <int D>
struct KernelSample {
  double w;                 // phi_a(y)
  Vec<D, double> gradient;  // d phi_a / dx (y = x - x_I)
};

// phi_a(y) and its gradient; a strict support (rkpm.md 1.1-1.2): a sphere,
// z = r/a < 1, or a box (`box`), the tensor product prod_k phi(|y_k|/a) with
// every |y_k| < a (reach a sqrt(d)). A singular node's kernel is
// phi/z^alpha with z = r/a in both (rkpm.md 1.7); the caller handles z below
// kSingularGuard (Kronecker values).
template <int D>
MFSD_HD inline KernelSample<D> kernel(const Vec<D, double>& y, double a, bool singular, bool box = false) {
  KernelSample<D> s{0.0, Vec<D, double>::zero()};
  const double r = norm(y);
  const double z = r / a;
  double phi;
  Vec<D, double> grad;  // d phi / dx
  if (box) {
    double f[D], df[D];
    for (int k = 0; k < D; ++k) {
      const double zk = math::fabs(y.v[k]) / a;
      if (!(zk < 1.0)) return s;
      f[k] = bspline(zk);
      df[k] = bspline_derivative(zk) * (y.v[k] < 0.0 ? -1.0 : 1.0) / a;
    }
    phi = 1.0;
    for (int k = 0; k < D; ++k) phi *= f[k];
    for (int k = 0; k < D; ++k) {
      grad.v[k] = df[k];
      for (int j = 0; j < D; ++j)
        if (j != k) grad.v[k] *= f[j];
    }
  } else {
    if (!(z < 1.0)) return s;
    phi = bspline(z);
    grad = r > 0.0 ? y * (bspline_derivative(z) / (a * r)) : Vec<D, double>::zero();  // phi'(z) y / (a r)
  }
  if (singular && r > 0.0) {
    // phi^ = z^-alpha phi, grad phi^ = z^-alpha (grad phi - alpha phi y / (a^2 z^2))  (rkpm.md 1.7)
    const double za = math::pow(z, kSingularExponent);
    s.w = phi / za;
    s.gradient = (grad - y * (kSingularExponent * phi / (a * a * z * z))) * (1.0 / za);
  } else {
    s.w = phi;
    s.gradient = grad;
  }
  return s;
}

// The kernel's reach as a multiple of a: 1 for spheres, sqrt(d) for boxes.
template <int D>
MFSD_HD inline double kernel_reach_factor(bool box) {
  return box ? math::sqrt(double(D)) : 1.0;
}

// The scaled linear basis H(y) = [1, y/abar] (rkpm.md 1.3).
template <int D>
MFSD_HD inline Vec<D + 1, double> basis(const Vec<D, double>& y, double inv_abar) {
  Vec<D + 1, double> h;
  h.v[0] = 1.0;
  for (int k = 0; k < D; ++k) h.v[k + 1] = y.v[k] * inv_abar;
  return h;
}

// Psi_I(x) = b^T H(y) phi (seed 004 eq. 18).
template <int D, class Real>
MFSD_HD inline double shape_value(const Vec<D + 1, Real>& b, const Vec<D, double>& y, double inv_abar, double w) {
  double s = double(b.v[0]);
  for (int k = 0; k < D; ++k) s += double(b.v[k + 1]) * y.v[k] * inv_abar;
  return s * w;
}

// M = sum_I H H^T phi (seed 004 eq. 19), with the count of covering kernels.
template <int D>
struct MomentSum {
  Mat<D + 1, double> M = Mat<D + 1, double>::zero();
  int covering = 0;
  MFSD_HD void add(const Vec<D + 1, double>& h, double w) {
    if (!(w > 0.0)) return;
    ++covering;
    for (int p = 0; p < D + 1; ++p)
      for (int q = 0; q < D + 1; ++q) M.m[p][q] += h.v[p] * h.v[q] * w;
  }
};

// How the coefficients of one evaluation point were obtained.
enum class Solve : unsigned char { linear, regularized, shepard, failed };

// The smallest eigenvalue of the Schur complement A = M^_ll - m^_l m^_l^T of
// M^ = M/M_00 (the kernel-weighted covariance of the neighbour offsets /
// abar^2; rkpm.md 1.6 step 2).
template <int D>
MFSD_HD inline double covariance_floor(const Mat<D + 1, double>& M) {
  Mat<D, double> A;
  const double inv = 1.0 / M.m[0][0];
  for (int p = 0; p < D; ++p)
    for (int q = 0; q < D; ++q) A.m[p][q] = M.m[p + 1][q + 1] * inv - (M.m[0][p + 1] * inv) * (M.m[0][q + 1] * inv);
  const SymmetricEigen<D, double> e = eigen_symmetric(A);
  double s = e.values.v[0];
  for (int k = 1; k < D; ++k) s = math::min(s, e.values.v[k]);
  return s;
}

// Adds the regularizer eta M_00 diag(0, 1, .., 1) (rkpm.md 1.6 step 3): its
// first row is zero, so sum Psi = 1 and sum grad Psi = 0 stay exact.
// The floor is judged on `regular` where given: the moments of the regular
// kernels at a point near a singular node, whose weight phi/z^2 would
// otherwise dominate M_00 and regularize shape functions that need none
// (losing linear reproduction there; tests/unit/test_rkpm_shape_functions.cpp).
template <int D>
MFSD_HD inline double regularize(Mat<D + 1, double>& M, double tau, const Mat<D + 1, double>* regular = nullptr) {
  const double eta = math::max(0.0, tau - covariance_floor<D>(regular ? *regular : M));
  for (int k = 1; k < D + 1; ++k) M.m[k][k] += eta * M.m[0][0];
  return eta;
}

// b = M^-1 H0 with the quasi-linear fallback (rkpm.md 1.6); `mode` 0
// regularize, 1 shepard, 2 off (failed when the basis is not supported). M is
// left as solved (regularized) for the derivatives.
template <int D>
MFSD_HD inline Solve solve_moments(Mat<D + 1, double>& M, int covering, int mode, double tau, Vec<D + 1, double>& b,
                                   const Mat<D + 1, double>* regular = nullptr) {
  b = Vec<D + 1, double>::zero();
  if (!(M.m[0][0] > 0.0)) return Solve::failed;  // no covering kernel at all
  Solve how = Solve::linear;
  if (mode == 0) {
    if (regularize<D>(M, tau, regular) > 0.0) how = Solve::regularized;
  } else if (covering < D + 1 || covariance_floor<D>(regular ? *regular : M) < tau) {
    if (mode == 2) return Solve::failed;
    b.v[0] = 1.0 / M.m[0][0];  // Shepard: Psi_I = phi_I / sum phi
    return Solve::shepard;
  }
  Vec<D + 1, double> h0 = Vec<D + 1, double>::zero();
  h0.v[0] = 1.0;
  if (!solve(M, h0, b, 1e-14)) {
    if (mode == 2) return Solve::failed;
    b = Vec<D + 1, double>::zero();
    b.v[0] = 1.0 / M.m[0][0];
    return Solve::shepard;
  }
  return how;
}

// NSNI data of a node (rkpm.md 1.5): rows k + 1 (k < D) of M^-1 and of
// (M^-1)_,i = -M^-1 M_,i M^-1, with which
//   Psi_I,ki = -(1/abar) e_{k+1}^T [(M^-1)_,i H phi + M^-1 H_,i phi + M^-1 H phi_,i]
// is the derivative of the implicit gradient Psi^(k)_I.
template <int D, class Real>
struct ImplicitGradient {
  Vec<D + 1, Real> inverse_row[D];            // [k]: row k + 1 of M^-1
  Vec<D + 1, Real> inverse_derivative[D][D];  // [i][k]: row k + 1 of (M^-1)_,i
};

// The derivative sums of M at a point: M_,i = sum [(H_,i H^T + H H_,i^T) phi + H H^T phi_,i].
template <int D>
struct MomentDerivativeSum {
  Mat<D + 1, double> dM[D];
  MFSD_HD MomentDerivativeSum() {
    for (int i = 0; i < D; ++i) dM[i] = Mat<D + 1, double>::zero();
  }
  MFSD_HD void add(const Vec<D + 1, double>& h, const KernelSample<D>& s, double inv_abar) {
    for (int i = 0; i < D; ++i) {
      for (int p = 0; p < D + 1; ++p)
        for (int q = 0; q < D + 1; ++q) dM[i].m[p][q] += h.v[p] * h.v[q] * s.gradient.v[i];
      // H_,i = e_{i+1}/abar: (H_,i H^T + H H_,i^T) phi
      for (int q = 0; q < D + 1; ++q) {
        dM[i].m[i + 1][q] += inv_abar * h.v[q] * s.w;
        dM[i].m[q][i + 1] += inv_abar * h.v[q] * s.w;
      }
    }
  }
};

// From the (regularized) moment matrix and its derivatives; false when M
// cannot be inverted (then the data are zero: no NSNI term at this node).
template <int D, class Real>
MFSD_HD inline bool implicit_gradient(const Mat<D + 1, double>& M, const MomentDerivativeSum<D>& d,
                                      ImplicitGradient<D, Real>& out) {
  Mat<D + 1, double> Mi = Mat<D + 1, double>::zero();
  const bool ok = try_inverse(M, Mi, 1e-14);
  for (int k = 0; k < D; ++k) {
    for (int q = 0; q < D + 1; ++q) out.inverse_row[k].v[q] = ok ? Real(Mi.m[k + 1][q]) : Real(0);
    for (int i = 0; i < D; ++i) {
      // row k+1 of -M^-1 M_,i M^-1
      for (int q = 0; q < D + 1; ++q) {
        double s = 0.0;
        if (ok)
          for (int p = 0; p < D + 1; ++p) {
            double t = 0.0;
            for (int r = 0; r < D + 1; ++r) t += d.dM[i].m[p][r] * Mi.m[r][q];
            s -= Mi.m[k + 1][p] * t;
          }
        out.inverse_derivative[i][k].v[q] = Real(s);
      }
    }
  }
  return ok;
}

// Psi_I,ki(x) for all k, i (rkpm.md 1.5), at offset y = x - x_I with the
// kernel sample s of node I (regular kernel) and the node's data g.
template <int D, class Real>
MFSD_HD inline Mat<D, double> implicit_second_derivatives(const ImplicitGradient<D, Real>& g,
                                                          const Vec<D + 1, double>& h, const KernelSample<D>& s,
                                                          double inv_abar) {
  Mat<D, double> out;
  for (int k = 0; k < D; ++k) {
    double rh = 0.0;
    for (int q = 0; q < D + 1; ++q) rh += double(g.inverse_row[k].v[q]) * h.v[q];
    for (int i = 0; i < D; ++i) {
      double dh = 0.0;
      for (int q = 0; q < D + 1; ++q) dh += double(g.inverse_derivative[i][k].v[q]) * h.v[q];
      out.m[k][i] = -inv_abar * (dh * s.w + double(g.inverse_row[k].v[i + 1]) * inv_abar * s.w + rh * s.gradient.v[i]);
    }
  }
  return out;
}

}  // namespace mfsd::rkpm
