// Cell-list neighbour search (design.md, "Neighbour search"): one grid per
// body over its own bounding box, cell edge = its search radius; particles
// sorted by key = the body's first key + the cell's index; each key's
// [start, end) found from the sorted keys; neighbours counted, scanned into
// CSR offsets and filled. Only particles of the same body are neighbours
// (bodies interact by contact, not through the reference list), so bodies far
// apart cost no cells between them.
#pragma once
#include <type_traits>

#include "kernels/core/vec.hpp"
#include "kernels/fracture/notch.hpp"

namespace mfsd {

// P: the precision of the positions searched (double for the reference
// search at set-up, Real for the current-configuration search of a step, so
// that a float run does no double arithmetic per step).
template <int D, class P = double>
struct CellGrid {
  P origin[D];
  P inv_cell_size;
  int dims[D];
  std::int64_t cells;      // dims[0] x ... x dims[D-1]
  std::int64_t first_key;  // keys of this grid: [first_key, first_key + cells)

  MFSD_HD int coordinate(int axis, P x) const {
    int c = int(math::floor((x - origin[axis]) * inv_cell_size));
    return c < 0 ? 0 : (c >= dims[axis] ? dims[axis] - 1 : c);
  }
  MFSD_HD std::int64_t linear(const int* c) const {
    std::int64_t k = c[D - 1];
    for (int a = D - 2; a >= 0; --a) k = k * dims[a] + c[a];
    return k;
  }
};

// key_i = first key of body_i's grid + cell(X_i)
template <int D, class P = double>
struct CellKeyFunctor {
  const CellGrid<D, P>* grids;  // per body
  const Vec<D, P>* position;
  const int* body;
  std::int64_t* key;

  MFSD_HD void operator()(Index i) const {
    const CellGrid<D, P>& grid = grids[body[i]];
    int c[D];
    for (int a = 0; a < D; ++a) c[a] = grid.coordinate(a, position[i].v[a]);
    key[i] = grid.first_key + grid.linear(c);
  }
};

// From sorted keys, the [start, end) of every occupied key (others stay 0, 0).
struct CellRangeFunctor {
  const std::int64_t* key;
  Index n;
  Index* start;
  Index* end;

  MFSD_HD void operator()(Index i) const {
    const std::int64_t k = key[i];
    if (i == 0 || key[i - 1] != k) start[k] = i;
    if (i == n - 1 || key[i + 1] != k) end[k] = i + 1;
  }
};

// Visits every j != i of the same body with |X_i - X_j| < radius whose pair
// no notch cuts (kernels/fracture/notch.hpp); the visitor receives
// (j, X_i - X_j, |X_i - X_j|) in the positions' precision P.
template <int D, class P = double>
struct CellNeighborhood {
  const CellGrid<D, P>* grids;  // per body
  const Vec<D, P>* position;
  const int* body;
  const Index* start;
  const Index* end;
  const Index* order;  // cell-sorted position -> particle index; null = identity (reordered set)
  P radius2;
  NotchSet<D> notches;  // pair mask; empty without notches (reference search only)

  template <class Visitor>
  MFSD_HD void for_each(Index i, Visitor& visit) const {
    const Vec<D, P> xi = position[i];
    const CellGrid<D, P>& grid = grids[body[i]];
    int c[D], lo[D], hi[D];
    for (int a = 0; a < D; ++a) {
      c[a] = grid.coordinate(a, xi.v[a]);
      lo[a] = c[a] > 0 ? c[a] - 1 : 0;
      hi[a] = c[a] + 1 < grid.dims[a] ? c[a] + 1 : grid.dims[a] - 1;
    }
    const std::int64_t base = grid.first_key;
    int cc[D];
    if constexpr (D == 2) {
      for (cc[1] = lo[1]; cc[1] <= hi[1]; ++cc[1])
        for (cc[0] = lo[0]; cc[0] <= hi[0]; ++cc[0]) visit_cell(i, xi, base + grid.linear(cc), visit);
    } else {
      for (cc[2] = lo[2]; cc[2] <= hi[2]; ++cc[2])
        for (cc[1] = lo[1]; cc[1] <= hi[1]; ++cc[1])
          for (cc[0] = lo[0]; cc[0] <= hi[0]; ++cc[0]) visit_cell(i, xi, base + grid.linear(cc), visit);
    }
  }

 private:
  // Notches cut pairs of the reference search (double positions) only.
  MFSD_HD bool cut(Index i, const Vec<D, P>& xi, const Vec<D, P>& xj) const {
    if constexpr (std::is_same<P, double>::value)
      return notches.count && notches.cuts(body[i], xi, xj);
    else
      return false;
  }

  template <class Visitor>
  MFSD_HD void visit_cell(Index i, const Vec<D, P>& xi, std::int64_t k, Visitor& visit) const {
    for (Index s = start[k]; s < end[k]; ++s) {
      const Index j = order ? order[s] : s;
      if (j == i) continue;
      const Vec<D, P> d = xi - position[j];
      const P r2 = squared_norm(d);
      if (r2 < radius2 && !cut(i, xi, position[j])) visit(j, d, math::sqrt(r2));
    }
  }
};

struct CountVisitor {
  Index count = 0;
  Index self = 0, upper = 0;  // upper: the neighbours j > self (a half-pair list's row)
  template <class V, class P>
  MFSD_HD void operator()(Index j, const V&, P) {
    ++count;
    if (j > self) ++upper;
  }
};

template <int D, class P = double>
struct NeighborCountFunctor {
  CellNeighborhood<D, P> hood;
  Index* count;
  Index* upper = nullptr;  // where set, also the count of neighbours j > i
  MFSD_HD void operator()(Index i) const {
    CountVisitor v;
    v.self = i;
    hood.for_each(i, v);
    count[i] = v.count;
    if (upper) upper[i] = v.upper;
  }
};

}  // namespace mfsd
