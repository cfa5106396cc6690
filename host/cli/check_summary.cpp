#include "host/cli/check_summary.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "host/scene/body_properties.hpp"
#include "host/scene/particle_expressions.hpp"
#include "kernels/expr/interpreter.hpp"
#include "kernels/bc/conditions.hpp"

namespace mfsd {

namespace {

// Initial velocities as the run starts them: initial_velocity, then the
// velocity conditions active at t = 0 (seed 001 sets initial fields that way).
std::vector<Point3> initial_velocities(const Scene& s, const InitialParticles& P) {
  std::vector<Point3> v = P.velocity;
  for (size_t c = 0; c < s.conditions.size(); ++c) {
    const ConditionSpec& cond = s.conditions[c];
    if (cond.type != ConditionSpec::Type::velocity || cond.t_start > 0) continue;
    size_t b = 0;
    while (s.bodies[b].name != cond.body) ++b;
    for (int a = 0; a < s.dimension; ++a) {
      if (cond.value[size_t(a)].empty()) continue;
      const expr::Program prog = compile_particle_expression(cond.value[size_t(a)], s, b, "velocity condition");
      const auto view = prog.host_view<double>();
      for (long i : P.condition_particles[c].ids) {
        double vars[kParticleVariables] = {};
        for (int k = 0; k < 3; ++k) {
          vars[var_x0 + k] = vars[var_x + k] = P.position[size_t(i)][k];
          vars[var_vx + k] = v[size_t(i)][k];
        }
        vars[var_dx] = s.bodies[b].spacing;
        double value = 0;
        if (expr::evaluate(view, vars, &value, nullptr) == expr::Status::ok) v[size_t(i)][a] = value;
      }
    }
  }
  return v;
}

// A count estimated in double: whole below 1e15, else 3 significant digits
// (never through an integer conversion, which overflows).
std::string count_text(double n) {
  std::ostringstream o;
  if (std::isfinite(n) && std::abs(n) < 1e15)
    o << std::fixed << std::setprecision(0) << std::round(n);
  else if (std::isfinite(n))
    o << std::setprecision(3) << n;
  else
    o << "infinitely many";
  return o.str();
}

// More steps than a run ends in (1e9 steps of one particle take hours).
constexpr double kManySteps = 1e9;

}  // namespace

std::string check_summary(const SceneDocument& doc, const InitialParticles& P) {
  const Scene& s = doc.scene;
  const std::vector<Point3> v0 = initial_velocities(s, P);
  std::ostringstream o;
  o.precision(6);
  o << "scene '" << s.name << "' from " << doc.source_name << ": valid\n";
  if (!s.description.empty()) o << "  " << s.description << "\n";
  // One line of settings per method its bodies use (a scene of both runs each
  // part with solver_for, docs/scene-reference.md "Mixed methods").
  for (Method m : {Method::tlsph, Method::ulsph}) {
    std::string names;
    for (const BodySpec& b : s.bodies)
      if (b.method == m) names += (names.empty() ? "" : ", ") + b.name;
    if (names.empty()) continue;
    const SolverSpec sv = solver_for(s.solver, m);
    o << "  dimension " << s.dimension << ", method " << to_string(m) << ", hourglass " << to_string(sv.hourglass)
      << ", h/dp " << sv.h_over_dp << ", CFL " << sv.cfl << ", end time " << sv.end_time << " s, precision "
      << to_string(sv.precision) << "\n";
    if (mixed_methods(s)) o << "    bodies: " << names << "\n";
    const char* sound_speed =
        sv.sound_speed == SoundSpeed::bulk ? "bulk sqrt(K/rho0)" : "p-wave sqrt((K+4G/3)/rho0)";
    if (m == Method::ulsph) {
      const UlsphSpec& u = sv.ulsph;
      o << "  " << (u.dual_time_stepping ? "dual-criteria" : "single-criterion") << " time stepping (advection CFL "
        << u.advection_cfl << ", reference speed " << u.reference_speed << " m/s), pair data "
        << (u.refresh_pairs ? "formed every step" : "frozen over the advection step") << ", J2 return "
        << (u.remove_plastic_rate ? "seed" : "radial") << ", Riemann dissipation ";
      if (u.riemann_limiter > 0)
        o << "limited (eta " << u.riemann_limiter << ")";
      else
        o << "full";
      o << ", sound speed " << sound_speed << "\n";
    } else {
      o << "  damping factor " << sv.damping_factor << " ("
        << (sv.damping_form == DampingForm::split ? "split" : "isotropic") << "), sound speed " << sound_speed
        << ", kernel correction in force sums: " << (sv.correction_in_force ? "yes" : "no") << "\n";
    }
  }
  if (s.solver.relaxation.enabled) {
    const RelaxationSpec& r = s.solver.relaxation;
    o << "  dynamic relaxation: ";
    if (r.factor > 0)
      o << "factor " << r.factor << " (eta = factor p rho0 c0 h / CFL)";
    else
      o << "viscosity " << r.viscosity << " Pa s";
    o << ", random ratio " << r.random_ratio << ", seed " << r.seed << ", from t = " << r.t_start << " s";
    if (r.t_end < 1e299) o << " to " << r.t_end << " s";
    o << "; clamped and velocity-condition particles held\n";
  }
  double dt = 1e300, vmax_all = 0;
  for (size_t b = 0; b < s.bodies.size(); ++b) {
    const BodySpec& body = s.bodies[b];
    const BodyProperties p = body_properties(body, s.solver, s.dimension);
    const long n = P.body_range[b].end - P.body_range[b].begin;
    double vmax = 0;
    for (long i = P.body_range[b].begin; i < P.body_range[b].end; ++i) {
      const auto& v = v0[size_t(i)];
      vmax = std::max(vmax, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    }
    dt = std::min(dt, s.solver.cfl * p.h / (p.c0 + vmax));
    vmax_all = std::max(vmax_all, vmax);
    o << "  body '" << body.name << "': " << n << " particles (" << P.constrained_count[b] << " clamped), "
      << to_string(body.material.model) << ", rho0 " << body.material.density << ", E " << body.material.youngs_modulus
      << ", nu " << body.material.poisson_ratio << ", dp " << body.spacing << ", h " << p.h << ", c0 " << p.c0
      << " m/s, max initial speed " << vmax << " m/s\n";
    const FractureSpec& f = body.material.fracture;
    if (f.enabled) {
      long bounded = 0;
      for (long i = P.body_range[b].begin; i < P.body_range[b].end; ++i)
        bounded += !P.phase_field_lower.empty() && P.phase_field_lower[size_t(i)] > 0;
      const double c = f.speed > 0 ? f.speed : std::sqrt((p.K + 4.0 * p.G / 3.0) / body.material.density);
      o << "    fracture: Gc " << f.energy_release_rate << " J/m^2, eps0 " << f.length_scale << " m ("
        << f.length_scale / body.spacing << " dp), s_l " << f.phase_field_limit << ", phase-field speed " << c
        << " m/s, " << f.notches.size() << " notch(es), " << bounded << " particle(s) with a restricted phase field\n";
    }
  }
  for (size_t c = 0; c < s.clamps.size(); ++c)
    o << "  clamp '" << s.clamps[c].name << "' on body '" << s.clamps[c].body << "': " << P.clamp_particles[c].size()
      << " particles\n";
  const char* type_name[] = {"velocity condition", "point load", "traction load", "acceleration load"};
  const char* axes[3] = {"x", "y", "z"};
  for (size_t c = 0; c < s.conditions.size(); ++c) {
    const ConditionSpec& cond = s.conditions[c];
    const auto& sel = P.condition_particles[c];
    o << "  " << type_name[int(cond.type)] << " '" << cond.name << "' on body '" << cond.body << "': " << sel.ids.size()
      << " particles";
    if (!sel.area.empty()) {
      double area = 0;
      for (double a : sel.area) area += a;
      o << " (surface area " << area << (s.dimension == 2 ? " m^2 per m depth" : " m^2") << ")";
    }
    o << ", components";
    for (int a = 0; a < s.dimension; ++a)
      if (!cond.value[size_t(a)].empty()) o << " " << axes[a];
    if (cond.t_start > 0 || cond.t_end < 1e300) o << ", active for t in [" << cond.t_start << ", " << cond.t_end << "]";
    o << "\n";
  }
  for (size_t k = 0; k < s.measure_planes.size(); ++k)
    o << "  measure plane '" << s.measure_planes[k].name << "': " << P.measure_particles[k].size() << " particles\n";
  for (size_t k = 0; k < s.probes.size(); ++k) {
    const auto& members = P.probe_particles[k];
    Point3 x{0, 0, 0};
    for (long i : members)
      for (int a = 0; a < 3; ++a) x[a] += P.position[size_t(i)][a] / double(members.size());
    o << "  probe '" << s.probes[k].name << "': " << members.size() << " particle(s) centred at (" << x[0] << ", "
      << x[1];
    if (s.dimension == 3) o << ", " << x[2];
    o << ")\n";
  }
  const double steps = s.solver.end_time / dt;
  o << "  initial time step " << dt << " s, about " << count_text(steps) << " steps, "
    << count_text(steps * double(P.size()) / 1e6) << " million particle-steps; "
    << count_text(s.solver.end_time / s.output.interval) << " snapshots\n";
  if (!(steps <= kManySteps))
    o << "  warning: about " << count_text(steps) << " steps at the initial time step (more than "
      << count_text(kManySteps) << ": the run would take days or never end); check the initial velocities (fastest "
      << count_text(vmax_all) << " m/s), the materials' sound speeds and end_time\n";
  return o.str();
}

}  // namespace mfsd
