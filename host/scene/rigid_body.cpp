#include "host/scene/rigid_body.hpp"

#include <cmath>
#include <map>

#include "host/expr/expression_error.hpp"
#include "host/scene/scene_error.hpp"
#include "host/scene/surface.hpp"

namespace mfsd {

RigidBodyMotion::RigidBodyMotion(const RigidBodySpec& spec,
                                 const std::vector<std::pair<std::string, double>>& constants, const std::string& path)
    : spec_(spec) {
  std::map<std::string, double> c(constants.begin(), constants.end());
  const expr::VariableTable vars{{"t"}};
  const char* axes[3] = {"x", "y", "z"};
  auto compile = [&](const std::string& text, const std::string& where) {
    try {
      return expr::compile(text, vars, c);
    } catch (const expr::ExpressionError& e) {
      throw SceneError(where + ": " + e.what());
    }
  };
  for (int a = 0; a < 3; ++a)
    translation_[size_t(a)] = compile(spec.translation[size_t(a)], path + "/translation/" + axes[a]);
  angle_ = compile(spec.angle_degrees, path + "/rotation/angle_degrees");
}

Point3 RigidBodyMotion::translation(double t) const {
  Point3 d{0, 0, 0};
  for (int a = 0; a < 3; ++a) d[a] = translation_[size_t(a)].evaluate_host(&t);
  return d;
}

std::array<double, 9> RigidBodyMotion::rotation(double t) const {
  return rotation_matrix(spec_.axis, angle_.evaluate_host(&t) * M_PI / 180);
}

Point3 RigidBodyMotion::position(const Point3& X, double t) const {
  const auto R = rotation(t);
  const Point3 d = translation(t), &c = spec_.center;
  const Point3 r{X[0] - c[0], X[1] - c[1], X[2] - c[2]};
  Point3 x{0, 0, 0};
  for (int a = 0; a < 3; ++a)
    x[a] = c[a] + R[size_t(3 * a)] * r[0] + R[size_t(3 * a + 1)] * r[1] + R[size_t(3 * a + 2)] * r[2] + d[a];
  return x;
}

Point3 RigidBodyMotion::reference(const Point3& x, double t) const {
  const auto R = rotation(t);
  const Point3 d = translation(t), &c = spec_.center;
  const Point3 r{x[0] - d[0] - c[0], x[1] - d[1] - c[1], x[2] - d[2] - c[2]};
  Point3 X{0, 0, 0};
  for (int a = 0; a < 3; ++a)  // R^T r
    X[a] = c[a] + R[size_t(a)] * r[0] + R[size_t(3 + a)] * r[1] + R[size_t(6 + a)] * r[2];
  return X;
}

std::vector<Point3> rigid_body_markers(const Shape& shape, int dim, double spacing) {
  const Bounds bb = shape.bounds(dim);
  long n[3] = {1, 1, 1};
  for (int a = 0; a < dim; ++a) n[a] = std::max(1L, long(std::ceil((bb.max[a] - bb.min[a]) / spacing - 1e-6)));
  std::vector<Point3> inside;
  for (long k = 0; k < n[2]; ++k)
    for (long j = 0; j < n[1]; ++j)
      for (long i = 0; i < n[0]; ++i) {
        const Point3 p{bb.min[0] + (double(i) + 0.5) * spacing, bb.min[1] + (double(j) + 0.5) * spacing,
                       dim == 3 ? bb.min[2] + (double(k) + 0.5) * spacing : 0.0};
        if (shape.contains(p, dim, 1e-9 * spacing)) inside.push_back(p);
      }
  std::vector<unsigned char> surface(inside.size(), 0);
  mark_surface(inside, 0, long(inside.size()), spacing, dim, surface);
  std::vector<Point3> out;
  for (size_t k = 0; k < inside.size(); ++k)
    if (surface[k]) out.push_back(inside[k]);
  return out;
}

}  // namespace mfsd
