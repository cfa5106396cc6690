// Kinematic rigid bodies (seed 001's "auxiliary geometry", Fig. 3): a shape
// moved by a prescribed translation d(t) and rotation by angle(t) about an
// axis through a centre, x(t) = c + R(angle(t)) (X - c) + d(t), with
// expressions of t. They select loaded particles now ("near" selections) and
// will be contact partners; marker points on their surface are written to
// rigid_bodies.pvd next to the particle snapshots.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "host/expr/program.hpp"
#include "host/scene/scene.hpp"

namespace mfsd {

// The motion of one rigid body, compiled once.
class RigidBodyMotion {
 public:
  RigidBodyMotion(const RigidBodySpec& spec, const std::vector<std::pair<std::string, double>>& constants,
                  const std::string& path);
  // Position at time t of the material point X (reference: the shape as given).
  Point3 position(const Point3& X, double t) const;
  // Reference point of a current position (the inverse map at time t).
  Point3 reference(const Point3& x, double t) const;

 private:
  std::array<double, 9> rotation(double t) const;
  Point3 translation(double t) const;
  RigidBodySpec spec_;
  std::array<expr::Program, 3> translation_;
  expr::Program angle_;
};

// Marker points on the surface of a rigid body's shape, on a lattice of the
// given spacing (the outer layer of the lattice points inside the shape).
std::vector<Point3> rigid_body_markers(const Shape& shape, int dim, double spacing);

}  // namespace mfsd
