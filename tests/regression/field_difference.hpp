// How far apart two runs' fields are: max |a - b| over max |a| (the
// difference itself for a field that is zero in a).
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

inline double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double diff = 0, scale = 0;
  for (size_t k = 0; k < a.size(); ++k) {
    diff = std::max(diff, std::abs(a[k] - b[k]));
    scale = std::max(scale, std::abs(a[k]));
  }
  return scale > 0 ? diff / scale : diff;
}
