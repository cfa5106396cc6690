// Smoothing cells of stabilized nodal integration (seed 004 eq. 23-24;
// rkpm.md 3.1-3.2): the initial cell of node L is the box [X_L - lo, X_L + hi]
// (lo_k = hi_k = dp/2 inside, 0 on a clipped side), with 2d faces, face
// f = 2k for -e_k and 2k + 1 for +e_k (the surface bits of host/scene/surface.hpp).
// `mapped` cells map the initial faces with the node's cell map F (Nanson):
//   xbar_f - x_L = F dX_f,  a_f = J F^-T A0_f = cof(F) A0_f,  V = J V0,
// which keeps the cell identities sum_f a_f = 0 and sum_f (xbar_f - x_L) (x) a_f = V I;
// `box` cells are axis-aligned at the node with extents (lo, hi) J^(1/d).
#pragma once
#include "kernels/core/eigen_symmetric.hpp"
#include "kernels/core/mat.hpp"

namespace mfsd::rkpm {

template <int D>
struct CellFaces {
  Vec<D, double> offset[2 * D];  // xbar_f - x_L
  Vec<D, double> area[2 * D];    // a_f, outward area vector
  double volume;                 // V_L
};

// cof(F) = J F^-T.
template <class Real>
MFSD_HD inline Mat<2, Real> cofactor(const Mat<2, Real>& F) {
  Mat<2, Real> C;
  C.m[0][0] = F.m[1][1], C.m[0][1] = -F.m[1][0];
  C.m[1][0] = -F.m[0][1], C.m[1][1] = F.m[0][0];
  return C;
}
template <class Real>
MFSD_HD inline Mat<3, Real> cofactor(const Mat<3, Real>& F) {
  Mat<3, Real> C;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const int a1 = (a + 1) % 3, a2 = (a + 2) % 3, b1 = (b + 1) % 3, b2 = (b + 2) % 3;
      C.m[a][b] = F.m[a1][b1] * F.m[a2][b2] - F.m[a1][b2] * F.m[a2][b1];
    }
  return C;
}

// The current faces of a cell with map F and initial extents lo, hi
// (rkpm.md 3.2: dX_f = c - X_L +- l_k/2 e_k, A0_f = +-(V0/l_k) e_k).
template <int D>
MFSD_HD inline CellFaces<D> mapped_faces(const Mat<D, double>& F, const Vec<D, double>& lo, const Vec<D, double>& hi) {
  CellFaces<D> c;
  double V0 = 1.0;
  for (int k = 0; k < D; ++k) V0 *= lo.v[k] + hi.v[k];
  const Mat<D, double> cof = cofactor(F);
  const double J = det(F);
  const Vec<D, double> center = (hi - lo) * 0.5;  // c - X_L
  for (int k = 0; k < D; ++k) {
    const double l = lo.v[k] + hi.v[k];
    for (int s = 0; s < 2; ++s) {
      const double sign = s ? 1.0 : -1.0;
      Vec<D, double> dX = center, A0 = Vec<D, double>::zero();
      dX.v[k] += sign * 0.5 * l;
      A0.v[k] = sign * V0 / l;
      c.offset[2 * k + s] = F * dX;
      c.area[2 * k + s] = cof * A0;
    }
  }
  c.volume = J * V0;
  return c;
}

// The box cell's map: J^(1/d) I with J = det F (rkpm.md 3.2, `box`).
template <int D>
MFSD_HD inline Mat<D, double> box_map(const Mat<D, double>& F) {
  return Mat<D, double>::diagonal(math::pow(det(F), 1.0 / D));
}

// cond(F) = sigma_max / sigma_min from the eigenvalues of F^T F.
template <int D>
MFSD_HD inline double condition_number(const Mat<D, double>& F) {
  const SymmetricEigen<D, double> e = eigen_symmetric(transpose(F) * F);
  double lo = e.values.v[0], hi = e.values.v[0];
  for (int k = 1; k < D; ++k) lo = math::min(lo, e.values.v[k]), hi = math::max(hi, e.values.v[k]);
  return lo > 0.0 ? math::sqrt(hi / lo) : double(INFINITY);
}

// Re-celling (rkpm.md 3.2): F <- J^(1/d) R, R the rotation of the polar
// decomposition (Newton: R <- (R + R^-T)/2); volume and rotation kept.
template <int D>
MFSD_HD inline Mat<D, double> recell(const Mat<D, double>& F) {
  Mat<D, double> R = F;
  for (int it = 0; it < 30; ++it) {
    const Mat<D, double> next = (R + transpose(inverse(R))) * 0.5;
    const double change = frobenius_norm(next - R);
    R = next;
    if (change < 1e-15) break;
  }
  return R * math::pow(det(F), 1.0 / D);
}

}  // namespace mfsd::rkpm
