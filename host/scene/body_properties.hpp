// Quantities derived from a body's material and spacing, shared by the
// particle generator (expression constants), the solver and the reports.
#pragma once
#include <algorithm>
#include <cmath>

#include "host/scene/scene.hpp"
#include "kernels/materials/elastic_moduli.hpp"

namespace mfsd {

struct BodyProperties {
  double K, G, lambda;
  double c0;       // sound speed used by time step, damping and expressions
  double c_shear;  // sqrt(G / rho0)
  double h;        // smoothing length = h_over_dp * spacing
  double volume;   // dp^d
  double mass;     // rho0 dp^d
};

inline BodyProperties body_properties(const BodySpec& b, const SolverSpec& s, int dim) {
  const ElasticModuli m{b.material.youngs_modulus, b.material.poisson_ratio};
  BodyProperties p;
  p.K = m.bulk();
  p.G = m.shear();
  p.lambda = m.lame_lambda();
  double modulus = s.sound_speed == SoundSpeed::bulk ? p.K : p.K + 4.0 * p.G / 3.0;
  if (b.material.model == MaterialModel::holzapfel_ogden) {
    // Small-strain tangent of seed 000 eq. 17 at F = I: shear modulus a, bulk
    // lambda + 2ab + 2a/3 (the exponential's b adds to the bulk), and 4 a_f
    // (4 a_s) more along the fibre (sheet). The time step scales c0 with the
    // current stiffness (HolzapfelOgdenPoint::longitudinal_modulus).
    const HolzapfelOgdenSpec& h = b.material.holzapfel_ogden;
    p.G = h.a;
    p.lambda = h.lambda;
    p.K = h.lambda + 2.0 * h.a * h.b + 2.0 * h.a / 3.0;
    modulus = (s.sound_speed == SoundSpeed::bulk ? p.K : p.K + 4.0 * p.G / 3.0) + 4.0 * std::max(h.af, h.as);
  }
  p.c0 = std::sqrt(modulus / b.material.density);
  p.c_shear = std::sqrt(p.G / b.material.density);
  p.h = s.h_over_dp * b.spacing;
  p.volume = std::pow(b.spacing, dim);
  p.mass = b.material.density * p.volume;
  return p;
}

}  // namespace mfsd
