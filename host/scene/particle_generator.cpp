#include "host/scene/particle_generator.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "host/expr/expression_error.hpp"
#include "host/expr/program.hpp"
#include "host/scene/body_properties.hpp"
#include "host/scene/scene_error.hpp"
#include "kernels/expr/interpreter.hpp"

namespace mfsd {

namespace {

std::string point_text(const Point3& p, int dim) {
  std::ostringstream s;
  s << "[" << p[0] << ", " << p[1];
  if (dim == 3) s << ", " << p[2];
  s << "]";
  return s.str();
}

// Lattice points of a body: centres of the cells of size dp tiling its bounding box.
void fill_body(const BodySpec& body, int dim, std::vector<Point3>& out) {
  const Bounds bb = body.geometry.bounds(dim);
  const double dp = body.spacing;
  long n[3] = {1, 1, 1};
  for (int a = 0; a < dim; ++a) n[a] = long(std::ceil((bb.max[a] - bb.min[a]) / dp - 1e-6));
  const double tol = 1e-9 * dp;
  for (long k = 0; k < n[2]; ++k)
    for (long j = 0; j < n[1]; ++j)
      for (long i = 0; i < n[0]; ++i) {
        Point3 p{bb.min[0] + (double(i) + 0.5) * dp, bb.min[1] + (double(j) + 0.5) * dp,
                 dim == 3 ? bb.min[2] + (double(k) + 0.5) * dp : 0.0};
        if (body.geometry.contains(p, dim, tol)) out.push_back(p);
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
    fill_body(body, dim, P.position);
    const long end = long(P.position.size());
    if (end == begin)
      throw SceneError(path + "/geometry", body.geometry.describe(),
                       "a geometry that holds at least one particle at spacing " + std::to_string(body.spacing));
    P.body_range.push_back({begin, end});
    const BodyProperties props = body_properties(body, scene.solver, dim);
    P.body.resize(size_t(end), int(b));
    P.volume.resize(size_t(end), props.volume);

    // Initial velocity: one expression per component of x0, y0, z0 and constants.
    std::map<std::string, double> constants;
    for (auto& kv : body_expression_constants(scene, b)) constants[kv.first] = kv.second;
    const expr::VariableTable vars{{"x0", "y0", "z0"}};
    P.velocity.resize(size_t(end), Point3{0, 0, 0});
    const char* axis_name[3] = {"x", "y", "z"};
    for (int a = 0; a < dim; ++a) {
      const std::string epath = path + "/initial_velocity/" + axis_name[a];
      expr::Program prog;
      try {
        prog = expr::compile(body.initial_velocity[a], vars, constants);
      } catch (const expr::ExpressionError& e) {
        throw SceneError(epath + ": " + e.what());
      }
      const auto view = prog.host_view<double>();
      for (long i = begin; i < end; ++i) {
        const Point3& x = P.position[size_t(i)];
        double value = 0;
        int pc = 0;
        const expr::Status st = expr::evaluate(view, x.data(), &value, &pc);
        if (st == expr::Status::skipped) continue;  // 'skip': leave the value (0)
        if (st != expr::Status::ok)
          throw SceneError(epath + ": " + prog.describe_error(st, pc) + " at x0 = " + point_text(x, dim));
        P.velocity[size_t(i)][a] = value;
      }
    }
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
    for (long i = r.begin; i < r.end; ++i)
      if (clamp.region.contains(P.position[size_t(i)], dim, tol)) {
        if (!P.constrained[size_t(i)]) ++P.constrained_count[it->second];
        P.constrained[size_t(i)] = 1;
        ++selected;
      }
    if (selected == 0)
      throw SceneError(path + "/region", clamp.region.describe(),
                       "a region that holds at least one particle of body '" + clamp.body + "'");
  }
  for (size_t i = 0; i < P.position.size(); ++i)
    if (P.constrained[i]) P.velocity[i] = Point3{0, 0, 0};

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
  return P;
}

}  // namespace mfsd
