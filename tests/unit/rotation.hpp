// Test helper: a rotation matrix as Mat<3, double>, from the production
// axis-angle helper of the shapes (host/scene/shape.hpp).
#pragma once
#include "host/scene/shape.hpp"
#include "kernels/core/mat.hpp"

namespace mfsd::test {

inline Mat<3, double> rotation(Point3 axis, double angle) {
  const std::array<double, 9> r = rotation_matrix(axis, angle);
  Mat<3, double> R;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) R.m[a][b] = r[size_t(3 * a + b)];
  return R;
}

}  // namespace mfsd::test
