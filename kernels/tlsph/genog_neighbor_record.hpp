// What the 3-D genog force stage reads of a neighbour j, packed into one
// record per particle by the stress stage (CPU backend): the columns of
// Q_j = M_j + S_j and of F_j^{-1}, and u_j, each padded to four lanes with a
// zero, so that a pair costs a few 4-wide vector operations instead of some
// 80 scalar ones (acceleration.hpp; docs/performance.md). 28 reals: 224 bytes
// in double, 112 in float, 3.5 cache lines in double. Where the record is
// used, the stress stage writes it instead of the separate Q and F^{-1}.
#pragma once
#include "kernels/core/mat.hpp"

namespace mfsd {

template <class Real>
struct GenogNeighborRecord {
  Real q[3][4];  // q[b][a] = Q_ab, lane 3 zero
  Real f[3][4];  // f[b][a] = (F^{-1})_ab, lane 3 zero
  Real u[4];     // u_a, lane 3 zero

  MFSD_HD void set(const Mat<3, Real>& Q, const Mat<3, Real>& F_inv, const Vec<3, Real>& disp) {
    for (int b = 0; b < 3; ++b) {
      for (int a = 0; a < 3; ++a) {
        q[b][a] = Q.m[a][b];
        f[b][a] = F_inv.m[a][b];
      }
      q[b][3] = Real(0);
      f[b][3] = Real(0);
    }
    for (int a = 0; a < 3; ++a) u[a] = disp.v[a];
    u[3] = Real(0);
  }

  MFSD_HD Mat<3, Real> Q() const { return unpack(q); }
  MFSD_HD Mat<3, Real> F_inv() const { return unpack(f); }

 private:
  MFSD_HD static Mat<3, Real> unpack(const Real (&c)[3][4]) {
    Mat<3, Real> m;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) m.m[a][b] = c[b][a];
    return m;
  }
};

}  // namespace mfsd
