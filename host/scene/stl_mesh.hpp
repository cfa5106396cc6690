// Triangle meshes from STL files (ASCII or binary) for body geometry: the
// mesh must be closed (every edge shared by exactly two triangles), and the
// inside test casts a ray along +z with a consistent tie-break on shared
// edges and vertices (each lattice point is counted by exactly one of the
// triangles around an edge it projects onto), so meshes whose vertices sit
// on the particle lattice fill exactly.
#pragma once
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "host/scene/shape.hpp"

namespace mfsd {

class TriangleMesh {
 public:
  // Reads `path` (ASCII when it starts with "solid" and is not a valid binary
  // file, else binary), scales coordinates by `scale`; throws
  // std::runtime_error naming the file and the problem (unreadable, empty,
  // malformed, or not closed).
  static std::shared_ptr<const TriangleMesh> load(const std::string& path, double scale = 1.0);
  // From triangles (for tests and generated meshes); checks closure.
  static std::shared_ptr<const TriangleMesh> from_triangles(std::vector<std::array<Point3, 3>> triangles,
                                                            const std::string& name);

  bool contains(const Point3& p) const;  // boundary points count as inside
  const Bounds& bounds() const { return bounds_; }
  size_t size() const { return triangles_.size(); }

 private:
  void build();
  std::string name_;
  std::vector<std::array<Point3, 3>> triangles_;
  Bounds bounds_;
  // Buckets of the triangles' xy bounding boxes on an n x n grid.
  int grid_ = 1;
  double cell_[2] = {1, 1};
  std::vector<std::vector<unsigned>> buckets_;
};

}  // namespace mfsd
