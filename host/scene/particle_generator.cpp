#include "host/scene/particle_generator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "host/backend/host_memory.hpp"
#include "host/expr/expression_error.hpp"
#include "host/expr/program.hpp"
#include "host/scene/active_potential.hpp"
#include "host/scene/body_properties.hpp"
#include "host/scene/particle_expressions.hpp"
#include "host/scene/rigid_body.hpp"
#include "host/scene/scene_error.hpp"
#include "host/scene/surface.hpp"
#include "kernels/expr/interpreter.hpp"
#include "kernels/expr/particle_variables.hpp"

namespace mfsd {

namespace {

// The generator tests every cell of a body's bounding box; more cells than
// this take minutes and no memory holds their particles (about 1 kB each in a run).
constexpr double kMaxLatticeCells = 4e9;
// What the generator itself keeps per particle (positions, velocities,
// flags, selections, the surface hash) and a bit more.
constexpr double kGeneratorBytesPerParticle = 256;

std::string point_text(const Point3& p, int dim) {
  std::ostringstream s;
  s << "[" << p[0] << ", " << p[1];
  if (dim == 3) s << ", " << p[2];
  s << "]";
  return s.str();
}

std::string bytes_text(double bytes) {
  std::ostringstream s;
  s.precision(3);
  s << bytes / 1e9 << " GB";
  return s.str();
}

// Lattice cells of size dp tiling a bounding box, per axis (1 for unused
// axes); throws when there are more than kMaxLatticeCells (or the box is not
// finite), before any is visited: each is tested one by one.
std::array<long, 3> lattice_cells(const Bounds& bb, double dp, int dim, double at_least,
                                  const std::string& spacing_path) {
  double n[3] = {1, 1, 1};
  for (int a = 0; a < dim; ++a) n[a] = std::ceil((bb.max[a] - bb.min[a]) / dp - 1e-6);
  const double total = n[0] * n[1] * n[2];  // NaN for a box that is not finite
  if (!(total <= kMaxLatticeCells)) {
    std::ostringstream got;
    got.precision(3);
    got << dp << " for a bounding box of " << point_text(bb.min, dim) << " to " << point_text(bb.max, dim) << " ("
        << n[0] << " x " << n[1];
    if (dim == 3) got << " x " << n[2];
    got << " = " << total << " lattice cells)";
    std::ostringstream limit;
    limit.precision(3);
    limit << "a spacing and a geometry that give at most " << kMaxLatticeCells << " lattice cells";
    throw SceneError(spacing_path, got.str(), limit.str());
  }
  for (int a = 0; a < dim; ++a) n[a] = std::max(at_least, n[a]);
  return {long(n[0]), long(n[1]), long(n[2])};
}

// Lattice points of a body: centres of the cells of size dp tiling its
// bounding box. `total` counts the particles of earlier bodies: the fill stops
// with an error before the particles outgrow memory (a bad_alloc later).
void fill_body(const BodySpec& body, int dim, const std::string& path, std::vector<Point3>& out) {
  const Bounds bb = body.geometry.bounds(dim);
  const double dp = body.spacing;
  const std::array<long, 3> n = lattice_cells(bb, dp, dim, 0.0, path + "/spacing");
  const double tol = 1e-9 * dp;
  const double limit = host_memory_limit_bytes();
  for (long k = 0; k < n[2]; ++k)
    for (long j = 0; j < n[1]; ++j) {
      for (long i = 0; i < n[0]; ++i) {
        Point3 p{bb.min[0] + (double(i) + 0.5) * dp, bb.min[1] + (double(j) + 0.5) * dp,
                 dim == 3 ? bb.min[2] + (double(k) + 0.5) * dp : 0.0};
        if (body.geometry.contains(p, dim, tol)) out.push_back(p);
      }
      if (double(out.size()) * kGeneratorBytesPerParticle > limit / 2) {
        std::ostringstream got;
        got.precision(3);
        got << dp << " (" << out.size() << " particles after " << 100.0 * double(k * n[1] + j + 1) / double(n[1] * n[2])
            << " % of the lattice: " << bytes_text(double(out.size()) * kGeneratorBytesPerParticle)
            << " to set them up, more for the run)";
        throw SceneError(path + "/spacing", got.str(),
                         "a scene whose particles fit in memory (" + bytes_text(limit) + " available to mfsd)");
      }
    }
}

void evaluate_program(const Scene& scene, const expr::Program& prog, const std::string& epath, long begin, long end,
                      const std::vector<Point3>& position, int a, std::vector<Point3>& out);

// Evaluates one expression of x0 y0 z0 (and body b's constants) at every
// particle of [begin, end) into component `a` of `out`; 'skip' leaves the value.
void evaluate_particle_expression(const Scene& scene, size_t b, const std::string& text, const std::string& epath,
                                  long begin, long end, const std::vector<Point3>& position, int a,
                                  std::vector<Point3>& out) {
  std::map<std::string, double> constants;
  for (auto& kv : body_expression_constants(scene, b)) constants[kv.first] = kv.second;
  const expr::VariableTable vars{{"x0", "y0", "z0"}};
  expr::Program prog;
  try {
    prog = expr::compile(text, vars, constants);
  } catch (const expr::ExpressionError& e) {
    throw SceneError(epath + ": " + e.what());
  }
  evaluate_program(scene, prog, epath, begin, end, position, a, out);
}

// The same with a compiled program of x0 y0 z0 first (the particle
// variables' order, particle_expressions.hpp, or x0 y0 z0 alone).
void evaluate_program(const Scene& scene, const expr::Program& prog, const std::string& epath, long begin, long end,
                      const std::vector<Point3>& position, int a, std::vector<Point3>& out) {
  const auto view = prog.host_view<double>();
  for (long i = begin; i < end; ++i) {
    const Point3& x = position[size_t(i)];
    double vars[kParticleVariables] = {x[0], x[1], x[2]};
    double value = 0;
    int pc = 0;
    const expr::Status st = expr::evaluate(view, vars, &value, &pc);
    if (st == expr::Status::skipped) continue;
    if (st != expr::Status::ok)
      throw SceneError(epath + ": " + prog.describe_error(st, pc) + " at x0 = " + point_text(x, scene.dimension));
    out[size_t(i)][a] = value;
  }
}

// Evaluates the components of a body's initial field (velocity or
// displacement) at every particle of the body; 'skip' leaves the value.
void evaluate_initial_field(const Scene& scene, size_t b, const std::array<std::string, 3>& texts,
                            const std::string& path, long begin, long end, const std::vector<Point3>& position,
                            std::vector<Point3>& out) {
  const char* axis_name[3] = {"x", "y", "z"};
  for (int a = 0; a < scene.dimension; ++a)
    evaluate_particle_expression(scene, b, texts[size_t(a)], path + "/" + axis_name[a], begin, end, position, a, out);
}

// A body's reference map (docs/scene-reference.md): the lattice points move
// to X = map(x0), each volume scales by det(d map / d x0) (central differences
// with step dp/100, exact for maps that are linear over that step); the
// reference configuration is stress free.
void map_reference(const Scene& scene, size_t b, const std::string& path, InitialParticles& P) {
  const int dim = scene.dimension;
  const long begin = P.body_range[b].begin, end = P.body_range[b].end;
  const double h = 0.01 * scene.bodies[b].spacing;
  // 'skip' keeps the lattice point.
  std::vector<Point3> mapped = P.position, plus, minus;
  evaluate_initial_field(scene, b, scene.bodies[b].reference_map, path, begin, end, P.position, mapped);
  std::vector<std::array<double, 9>> jac(size_t(end - begin));
  for (int c = 0; c < dim; ++c) {
    std::vector<Point3> shifted_p = P.position, shifted_m = P.position;
    for (long i = begin; i < end; ++i) shifted_p[size_t(i)][c] += h, shifted_m[size_t(i)][c] -= h;
    plus = shifted_p;
    minus = shifted_m;
    evaluate_initial_field(scene, b, scene.bodies[b].reference_map, path, begin, end, shifted_p, plus);
    evaluate_initial_field(scene, b, scene.bodies[b].reference_map, path, begin, end, shifted_m, minus);
    for (long i = begin; i < end; ++i)
      for (int a = 0; a < dim; ++a) jac[size_t(i - begin)][size_t(3 * a + c)] = (plus[i][a] - minus[i][a]) / (2 * h);
  }
  for (long i = begin; i < end; ++i) {
    const auto& m = jac[size_t(i - begin)];
    const double J = dim == 2 ? m[0] * m[4] - m[1] * m[3]
                              : m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                                    m[2] * (m[3] * m[7] - m[4] * m[6]);
    if (!(J > 0))
      throw SceneError(
          path,
          "a map with det(d map / d x0) = " + std::to_string(J) + " at x0 = " + point_text(P.position[size_t(i)], dim),
          "a map that keeps every particle's volume positive (no fold, no collapse)");
    P.volume[size_t(i)] *= J;
  }
  for (long i = begin; i < end; ++i)
    for (int a = 0; a < dim; ++a) P.position[size_t(i)][a] = mapped[size_t(i)][a];
}

// The particles of body b that a selection holds.
std::vector<long> select_particles(const Scene& scene, size_t b, const SelectionSpec& sel, const std::string& path,
                                   const InitialParticles& P) {
  const int dim = scene.dimension;
  const auto r = P.body_range[b];
  std::vector<long> ids;
  if (sel.kind == SelectionSpec::Kind::body) {
    for (long i = r.begin; i < r.end; ++i) ids.push_back(i);
  } else if (sel.kind == SelectionSpec::Kind::region) {
    const double tol = 1e-9 * scene.bodies[b].spacing;
    for (long i = r.begin; i < r.end; ++i)
      if (sel.region.contains(P.position[size_t(i)], dim, tol)) ids.push_back(i);
  } else if (sel.kind == SelectionSpec::Kind::near) {
    // Within `distance` of the rigid body at t = 0 (the shape widened by it).
    const RigidBodySpec* rb = nullptr;
    for (auto& r : scene.rigid_bodies)
      if (r.name == sel.rigid_body) rb = &r;
    const RigidBodyMotion motion(*rb, scene.constants, path + "/near");
    const double tol = sel.distance + 1e-9 * scene.bodies[b].spacing;
    for (long i = r.begin; i < r.end; ++i)
      if (rb->shape.contains(motion.reference(P.position[size_t(i)], 0.0), dim, tol)) ids.push_back(i);
  } else {
    std::map<std::string, double> constants;
    for (auto& kv : body_expression_constants(scene, b)) constants[kv.first] = kv.second;
    expr::Program prog;
    try {
      prog = expr::compile(sel.expression, expr::VariableTable{{"x0", "y0", "z0"}}, constants);
    } catch (const expr::ExpressionError& e) {
      throw SceneError(path + "/where: " + e.what());
    }
    const auto view = prog.host_view<double>();
    for (long i = r.begin; i < r.end; ++i) {
      const Point3& x = P.position[size_t(i)];
      double value = 0;
      int pc = 0;
      const expr::Status st = expr::evaluate(view, x.data(), &value, &pc);
      if (st == expr::Status::skipped) continue;  // 'skip': not selected
      if (st != expr::Status::ok)
        throw SceneError(path + "/where: " + prog.describe_error(st, pc) + " at x0 = " + point_text(x, dim));
      if (value != 0) ids.push_back(i);
    }
  }
  return ids;
}

Point3 sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// The particles within thickness / 2 of a measure plane's segment (2-D) or
// convex planar quadrilateral (3-D), in the reference configuration.
std::vector<long> measure_plane_particles(const Scene& scene, const MeasurePlaneSpec& m, const std::string& path,
                                          const InitialParticles& P) {
  const int dim = scene.dimension;
  double thickness = m.thickness;
  if (thickness == 0) {  // default: the body's spacing (the smallest one without a body)
    thickness = 1e300;
    for (auto& b : scene.bodies)
      if (m.body.empty() || b.name == m.body) thickness = std::min(thickness, b.spacing);
  }
  const std::vector<Point3>& c = m.points;
  Point3 n{0, 0, 0};
  double size = 0;
  for (auto& p : c) size = std::max(size, std::sqrt(dot(sub(p, c[0]), sub(p, c[0]))));
  if (size == 0) throw SceneError(path + "/points", "coincident points", "a segment or quadrilateral of non-zero size");
  if (dim == 2) {
    const Point3 d = sub(c[1], c[0]);
    n = {-d[1] / size, d[0] / size, 0};
  } else {
    n = cross(sub(c[2], c[0]), sub(c[3], c[1]));
    const double nn = std::sqrt(dot(n, n));
    if (nn < 1e-12 * size * size)
      throw SceneError(path + "/points", "a degenerate or self-crossing quadrilateral",
                       "4 corners in order around a convex quadrilateral of non-zero area");
    for (auto& x : n) x /= nn;
    for (auto& p : c)
      if (std::abs(dot(sub(p, c[0]), n)) > 1e-6 * size)
        throw SceneError(path + "/points", "corners that are not in one plane", "4 coplanar corners");
    for (size_t k = 0; k < 4; ++k) {  // convex, corners in order
      const Point3 e0 = sub(c[(k + 1) % 4], c[k]), e1 = sub(c[(k + 2) % 4], c[(k + 1) % 4]);
      if (dot(cross(e0, e1), n) <= 0)
        throw SceneError(path + "/points", "a non-convex or self-crossing quadrilateral",
                         "4 corners in order around a convex quadrilateral");
    }
  }
  const double tol = 1e-9 * size;
  std::vector<long> ids;
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    if (!m.body.empty() && scene.bodies[b].name != m.body) continue;
    for (long i = P.body_range[b].begin; i < P.body_range[b].end; ++i) {
      const Point3 x = sub(P.position[size_t(i)], c[0]);
      if (std::abs(dot(x, n)) > 0.5 * thickness + tol) continue;
      bool inside = true;
      if (dim == 2) {
        const Point3 d = sub(c[1], c[0]);
        const double s = dot(x, d) / dot(d, d);
        inside = s >= -tol / size && s <= 1 + tol / size;
      } else {
        for (size_t k = 0; k < 4 && inside; ++k)
          inside = dot(cross(sub(c[(k + 1) % 4], c[k]), sub(P.position[size_t(i)], c[k])), n) >= -tol * size;
      }
      if (inside) ids.push_back(i);
    }
  }
  if (ids.empty())
    throw SceneError(path, "a plane that holds no particle",
                     "points and a thickness (" + std::to_string(thickness) + " m) that hold at least one particle");
  return ids;
}

// Velocity conditions active at t = 0 set velocities before the first step
// (in order, each from the velocities the earlier ones left, as the solver
// does): an expression that fails there is an input error, found before a
// run makes its folder. Evaluated in the scene's precision.
template <class Real>
void check_initial_velocity_conditions(const Scene& scene, const InitialParticles& P) {
  const int dim = scene.dimension;
  std::vector<Point3> v = P.velocity;
  size_t n_velocity = 0;
  const char* axis_name[3] = {"x", "y", "z"};
  for (size_t c = 0; c < scene.conditions.size(); ++c) {
    const ConditionSpec& cond = scene.conditions[c];
    if (cond.type != ConditionSpec::Type::velocity) continue;
    const std::string path = "/velocity_conditions/" + std::to_string(n_velocity++);
    if (cond.t_start > 0) continue;
    size_t b = 0;
    while (scene.bodies[b].name != cond.body) ++b;
    const auto& ids = P.condition_particles[c].ids;
    std::vector<Point3> next = v;
    for (int a = 0; a < dim; ++a) {
      if (cond.value[size_t(a)].empty()) continue;
      const std::string cpath = path + "/" + axis_name[a];
      const expr::Program prog = compile_particle_expression(cond.value[size_t(a)], scene, b, cpath);
      expr::ProgramView<Real> view;
      try {
        view = prog.host_view<Real>();
      } catch (const expr::ExpressionError& e) {
        throw SceneError(cpath + ": " + e.what());
      }
      for (long i : ids) {
        Real vars[kParticleVariables] = {};
        for (int k = 0; k < 3; ++k) {
          const double u = P.displacement.empty() ? 0.0 : P.displacement[size_t(i)][k];
          vars[var_x0 + k] = Real(P.position[size_t(i)][k]);
          vars[var_ux + k] = Real(u);
          vars[var_x + k] = Real(P.position[size_t(i)][k] + u);
          vars[var_vx + k] = Real(v[size_t(i)][k]);
        }
        vars[var_dx] = Real(scene.bodies[b].spacing);
        Real value = 0;
        int pc = 0;
        const expr::Status st = expr::evaluate(view, vars, &value, &pc);
        if (st == expr::Status::skipped) continue;
        if (st != expr::Status::ok)
          throw SceneError(cpath + ": " + prog.describe_error(st, pc) +
                           " at t = 0, x0 = " + point_text(P.position[size_t(i)], dim));
        next[size_t(i)][a] = double(value);
      }
    }
    v = std::move(next);
  }
}

}  // namespace

std::vector<std::pair<std::string, double>> body_expression_constants(const Scene& scene, size_t b) {
  const BodySpec& body = scene.bodies[b];
  const BodyProperties p = body_properties(body, scene.solver, scene.dimension);
  std::vector<std::pair<std::string, double>> c = scene.constants;
  c.insert(c.end(), {{"rho0", body.material.density},
                     {"E", body.material.youngs_modulus},
                     {"nu", body.material.poisson_ratio},
                     {"K", p.K},
                     {"G", p.G},
                     {"c0", p.c0},
                     {"cs", p.c_shear},
                     {"dp", body.spacing},
                     {"h", p.h}});
  return c;
}

// Fracturing bodies: every notch must reach into its body (its bounding box,
// widened by a spacing, meets the body's particles), and restrict_phase_field
// selections give a per-particle lower bound on s.
void fracture_setup(const Scene& scene, InitialParticles& P) {
  const int dim = scene.dimension;
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    const FractureSpec& f = scene.bodies[b].material.fracture;
    if (!f.enabled) continue;
    const std::string path = "/bodies/" + std::to_string(b) + "/material/fracture";
    const auto r = P.body_range[b];
    Point3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (long i = r.begin; i < r.end; ++i)
      for (int a = 0; a < dim; ++a) {
        lo[size_t(a)] = std::min(lo[size_t(a)], P.position[size_t(i)][size_t(a)]);
        hi[size_t(a)] = std::max(hi[size_t(a)], P.position[size_t(i)][size_t(a)]);
      }
    const double dp = scene.bodies[b].spacing;
    for (size_t k = 0; k < f.notches.size(); ++k) {
      bool meets = true;
      for (int a = 0; a < dim; ++a) {
        double nlo = 1e300, nhi = -1e300;
        for (const Point3& x : f.notches[k]) nlo = std::min(nlo, x[size_t(a)]), nhi = std::max(nhi, x[size_t(a)]);
        meets = meets && nhi >= lo[size_t(a)] - dp && nlo <= hi[size_t(a)] + dp;
      }
      if (!meets)
        throw SceneError(path + "/notches/" + std::to_string(k) + "/points",
                         "a notch outside body '" + scene.bodies[b].name + "' (particles span " + point_text(lo, dim) +
                             " to " + point_text(hi, dim) + ")",
                         "a notch that cuts into its body");
    }
    for (size_t k = 0; k < f.restrictions.size(); ++k) {
      SelectionSpec sel;
      sel.kind = SelectionSpec::Kind::expression;
      sel.expression = f.restrictions[k].where;
      const auto ids = select_particles(scene, b, sel, path + "/restrict_phase_field/" + std::to_string(k), P);
      if (P.phase_field_lower.empty()) P.phase_field_lower.assign(P.size(), 0.0);
      for (long i : ids)
        P.phase_field_lower[size_t(i)] = std::max(P.phase_field_lower[size_t(i)], f.restrictions[k].minimum);
    }
  }
}

// Fibre and sheet directions and the active tension of Holzapfel-Ogden body b
// (docs/scene-reference.md): each direction normalised; zero, non-finite or
// (sheet) non-orthogonal directions are errors naming the particle.
void material_directions(const Scene& scene, size_t b, const std::string& path, InitialParticles& P) {
  const int dim = scene.dimension;
  const HolzapfelOgdenSpec& h = scene.bodies[b].material.holzapfel_ogden;
  const long begin = P.body_range[b].begin, end = P.body_range[b].end;
  if (P.fibre.empty()) {
    P.fibre.assign(P.size(), Point3{0, 0, 0});
    P.sheet.assign(P.size(), Point3{0, 0, 0});
    P.active_tension.assign(P.size(), 0.0);
  }
  auto norm = [&](const Point3& v) {
    double s = 0;
    for (int a = 0; a < dim; ++a) s += v[a] * v[a];
    return std::sqrt(s);
  };
  auto directions = [&](const std::array<std::string, 3>& text, const Point3& fallback, const std::string& key,
                        std::vector<Point3>& out) {
    if (text[0].empty()) {
      for (long i = begin; i < end; ++i) out[size_t(i)] = fallback;
      return;
    }
    evaluate_initial_field(scene, b, text, path + "/" + key, begin, end, P.position, out);
    for (long i = begin; i < end; ++i) {
      Point3& v = out[size_t(i)];
      const double n = norm(v);
      if (!std::isfinite(n) || !(n > 1e-12))
        throw SceneError(path + "/" + key,
                         "the direction " + point_text(v, dim) + " at x0 = " + point_text(P.position[size_t(i)], dim),
                         "a finite, non-zero direction at every particle (it is normalised)");
      for (int a = 0; a < dim; ++a) v[a] /= n;
    }
  };
  directions(h.fibre, Point3{1, 0, 0}, "fibre", P.fibre);
  directions(h.sheet, Point3{0, 1, 0}, "sheet", P.sheet);
  if (!h.sheet[0].empty() && !h.fibre[0].empty())
    for (long i = begin; i < end; ++i) {
      const Point3 &f = P.fibre[size_t(i)], &s = P.sheet[size_t(i)];
      double c = 0;
      for (int a = 0; a < dim; ++a) c += f[a] * s[a];
      if (std::fabs(c) > 1e-3)
        throw SceneError(path + "/sheet",
                         "f0 . s0 = " + std::to_string(c) + " at x0 = " + point_text(P.position[size_t(i)], dim),
                         "a sheet direction orthogonal to the fibre (|f0 . s0| <= 1e-3)");
    }
  // A potential that reads t (or the motion) is evaluated each step on the
  // device (host/solver/common/conditions.hpp); this one at set-up.
  const std::string vpath = active_potential_path(b);
  if (h.active.enabled && !h.active.per_step) {
    std::vector<Point3> vm(P.size(), Point3{0, 0, 0});
    evaluate_program(scene, active_potential_program(scene, b), vpath, begin, end, P.position, 0, vm);
    for (long i = begin; i < end; ++i) {
      const double t = h.active.tension_per_potential * vm[size_t(i)][0];
      if (!std::isfinite(t))
        throw SceneError(
            vpath, "V_m = " + std::to_string(vm[size_t(i)][0]) + " at x0 = " + point_text(P.position[size_t(i)], dim),
            "a finite transmembrane potential at every particle");
      P.active_tension[size_t(i)] = t;
    }
  }
}

InitialParticles generate_particles(const Scene& scene) {
  const int dim = scene.dimension;
  InitialParticles P;
  P.dimension = dim;
  std::map<std::string, size_t> body_index;
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodySpec& body = scene.bodies[b];
    body_index[body.name] = b;
    const std::string path = "/bodies/" + std::to_string(b);
    const long begin = long(P.position.size());
    fill_body(body, dim, path, P.position);
    const long end = long(P.position.size());
    if (end == begin)
      throw SceneError(path + "/geometry", body.geometry.describe(),
                       "a geometry that holds at least one particle at spacing " + std::to_string(body.spacing));
    P.body_range.push_back({begin, end});
    const BodyProperties props = body_properties(body, scene.solver, dim);
    P.body.resize(size_t(end), int(b));
    P.volume.resize(size_t(end), props.volume);
  }
  // Faces on the lattice, before a reference map moves the points.
  P.surface.assign(P.position.size(), 0);
  for (size_t b = 0; b < scene.bodies.size(); ++b)
    mark_surface(P.position, P.body_range[b].begin, P.body_range[b].end, scene.bodies[b].spacing, dim, P.surface);
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodySpec& body = scene.bodies[b];
    const std::string path = "/bodies/" + std::to_string(b);
    if (!body.reference_map[0].empty()) map_reference(scene, b, path + "/reference_map", P);
    // Initial velocity: one expression per component of x0, y0, z0 and constants.
    P.velocity.resize(P.position.size(), Point3{0, 0, 0});
    evaluate_initial_field(scene, b, body.initial_velocity, path + "/initial_velocity", P.body_range[b].begin,
                           P.body_range[b].end, P.position, P.velocity);
  }
  for (size_t b = 0; b < scene.bodies.size(); ++b)
    if (scene.bodies[b].material.model == MaterialModel::holzapfel_ogden)
      material_directions(scene, b, "/bodies/" + std::to_string(b) + "/material", P);
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodySpec& body = scene.bodies[b];
    if (body.initial_displacement[0].empty()) continue;
    P.displacement.resize(P.position.size(), Point3{0, 0, 0});
    evaluate_initial_field(scene, b, body.initial_displacement,
                           "/bodies/" + std::to_string(b) + "/initial_displacement", P.body_range[b].begin,
                           P.body_range[b].end, P.position, P.displacement);
  }
  P.constrained.assign(P.position.size(), 0);
  P.constrained_count.assign(scene.bodies.size(), 0);

  for (size_t c = 0; c < scene.clamps.size(); ++c) {
    const ClampSpec& clamp = scene.clamps[c];
    const std::string path = "/clamps/" + std::to_string(c);
    auto it = body_index.find(clamp.body);
    if (it == body_index.end()) throw SceneError(path + "/body", "\"" + clamp.body + "\"", "the name of a body");
    const auto r = P.body_range[it->second];
    long selected = 0;
    const double tol = 1e-9 * scene.bodies[it->second].spacing;
    P.clamp_particles.emplace_back();
    for (long i = r.begin; i < r.end; ++i)
      if (clamp.region.contains(P.position[size_t(i)], dim, tol)) {
        if (!P.constrained[size_t(i)]) {
          ++P.constrained_count[it->second];
          P.clamp_particles.back().push_back(i);
        }
        P.constrained[size_t(i)] = 1;
        ++selected;
      }
    if (selected == 0)
      throw SceneError(path + "/region", clamp.region.describe(),
                       "a region that holds at least one particle of body '" + clamp.body + "'");
  }
  for (size_t i = 0; i < P.position.size(); ++i)
    if (P.constrained[i]) {
      P.velocity[i] = Point3{0, 0, 0};
      if (!P.displacement.empty()) P.displacement[i] = Point3{0, 0, 0};
    }

  // Velocity conditions and loads: the selected particles, checked
  // expressions, and the surface area of traction particles.
  size_t n_velocity = 0;
  for (size_t c = 0; c < scene.conditions.size(); ++c) {
    const ConditionSpec& cond = scene.conditions[c];
    const bool velocity = cond.type == ConditionSpec::Type::velocity;
    const size_t k = velocity ? n_velocity++ : c - n_velocity;
    const std::string path = (velocity ? "/velocity_conditions/" : "/loads/") + std::to_string(k);
    const size_t b = body_index.at(cond.body);
    std::vector<long> ids = select_particles(scene, b, cond.select, path, P);
    InitialParticles::Selected sel;
    const double dp = scene.bodies[b].spacing;
    for (long i : ids) {
      if (cond.type == ConditionSpec::Type::traction &&
          (cond.face < 0 ? !P.surface[size_t(i)] : !(P.surface[size_t(i)] & (1u << cond.face))))
        continue;
      sel.ids.push_back(i);
      if (cond.type == ConditionSpec::Type::traction) sel.area.push_back(dim == 3 ? dp * dp : dp);  // 2-D: 1 m deep
    }
    if (sel.ids.empty())
      throw SceneError(path, ids.empty() ? "a selection with no particle" : "a selection with no surface particle",
                       "a selection that holds at least one " +
                           std::string(cond.type == ConditionSpec::Type::traction ? "surface " : "") +
                           "particle of body '" + cond.body + "'");
    const char* axis_name[3] = {"x", "y", "z"};
    for (int a = 0; a < dim; ++a)
      if (!cond.value[size_t(a)].empty())
        compile_particle_expression(cond.value[size_t(a)], scene, b, path + "/" + axis_name[a]);
    P.condition_particles.push_back(std::move(sel));
  }
  if (scene.solver.precision == Precision::single_precision)
    check_initial_velocity_conditions<float>(scene, P);
  else
    check_initial_velocity_conditions<double>(scene, P);

  for (size_t k = 0; k < scene.rigid_bodies.size(); ++k) {
    const RigidBodySpec& rb = scene.rigid_bodies[k];
    RigidBodyMotion(rb, scene.constants, "/rigid_bodies/" + std::to_string(k));  // checks the expressions
    lattice_cells(rb.shape.bounds(dim), rb.marker_spacing, dim, 1.0,
                  "/rigid_bodies/" + std::to_string(k) + "/marker_spacing");
    P.rigid_markers.push_back(rigid_body_markers(rb.shape, dim, rb.marker_spacing));
    if (P.rigid_markers.back().empty())
      throw SceneError("/rigid_bodies/" + std::to_string(k) + "/shape", rb.shape.describe(),
                       "a shape that holds at least one marker point at spacing " + std::to_string(rb.marker_spacing));
  }

  for (size_t k = 0; k < scene.measure_planes.size(); ++k)
    P.measure_particles.push_back(
        measure_plane_particles(scene, scene.measure_planes[k], "/measure_planes/" + std::to_string(k), P));

  for (size_t k = 0; k < scene.probes.size(); ++k) {
    const ProbeSpec& probe = scene.probes[k];
    const std::string path = "/probes/" + std::to_string(k);
    std::vector<long> members;
    bool inside = false;
    for (size_t b = 0; b < scene.bodies.size() && !inside; ++b) {
      const double tol = 1e-9 * scene.bodies[b].spacing;
      if (!scene.bodies[b].geometry.contains(probe.point, dim, tol)) continue;
      inside = true;
      long best = -1;
      double best_d2 = std::numeric_limits<double>::max();
      const double r2 = probe.radius * probe.radius * (1 + 1e-9);
      for (long i = P.body_range[b].begin; i < P.body_range[b].end; ++i) {
        double d2 = 0;
        for (int a = 0; a < dim; ++a) d2 += std::pow(P.position[size_t(i)][a] - probe.point[a], 2);
        if (d2 < best_d2) best_d2 = d2, best = i;
        if (probe.radius > 0 && d2 <= r2) members.push_back(i);
      }
      if (probe.radius == 0) members.push_back(best);
    }
    if (!inside) throw SceneError(path + "/point", point_text(probe.point, dim), "a point inside one of the bodies");
    if (members.empty())
      throw SceneError(path + "/radius", std::to_string(probe.radius),
                       "a radius that holds at least one particle around the point");
    P.probe_particles.push_back(members);
  }
  fracture_setup(scene, P);
  return P;
}

}  // namespace mfsd
