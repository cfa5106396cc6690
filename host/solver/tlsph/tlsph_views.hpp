// Raw views of the TLSPH particle fields and reference pairs, gathered once
// after set-up (buffers never move afterwards) and handed to the functors.
#pragma once
#include <type_traits>
#include <utility>

#include "host/solver/common/kinematics.hpp"
#include "kernels/core/mat.hpp"
#include "kernels/fracture/phase_field.hpp"
#include "kernels/materials/j2_plastic.hpp"
#include "kernels/tlsph/genog_neighbor_record.hpp"
#include "kernels/tlsph/reference_pairs.hpp"

namespace mfsd {

// The precision of a pair list's data (with_half_pairs' argument).
template <class Pairs>
using HalfPairReal = std::remove_cv_t<std::remove_pointer_t<decltype(std::declval<Pairs>().stretch)>>;

template <int D, class Real>
struct TlsphViews : Kinematics<D, Real> {
  ReferencePairs<D, Real> pairs;
  // The half-pair loop (CPU; --pair-loop): each row's pairs with j > i and
  // the largest j - i; half_bandwidth -1 where the full gather runs.
  ReferencePairs<D, Real> half_pairs{};
  Index half_bandwidth = -1;
  // The same with float pair data (--pair-precision float in a double run,
  // issue 24 item 4): then half_float, and half_pairs_f in place of half_pairs.
  ReferencePairs<D, float> half_pairs_f{};
  bool half_float = false;
  // The one place the half loops choose between the two: visit(pairs) with
  // the list in the precision its data are stored in (ReferencePairs<D,
  // float> or <D, Real>); HalfPairReal<decltype(pairs)> names that precision.
  template <class Visit>
  void with_half_pairs(Visit&& visit) const {
    if (half_float)
      visit(half_pairs_f);
    else
      visit(half_pairs);
  }
  Mat<D, Real>* deformation_gradient;
  Mat<D, Real>* deformation_rate;
  const Mat<D, Real>* correction;
  Mat<D, Real>* force_stress;
  Real* shear_coefficient;                     // laplacian bodies only (else null)
  Mat<D, Real>* shear_stress;                  // genog bodies only
  Mat<D, Real>* inverse_F;                     // genog bodies, and scratch for the indicator
  GenogNeighborRecord<Real>* neighbor_record;  // 3-D genog on the CPU backend, else null
  Real* hourglass_indicator;
  J2State<Real>* plastic_state;  // when some body is plastic, else null
  Real* von_mises;
  Real* jacobian;
  Real* von_mises_strain;
  Real* plastic_strain;  // when some body is plastic, else null
  Real* damping_work;    // with Kelvin-Voigt damping (factor > 0), else null
  // When some body is Holzapfel-Ogden, else null:
  const Vec<D, Real>* fibre;    // f0
  const Vec<D, Real>* sheet;    // s0
  Real* active_tension;         // k V_m (written each step for a time-dependent V_m)
  Real* stiffening;             // current / reference longitudinal modulus, for the time step
  Real* active_work;            // work of the active stress on the body per V0 (when some body has one)
  PhaseFieldViews<Real> phase;  // when some body has fracture, else all null
};

}  // namespace mfsd
