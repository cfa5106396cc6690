// Hughes-Winget incremental kinematics of the semi-Lagrangian RKPM stress
// update (rkpm.md 4.1; seed 004 section 7.1, eq. 25-26; Hughes & Winget,
// IJNME 15 (1980) 1862-1867). From the gradient of the displacement increment
// in configuration n, L_n = d(Delta u)/dx^n (D x D, D = 2 or 3), one step gives
//   G   = L_n (I + L_n/2)^-1          (= d(Delta u)/dx^{n+1/2}, eq. 26)
//   Deps = sym G,  dW = skew G,  Q = (I - dW/2)^-1 (I + dW/2)
// and the caller rotates and increments the stress with them
// (stress_update.hpp). Both are returned as 3 x 3 tensors: for D = 2 (plane
// strain) Deps_33 = 0, Q_33 = 1 and the off-plane terms are zero. For a rigid
// rotation increment R (L_n = R - I, any angle < 180 deg) G = 2 (R - I)(R + I)^-1
// is skew and Q = R exactly (tests/unit/test_rkpm_stress_update.cpp: 1e-13).
// The mapped-cell update F_cell <- (I + L_n) F_cell is the caller's.
//
// Option (rkpm.md 4.1, `cells: box` only): with the gradient in configuration
// n+1, Lbar = d(Delta u)/dx^{n+1}, G = Lbar (I - Lbar/2)^-1
// (midpoint_gradient_from_end); the rest is the same.
#pragma once
#include "kernels/core/mat.hpp"

namespace mfsd::rkpm {

// The strain increment and the incremental rotation of one step, 3 x 3.
struct HughesWingetIncrement {
  Mat<3, double> strain;    // Deps = sym G (plane strain: third row and column zero)
  Mat<3, double> rotation;  // Q (plane strain: Q_33 = 1, off-plane terms zero)
};

// A D x D tensor embedded into 3 x 3, the (3,3) entry set to a33 (plane strain: 0 for strains, 1 for rotations).
MFSD_HD inline Mat<3, double> embed_3d(const Mat<3, double>& A, double) { return A; }
MFSD_HD inline Mat<3, double> embed_3d(const Mat<2, double>& A, double a33) {
  Mat<3, double> R = Mat<3, double>::zero();
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) R.m[a][b] = A.m[a][b];
  R.m[2][2] = a33;
  return R;
}

// G = L_n (I + L_n/2)^-1, the gradient on the midpoint configuration x^{n+1/2} = x^n + Delta u/2.
template <int D>
MFSD_HD inline Mat<D, double> midpoint_gradient(const Mat<D, double>& L) {
  Mat<D, double> A = L * 0.5;
  A.add_diagonal(1.0);
  return L * inverse(A);  // rkpm.md 4.1; seed 004 eq. 26 (d x^{n+1/2} = (I + L_n/2) d x^n)
}

// Option `cells: box`: G = Lbar (I - Lbar/2)^-1 from Lbar = d(Delta u)/dx^{n+1}.
template <int D>
MFSD_HD inline Mat<D, double> midpoint_gradient_from_end(const Mat<D, double>& Lbar) {
  Mat<D, double> A = Lbar * -0.5;
  A.add_diagonal(1.0);
  return Lbar * inverse(A);  // rkpm.md 4.1 option; seed 004 eq. 26 (d x^{n+1/2} = (I - Lbar/2) d x^{n+1})
}

// Deps = sym G and Q = (I - dW/2)^-1 (I + dW/2), dW = skew G, from the midpoint gradient G.
template <int D>
MFSD_HD inline HughesWingetIncrement hughes_winget_from_midpoint(const Mat<D, double>& G) {
  const Mat<D, double> Gt = transpose(G);
  const Mat<D, double> half_spin = (G - Gt) * 0.25;  // dW/2, dW = skew G (rkpm.md 4.1)
  const Mat<D, double> I = Mat<D, double>::identity();
  HughesWingetIncrement r;
  r.strain = embed_3d((G + Gt) * 0.5, 0.0);                              // Deps = sym G (rkpm.md 4.1)
  r.rotation = embed_3d(inverse(I - half_spin) * (I + half_spin), 1.0);  // Hughes & Winget 1980
  return r;
}

// One step's Deps and Q from L_n = d(Delta u)/dx^n (the default of rkpm.md 4.1).
template <int D>
MFSD_HD inline HughesWingetIncrement hughes_winget(const Mat<D, double>& L) {
  return hughes_winget_from_midpoint(midpoint_gradient(L));
}

}  // namespace mfsd::rkpm
