// Geometry of bodies and regions: boxes combined by union and difference
// (constructive solid geometry). Coordinates are 3-component; 2-D scenes
// ignore z. Boundaries are inclusive.
#pragma once
#include <array>
#include <string>
#include <vector>

namespace mfsd {

using Point3 = std::array<double, 3>;

struct Bounds {
  Point3 min{0, 0, 0};
  Point3 max{0, 0, 0};
};

struct Shape {
  enum class Kind { box, union_of, difference };
  Kind kind = Kind::box;
  Point3 min{0, 0, 0};          // box
  Point3 max{0, 0, 0};          // box
  std::vector<Shape> children;  // union_of: any; difference: first minus the others

  static Shape box(const Point3& lo, const Point3& hi) {
    Shape s;
    s.kind = Kind::box;
    s.min = lo;
    s.max = hi;
    return s;
  }

  // Inside test; `dim` = 2 ignores z. `tol` widens boxes (absolute length).
  bool contains(const Point3& p, int dim, double tol = 0.0) const;
  // Axis-aligned bounding box (of the union; a difference keeps its first part's box).
  Bounds bounds(int dim) const;
  std::string describe() const;
};

}  // namespace mfsd
