#include "host/scene/shape.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "host/scene/stl_mesh.hpp"

namespace mfsd {

namespace {

double dot3(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Even-odd test of a point against a closed polygon, inclusive of its edges
// up to `tol`.
bool polygon_contains(const std::vector<std::array<double, 2>>& v, double x, double y, double tol) {
  const size_t n = v.size();
  bool inside = false;
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    const double xi = v[i][0], yi = v[i][1], xj = v[j][0], yj = v[j][1];
    // On the edge (within tol): inside.
    const double ex = xj - xi, ey = yj - yi, len2 = ex * ex + ey * ey;
    const double s = len2 > 0 ? std::clamp(((x - xi) * ex + (y - yi) * ey) / len2, 0.0, 1.0) : 0.0;
    const double dx = x - (xi + s * ex), dy = y - (yi + s * ey);
    if (dx * dx + dy * dy <= tol * tol) return true;
    if ((yi > y) != (yj > y) && x < xi + (y - yi) * (xj - xi) / (yj - yi)) inside = !inside;
  }
  return inside;
}

}  // namespace

std::array<double, 9> rotation_matrix(Point3 n, double angle) {
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (auto& x : n) x /= len;
  const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;  // Rodrigues
  return {t * n[0] * n[0] + c,        t * n[0] * n[1] - s * n[2], t * n[0] * n[2] + s * n[1],
          t * n[0] * n[1] + s * n[2], t * n[1] * n[1] + c,        t * n[1] * n[2] - s * n[0],
          t * n[0] * n[2] - s * n[1], t * n[1] * n[2] + s * n[0], t * n[2] * n[2] + c};
}

bool Shape::contains(const Point3& p, int dim, double tol) const {
  switch (kind) {
    case Kind::box:
      for (int a = 0; a < dim; ++a)
        if (p[a] < min[a] - tol || p[a] > max[a] + tol) return false;
      return true;
    case Kind::sphere:
    case Kind::circle: {
      double r2 = 0;
      for (int a = 0; a < dim; ++a) r2 += (p[a] - center[a]) * (p[a] - center[a]);
      const double r = std::sqrt(r2);
      return r <= radius + tol && (inner_radius <= 0 || r >= inner_radius - tol);
    }
    case Kind::cylinder: {
      const double len = std::sqrt(dot3(axis, axis));
      const Point3 d{p[0] - center[0], p[1] - center[1], p[2] - center[2]};
      const double h = dot3(d, axis) / len;  // height along the axis
      if (h < -tol || h > len + tol) return false;
      const double r2 = std::max(0.0, dot3(d, d) - h * h), r = std::sqrt(r2);
      return r <= radius + tol && (inner_radius <= 0 || r >= inner_radius - tol);
    }
    case Kind::polygon:
      return polygon_contains(vertices, p[0], p[1], tol);
    case Kind::extrude:
      return p[2] >= z_min - tol && p[2] <= z_max + tol && children[0].contains(p, 2, tol);
    case Kind::mesh:
      // The ray test is exact on the mesh; tol only widens through the bounding box.
      return triangles->contains(p);
    case Kind::transform: {
      // x_child = R^T (x - t) / scale
      const Point3 d{p[0] - translation[0], p[1] - translation[1], p[2] - translation[2]};
      Point3 q{0, 0, 0};
      for (int a = 0; a < 3; ++a)
        q[a] = (rotation[size_t(a)] * d[0] + rotation[size_t(3 + a)] * d[1] + rotation[size_t(6 + a)] * d[2]) / scale;
      return children[0].contains(q, dim, tol / scale);
    }
    case Kind::union_of:
      return std::any_of(children.begin(), children.end(), [&](const Shape& c) { return c.contains(p, dim, tol); });
    case Kind::difference:
      if (children.empty() || !children[0].contains(p, dim, tol)) return false;
      // A removed part shrinks by tol so that the widened test stays conservative.
      for (size_t k = 1; k < children.size(); ++k)
        if (children[k].contains(p, dim, -tol)) return false;
      return true;
  }
  return false;
}

Bounds Shape::bounds(int dim) const {
  switch (kind) {
    case Kind::box:
      return Bounds{min, max};
    case Kind::sphere:
    case Kind::circle: {
      Bounds b{center, center};
      for (int a = 0; a < dim; ++a) b.min[a] -= radius, b.max[a] += radius;
      return b;
    }
    case Kind::cylinder: {
      // The end discs: along axis a a disc of radius r spans r sqrt(1 - n_a^2).
      const double len = std::sqrt(dot3(axis, axis));
      Bounds b;
      for (int a = 0; a < 3; ++a) {
        const double n = axis[a] / len, e = radius * std::sqrt(std::max(0.0, 1 - n * n));
        b.min[a] = std::min(center[a], center[a] + axis[a]) - e;
        b.max[a] = std::max(center[a], center[a] + axis[a]) + e;
      }
      return b;
    }
    case Kind::polygon: {
      Bounds b{{vertices[0][0], vertices[0][1], 0}, {vertices[0][0], vertices[0][1], 0}};
      for (auto& v : vertices)
        for (int a = 0; a < 2; ++a) b.min[a] = std::min(b.min[a], v[a]), b.max[a] = std::max(b.max[a], v[a]);
      return b;
    }
    case Kind::extrude: {
      Bounds b = children[0].bounds(2);
      b.min[2] = z_min;
      b.max[2] = z_max;
      return b;
    }
    case Kind::mesh:
      return triangles->bounds();
    case Kind::transform: {
      const Bounds c = children[0].bounds(dim);
      Bounds b;
      for (int corner = 0; corner < 8; ++corner) {
        const Point3 q{corner & 1 ? c.max[0] : c.min[0], corner & 2 ? c.max[1] : c.min[1],
                       corner & 4 ? c.max[2] : c.min[2]};
        Point3 x{0, 0, 0};
        for (int a = 0; a < 3; ++a)
          x[a] = scale * (rotation[size_t(3 * a)] * q[0] + rotation[size_t(3 * a + 1)] * q[1] +
                          rotation[size_t(3 * a + 2)] * q[2]) +
                 translation[a];
        for (int a = 0; a < 3; ++a) {
          b.min[a] = corner ? std::min(b.min[a], x[a]) : x[a];
          b.max[a] = corner ? std::max(b.max[a], x[a]) : x[a];
        }
      }
      if (dim == 2) b.min[2] = b.max[2] = 0;
      return b;
    }
    case Kind::union_of:
    case Kind::difference:
      break;
  }
  if (children.empty()) return Bounds{};
  if (kind == Kind::difference) return children[0].bounds(dim);
  Bounds b = children[0].bounds(dim);
  for (size_t k = 1; k < children.size(); ++k) {
    const Bounds c = children[k].bounds(dim);
    for (int a = 0; a < 3; ++a) {
      b.min[a] = std::min(b.min[a], c.min[a]);
      b.max[a] = std::max(b.max[a], c.max[a]);
    }
  }
  return b;
}

std::string Shape::describe() const {
  std::ostringstream s;
  auto pt = [&](const Point3& p) { s << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")"; };
  switch (kind) {
    case Kind::box:
      s << "box[";
      pt(min);
      s << " - ";
      pt(max);
      s << "]";
      break;
    case Kind::sphere:
    case Kind::circle:
      s << (kind == Kind::sphere ? "sphere[" : "circle[") << "centre ";
      pt(center);
      s << ", radius " << radius;
      if (inner_radius > 0) s << ", inner radius " << inner_radius;
      s << "]";
      break;
    case Kind::cylinder:
      s << "cylinder[base ";
      pt(center);
      s << ", axis ";
      pt(axis);
      s << ", radius " << radius;
      if (inner_radius > 0) s << ", inner radius " << inner_radius;
      s << "]";
      break;
    case Kind::polygon:
      s << "polygon[" << vertices.size() << " vertices]";
      break;
    case Kind::extrude:
      s << "extrude[" << children[0].describe() << ", z " << z_min << " to " << z_max << "]";
      break;
    case Kind::mesh:
      s << "stl['" << source << "', " << triangles->size() << " triangles]";
      break;
    case Kind::transform:
      s << "transform[" << children[0].describe() << "]";
      break;
    case Kind::union_of:
    case Kind::difference:
      s << (kind == Kind::union_of ? "union(" : "difference(");
      for (size_t k = 0; k < children.size(); ++k) s << (k ? ", " : "") << children[k].describe();
      s << ")";
      break;
  }
  return s.str();
}

}  // namespace mfsd
