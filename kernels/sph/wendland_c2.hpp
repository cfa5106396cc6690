// Wendland C2 smoothing kernel ("5th-order Wendland"), support radius 2h
// (formulations.md section 0; seed 000 section 5, seed 003 section 4):
//   W(q) = a_d (1 - q/2)^4 (1 + 2q),  q = r/h in [0, 2],
//   a_1 = 3/(4h), a_2 = 7/(4 pi h^2), a_3 = 21/(16 pi h^3).
//   dW/dr = -(5 a_d / h) q (1 - q/2)^3.
#pragma once
#include "kernels/core/math.hpp"

namespace mfsd {

template <int D, class Real>
struct WendlandC2 {
  Real h;  // smoothing length
  Real inv_h;
  Real factor;  // a_d

  MFSD_HD static WendlandC2 make(Real smoothing_length) {
    WendlandC2 k;
    k.h = smoothing_length;
    k.inv_h = Real(1) / smoothing_length;
    const Real pi = math::pi<Real>;
    if (D == 1) k.factor = Real(3) / (Real(4) * smoothing_length);
    if (D == 2) k.factor = Real(7) / (Real(4) * pi * smoothing_length * smoothing_length);
    if (D == 3) k.factor = Real(21) / (Real(16) * pi * smoothing_length * smoothing_length * smoothing_length);
    return k;
  }

  MFSD_HD Real cutoff() const { return Real(2) * h; }

  MFSD_HD Real W(Real r) const {
    const Real q = r * inv_h;
    if (q >= Real(2)) return Real(0);
    const Real s = Real(1) - Real(0.5) * q;
    const Real s2 = s * s;
    return factor * s2 * s2 * (Real(1) + Real(2) * q);
  }

  // dW/dr (<= 0).
  MFSD_HD Real dW(Real r) const {
    const Real q = r * inv_h;
    if (q >= Real(2)) return Real(0);
    const Real s = Real(1) - Real(0.5) * q;
    return -Real(5) * factor * inv_h * q * s * s * s;
  }

  // dW/dr / r = -(5 a_d / h^2) (1 - q/2)^3 (<= 0): the pair data's factor
  // without a division by r (finite at r = 0).
  MFSD_HD Real dW_over_r(Real r) const {
    const Real q = r * inv_h;
    if (q >= Real(2)) return Real(0);
    const Real s = Real(1) - Real(0.5) * q;
    return -Real(5) * factor * inv_h * inv_h * s * s * s;
  }
};

}  // namespace mfsd
