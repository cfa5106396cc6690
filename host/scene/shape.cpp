#include "host/scene/shape.hpp"

#include <algorithm>
#include <sstream>

namespace mfsd {

bool Shape::contains(const Point3& p, int dim, double tol) const {
  switch (kind) {
    case Kind::box:
      for (int a = 0; a < dim; ++a)
        if (p[a] < min[a] - tol || p[a] > max[a] + tol) return false;
      return true;
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
  if (kind == Kind::box) return Bounds{min, max};
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
  switch (kind) {
    case Kind::box:
      s << "box[(" << min[0] << ", " << min[1] << ", " << min[2] << ") - (" << max[0] << ", " << max[1] << ", "
        << max[2] << ")]";
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
