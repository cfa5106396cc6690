// Geometry of bodies and regions (constructive solid geometry): primitives
// box, sphere, cylinder (3-D), circle/annulus and polygon (2-D), extrusion of
// a 2-D shape along z, closed triangle meshes from STL files, transforms,
// union and difference. Coordinates are 3-component; 2-D scenes ignore z.
// Boundaries are inclusive (up to `tol`).
#pragma once
#include <array>
#include <memory>
#include <string>
#include <vector>

namespace mfsd {

using Point3 = std::array<double, 3>;

struct Bounds {
  Point3 min{0, 0, 0};
  Point3 max{0, 0, 0};
};

class TriangleMesh;

// Rotation matrix (row-major) about an axis (any length > 0) by an angle [rad].
std::array<double, 9> rotation_matrix(Point3 axis, double angle);

struct Shape {
  enum class Kind { box, sphere, cylinder, circle, polygon, extrude, mesh, transform, union_of, difference };
  Kind kind = Kind::box;
  Point3 min{0, 0, 0};                          // box
  Point3 max{0, 0, 0};                          // box
  Point3 center{0, 0, 0};                       // sphere, circle; cylinder: centre of the base
  Point3 axis{0, 0, 1};                         // cylinder: from the base centre to the top centre
  double radius = 0, inner_radius = 0;          // sphere, circle, cylinder (inner > 0: shell, annulus, tube)
  std::vector<std::array<double, 2>> vertices;  // polygon
  double z_min = 0, z_max = 0;                  // extrude
  std::array<double, 9> rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};  // transform: x = R (scale x_child) + translation
  Point3 translation{0, 0, 0};
  double scale = 1;
  std::shared_ptr<const TriangleMesh> triangles;  // mesh
  std::string source;                             // mesh: file name (messages)
  std::vector<Shape> children;  // union_of: any; difference: first minus the others; extrude, transform: one

  static Shape box(const Point3& lo, const Point3& hi) {
    Shape s;
    s.kind = Kind::box;
    s.min = lo;
    s.max = hi;
    return s;
  }

  // Inside test; `dim` = 2 ignores z. `tol` widens the shape (absolute length).
  bool contains(const Point3& p, int dim, double tol = 0.0) const;
  // Axis-aligned bounding box (of the union; a difference keeps its first part's box).
  Bounds bounds(int dim) const;
  std::string describe() const;
};

}  // namespace mfsd
