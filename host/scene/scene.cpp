#include "host/scene/scene.hpp"

#include <algorithm>
#include <cmath>

namespace mfsd {

bool has_plastic_body(const Scene& scene) {
  for (const auto& b : scene.bodies)
    if (b.material.plastic()) return true;
  return false;
}

SolverSpec solver_for(const SolverSpec& s, Method m) {
  if (m == s.method) return s;
  SolverSpec r;  // the other method's defaults
  r.method = m;
  r.ulsph = s.ulsph;
  r.end_time = s.end_time;
  r.h_over_dp = s.h_over_dp;
  r.precision = s.precision;
  r.sound_speed = s.sound_speed;
  r.gravity = s.gravity;
  r.reorder = s.reorder;
  r.cfl_given = s.cfl_given;
  r.deformed_time_step = s.deformed_time_step;
  r.deformed_time_step_given = s.deformed_time_step_given;
  if (m == Method::ulsph) {
    r.hourglass = s.ulsph.hourglass;
    r.damping_factor = 0;  // ULSPH dissipates through its Riemann solver (seed 002 eq. 15-17)
    r.cfl = s.cfl_given ? s.cfl : 0.4;
  } else {
    r.cfl = s.cfl_given ? s.cfl : 0.6;
  }
  return r;
}

bool mixed_methods(const Scene& scene) {
  for (const auto& b : scene.bodies)
    if (b.method != scene.bodies.front().method) return true;
  return false;
}

Method scene_method(const Scene& scene) {
  return scene.bodies.empty() ? scene.solver.method : scene.bodies.front().method;
}

bool has_fracture_body(const Scene& scene) {
  for (const auto& b : scene.bodies)
    if (b.material.fracture.enabled) return true;
  return false;
}

bool has_load_condition(const Scene& scene) {
  for (const auto& c : scene.conditions)
    if (c.type != ConditionSpec::Type::velocity) return true;
  return false;
}

bool has_ulsph_energy_audit(const Scene& scene) {
  if (!scene.solver.ulsph.energy_audit) return false;
  for (const auto& b : scene.bodies)
    if (b.method == Method::ulsph) return true;
  return false;
}

bool has_holzapfel_ogden_body(const Scene& scene) {
  for (const auto& b : scene.bodies)
    if (b.material.model == MaterialModel::holzapfel_ogden) return true;
  return false;
}

bool has_active_stress(const Scene& scene) {
  for (const auto& b : scene.bodies)
    if (b.material.model == MaterialModel::holzapfel_ogden && b.material.holzapfel_ogden.active.enabled) return true;
  return false;
}

std::vector<CrackSpec> crack_specs(const Scene& scene) {
  std::vector<CrackSpec> out;
  const int dim = scene.dimension;
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    const FractureSpec& f = scene.bodies[b].material.fracture;
    if (!f.enabled) continue;
    CrackSpec c{b, {0, 0, 0}, f.crack_direction, 0.0};
    if (c.direction == Point3{0, 0, 0} && dim == 2 && !f.notches.empty())
      for (int a = 0; a < 2; ++a) c.direction[size_t(a)] = f.notches[0][1][size_t(a)] - f.notches[0][0][size_t(a)];
    const double norm =
        std::sqrt(c.direction[0] * c.direction[0] + c.direction[1] * c.direction[1] + c.direction[2] * c.direction[2]);
    if (norm == 0) continue;
    for (auto& x : c.direction) x /= norm;
    if (!f.notches.empty()) {
      const auto& p = f.notches[0];
      if (dim == 2) {
        c.origin = p[1];
        // The notch clipped to the body's bounding box (Liang-Barsky).
        const Bounds box = scene.bodies[b].geometry.bounds(dim);
        double t0 = 0, t1 = 1;
        for (int a = 0; a < 2; ++a) {
          const double d = p[1][size_t(a)] - p[0][size_t(a)], lo = box.min[size_t(a)] - p[0][size_t(a)],
                       hi = box.max[size_t(a)] - p[0][size_t(a)];
          if (d == 0) {
            if (lo > 0 || hi < 0) t1 = -1;
            continue;
          }
          double ta = lo / d, tb = hi / d;
          if (ta > tb) std::swap(ta, tb);
          t0 = std::max(t0, ta);
          t1 = std::min(t1, tb);
        }
        const double len = std::hypot(p[1][0] - p[0][0], p[1][1] - p[0][1]);
        c.notch_length = t1 > t0 ? (t1 - t0) * len : 0.0;
      } else {
        for (int a = 0; a < 3; ++a)
          c.origin[size_t(a)] = 0.25 * (p[0][size_t(a)] + p[1][size_t(a)] + p[2][size_t(a)] + p[3][size_t(a)]);
      }
    }
    out.push_back(c);
  }
  return out;
}

const char* to_string(MaterialModel m) {
  switch (m) {
    case MaterialModel::neo_hookean:
      return "neo_hookean";
    case MaterialModel::saint_venant_kirchhoff:
      return "saint_venant_kirchhoff";
    case MaterialModel::j2:
      return "j2";
    case MaterialModel::j2_mandel:
      return "j2_mandel";
    case MaterialModel::holzapfel_ogden:
      return "holzapfel_ogden";
    case MaterialModel::drucker_prager:
      return "drucker_prager";
    case MaterialModel::linear_elastic:
      return "linear_elastic";
  }
  return "?";
}
const char* to_string(Method m) { return m == Method::ulsph ? "ulsph" : m == Method::rkpm ? "rkpm" : "tlsph"; }

const char* to_string(HourglassControl h) {
  switch (h) {
    case HourglassControl::none:
      return "none";
    case HourglassControl::laplacian:
      return "laplacian";
    case HourglassControl::genog:
      return "genog";
    case HourglassControl::gnog:
      return "gnog";
    case HourglassControl::gnog_amc:
      return "gnog_amc";
  }
  return "?";
}
const char* to_string(Precision p) { return p == Precision::single_precision ? "float" : "double"; }

}  // namespace mfsd
