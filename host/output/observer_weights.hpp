// The weights of an observer point (issue 28; SPHinXsys's observers): the
// particles j within the radius r of the point x, with W the Wendland C2
// kernel of support r (seed 000 eq. 10's kernel; its constant cancels):
//   Shepard:  w_j = W_j V_j / sum_k W_k V_k   (constants exact)
//   linear:   w_j = W_j V_j (a + b . (x_j - x)), a and b such that
//             sum_j w_j = 1 and sum_j w_j (x_j - x) = 0  (linear fields exact;
//             the reproducing-kernel correction of rkpm.md 1.3 at order 1),
//             Shepard where the moment matrix is singular (a point seen by
//             fewer than d + 1 particles, or by a line of them).
// A point with no particle within r gets no weights (NaN values).
#pragma once
#include <cstddef>
#include <vector>

namespace mfsd {

struct ObserverWeight {
  size_t particle;
  double weight;
};

// x: n positions of `dim` coordinates (x[dim * j + a]); volume: n; use:
// n flags (null: every particle). One list per point.
std::vector<std::vector<ObserverWeight>> observer_weights(const std::vector<std::vector<double>>& points,
                                                          const std::vector<double>& x,
                                                          const std::vector<double>& volume,
                                                          const std::vector<unsigned char>* use, int dim, double radius,
                                                          bool linear);

// sum_j w_j f_j for a field of `components` values per particle.
std::vector<double> observe(const std::vector<ObserverWeight>& weights, const std::vector<double>& field,
                            int components);

}  // namespace mfsd
