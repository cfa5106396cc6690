// material.fracture of a body (docs/scene-reference.md, "Fracture"; seed 001
// sections 2.2-2.4 and 3.3.1).
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"

namespace mfsd {

namespace {

Point3 minus(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Point3 cross3(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot3(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double length(const Point3& a) { return std::sqrt(dot3(a, a)); }

std::string number_text(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

// A segment of positive length (2-D) or a planar, convex quadrilateral of
// positive area (3-D), measured against the body's spacing.
void check_notch(const std::vector<Point3>& p, int dim, double spacing, const std::string& path) {
  const double tiny = 1e-6 * spacing;
  if (dim == 2) {
    if (length(minus(p[1], p[0])) <= tiny)
      throw SceneError(path, "a notch of zero length", "two distinct ends (a segment in the reference configuration)");
    return;
  }
  const Point3 normal = cross3(minus(p[2], p[0]), minus(p[3], p[1]));
  const double area = 0.5 * length(normal);
  if (area <= tiny * tiny)
    throw SceneError(path, "a degenerate quadrilateral (zero area)", "4 corners of a planar quadrilateral, in order");
  const Point3 n{normal[0] / (2 * area), normal[1] / (2 * area), normal[2] / (2 * area)};
  double size = 0;
  for (int k = 0; k < 4; ++k) size = std::max(size, length(minus(p[size_t((k + 1) % 4)], p[size_t(k)])));
  for (int k = 0; k < 4; ++k)
    if (std::fabs(dot3(n, minus(p[size_t(k)], p[0]))) > 1e-6 * size)
      throw SceneError(path, "corner " + std::to_string(k) + " off the plane of the others",
                       "4 corners of a planar quadrilateral");
  for (int k = 0; k < 4; ++k) {
    const Point3 e1 = minus(p[size_t((k + 1) % 4)], p[size_t(k)]);
    const Point3 e2 = minus(p[size_t((k + 2) % 4)], p[size_t((k + 1) % 4)]);
    if (dot3(cross3(e1, e2), n) <= 0)
      throw SceneError(path, "a quadrilateral that is not convex (or corners out of order)",
                       "4 corners of a convex quadrilateral, in order around it");
  }
}

}  // namespace

FractureSpec read_fracture(JsonNode f, const MaterialSpec& material, double spacing, int dim,
                           std::vector<std::string>& warnings) {
  FractureSpec spec;
  spec.enabled = true;
  if (material.plastic())
    throw SceneError(f.path(), std::string("fracture with the \"") + to_string(material.model) + "\" model",
                     "an elastic model (saint_venant_kirchhoff or neo_hookean): phase-field fracture is brittle and is "
                     "not combined with J2 plasticity (seed 001, Remark 3)");
  spec.energy_release_rate = f.number("energy_release_rate", Range::positive());
  spec.length_scale = f.number("length_scale", Range::positive());
  if (spec.length_scale < 0.25 * spacing)
    throw SceneError(f.key_path("length_scale"), number_text(spec.length_scale),
                     "a length scale of at least a quarter of the body's spacing (" + number_text(0.25 * spacing) +
                         "): the phase field cannot be resolved on fewer particles");
  if (spec.length_scale < spacing)
    warnings.push_back(f.key_path("length_scale") + ": " + number_text(spec.length_scale) +
                       " is smaller than the spacing " + number_text(spacing) +
                       "; the crack band is under-resolved (seed 001: eps0 >= dx)");
  spec.phase_field_limit = f.number("phase_field_limit", 0.1, Range{0.0, 1.0, false, true, "a number in [0, 1)"});
  spec.speed = f.number("speed", 0.0, Range::non_negative());
  auto notches = f.array("notches", false);
  for (size_t k = 0; k < notches.size(); ++k) {
    JsonNode n = f.element("notches", k, *notches[k]);
    const auto points = read_points(n, "points", dim == 3 ? 4 : 2, dim,
                                    dim == 3 ? "4 corners of a planar quadrilateral" : "the 2 ends of a segment");
    check_notch(points, dim, spacing, n.key_path("points"));
    n.finish();
    spec.notches.push_back(points);
  }
  auto restrictions = f.array("restrict_phase_field", false);
  for (size_t k = 0; k < restrictions.size(); ++k) {
    JsonNode r = f.element("restrict_phase_field", k, *restrictions[k]);
    PhaseFieldRestriction p;
    p.where = r.expression("where", "");
    if (p.where.empty())
      throw SceneError(r.key_path("where"), "nothing", "an expression of x0, y0, z0 (non-zero where s is bounded)");
    p.minimum = r.number("minimum", Range{0.0, 1.0, false, false, "a number in [0, 1]"});
    r.finish();
    spec.restrictions.push_back(p);
  }
  if (f.has("crack_direction")) {
    const auto d = f.vector("crack_direction", size_t(dim), Range::any());
    double n2 = 0;
    for (int a = 0; a < dim; ++a) spec.crack_direction[size_t(a)] = d[size_t(a)], n2 += d[size_t(a)] * d[size_t(a)];
    if (n2 == 0) throw SceneError(f.key_path("crack_direction"), "a zero vector", "a direction (non-zero vector)");
  }
  f.finish();
  return spec;
}

}  // namespace mfsd
