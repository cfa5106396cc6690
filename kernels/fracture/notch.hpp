// Pre-existing cracks (seed 001 section 3.3.1, Fig. 4-5: "notch"): a segment
// in 2-D, a planar quadrilateral in 3-D. A reference pair whose connecting
// segment X_i X_j crosses a notch of its body is left out of the reference
// neighbour list, so that the two sides of the notch never interact
// (neither in the forces, dF/dt and B0, nor in the phase-field Laplacian).
// A point exactly on the notch's line/plane counts as on its positive side,
// so a pair is cut at most once and particles on the notch keep one side.
#pragma once
#include "kernels/core/vec.hpp"

namespace mfsd {

template <int D>
struct Notch {
  Vec<D, double> p[4];  // 2-D: the ends p[0], p[1]; 3-D: the corners in order
  int body;
};

namespace detail {
// Orders a pair's ends, so that i-j and j-i take the same rounding and are cut
// alike (a pair through a notch's end would otherwise be cut from one side
// only, and the forces would no longer conserve momentum).
template <int D>
MFSD_HD inline void order_pair(Vec<D, double>& a, Vec<D, double>& b) {
  for (int k = 0; k < D; ++k) {
    if (a.v[k] < b.v[k]) return;
    if (a.v[k] > b.v[k]) {
      const Vec<D, double> t = a;
      a = b;
      b = t;
      return;
    }
  }
}
MFSD_HD inline double cross2(const Vec<2, double>& a, const Vec<2, double>& b) {
  return a.v[0] * b.v[1] - a.v[1] * b.v[0];
}
}  // namespace detail

// Does the segment a-b cross the notch?
MFSD_HD inline bool notch_cuts(const Notch<2>& n, Vec<2, double> a, Vec<2, double> b) {
  detail::order_pair(a, b);
  const Vec<2, double> t = n.p[1] - n.p[0];
  const double sa = detail::cross2(t, a - n.p[0]), sb = detail::cross2(t, b - n.p[0]);
  if ((sa >= 0) == (sb >= 0)) return false;  // both on one side of the notch's line
  const Vec<2, double> e = b - a;            // the notch's ends on either side of the pair's line
  const double oc = detail::cross2(e, n.p[0] - a), od = detail::cross2(e, n.p[1] - a);
  return oc * od <= 0;
}

MFSD_HD inline bool notch_cuts(const Notch<3>& n, Vec<3, double> a, Vec<3, double> b) {
  detail::order_pair(a, b);
  const Vec<3, double> normal = cross(n.p[2] - n.p[0], n.p[3] - n.p[1]);  // from the diagonals
  const double sa = dot(normal, a - n.p[0]), sb = dot(normal, b - n.p[0]);
  if ((sa >= 0) == (sb >= 0)) return false;
  const Vec<3, double> x = a + (b - a) * (sa / (sa - sb));  // where the pair meets the plane
  bool pos = true, neg = true;  // x on the same side of every edge: inside the (convex) quad
  for (int k = 0; k < 4; ++k) {
    const double o = dot(cross(n.p[(k + 1) % 4] - n.p[k], x - n.p[k]), normal);
    pos = pos && o >= 0;
    neg = neg && o <= 0;
  }
  return pos || neg;
}

// The notches of a scene, as a pair mask for the reference search.
template <int D>
struct NotchSet {
  const Notch<D>* notches = nullptr;
  int count = 0;
  MFSD_HD bool cuts(int body, const Vec<D, double>& a, const Vec<D, double>& b) const {
    for (int k = 0; k < count; ++k)
      if (notches[k].body == body && notch_cuts(notches[k], a, b)) return true;
    return false;
  }
};

}  // namespace mfsd
