// The RKPM neighbour list and its per-step bookkeeping (rkpm.md 2):
// - one symmetric CSR list from the cell-list search, each row holding its
//   own node first (a node's kernel covers its own evaluation points), so
//   that every loop is a gather over one row;
// - the step's reduction per body: the health check, the stable time step
//   dt_L = h0 J^(1/d) / c_L, c_L = sqrt((lambda + 2 mu) J / rho0) (rkpm.md 5.3),
//   and what decides a rebuild: the largest drift since the build and the
//   largest support a and cell reach r (2 drift + growth > skin).
#pragma once
#include "kernels/core/mat.hpp"
#include "kernels/neighbors/bounding_box.hpp"
#include "kernels/neighbors/cell_list.hpp"

namespace mfsd::rkpm {

// offsets[i] += i (the search's offsets without the node itself); i in [0, n].
struct SelfOffsetsFunctor {
  PairIndex* offsets;
  MFSD_HD void operator()(Index i) const { offsets[i] += PairIndex(i); }
};

template <int D, class Real>
struct RowFillFunctor {
  CellNeighborhood<D, Real> hood;
  const PairIndex* offsets;
  Index* neighbor;
  struct Writer {
    Index* neighbor;
    PairIndex p;
    MFSD_HD void operator()(Index j, const Vec<D, Real>&, Real) { neighbor[p++] = j; }
  };
  MFSD_HD void operator()(Index i) const {
    Writer w{neighbor, offsets[i] + 1};
    neighbor[offsets[i]] = i;
    hood.for_each(i, w);
  }
};

template <int D, class Real>
struct StepStats {
  Real max_speed2;
  Real max_drift2;  // |x + dt v - x_build|^2: the next step's position against the list's
  Real max_support;
  Real max_cell_reach;       // reach - a: max_f |xbar_f - x_L| (+ a (sqrt d - 1) with box supports)
  Real min_dt;               // CFL-free stable step h/c
  Index first_bad;           // smallest index of a non-finite or escaped node, or n
  BoundingBox<D, Real> box;  // the body's box (the next search's grid, without a round trip)
};

template <int D, class Real>
struct StepStatsCombine {
  MFSD_HD StepStats<D, Real> operator()(const StepStats<D, Real>& a, const StepStats<D, Real>& b) const {
    StepStats<D, Real> r{math::max(a.max_speed2, b.max_speed2),
                         math::max(a.max_drift2, b.max_drift2),
                         math::max(a.max_support, b.max_support),
                         math::max(a.max_cell_reach, b.max_cell_reach),
                         math::min(a.min_dt, b.min_dt),
                         math::min(a.first_bad, b.first_bad),
                         BoundingBoxCombine<D, Real>{}(a.box, b.box)};
    return r;
  }
};

template <int D, class Real>
struct StepStatsFunctor {
  const Vec<D, Real>* reference_position;
  const Vec<D, Real>* displacement;
  const Vec<D, Real>* velocity;
  const Vec<D, Real>* build_position;  // x at the list's build
  const Mat<D, Real>* cell_map;
  const Real* support;
  const Real* reach;    // a + r
  const Real* nearest;  // distance to the nearest node; null: h0 J^(1/d) alone
  double h0;            // the body's spacing
  double slowness;      // sqrt(rho0 / (lambda + 2 mu))
  double dt;
  Vec<D, Real> lower, upper;  // scene bounds
  Index n;
  const unsigned char* ghost = nullptr;  // distributed runs: ghosts count for nothing (their owners do)

  MFSD_HD StepStats<D, Real> operator()(Index i) const {
    if (ghost && ghost[i])
      return StepStats<D, Real>{Real(0), Real(0), Real(0), Real(0), Real(INFINITY), n, BoundingBox<D, Real>::empty()};
    const Vec<D, Real> v = velocity[i];
    const Vec<D, Real> x = reference_position[i] + displacement[i];
    const double J = double(det(cell_map[i]));
    const Real v2 = squared_norm(v);
    bool ok = math::isfinite(v2) && J > 0.0;
    for (int k = 0; k < D; ++k) ok = ok && x.v[k] >= lower.v[k] && x.v[k] <= upper.v[k];  // false for NaN
    if (!ok)
      return StepStats<D, Real>{
          Real(0), Real(0), Real(0), Real(0), Real(INFINITY), i, BoundingBox<D, Real>{lower, upper}};
    // rkpm.md 5.3: h_L = h0 J^(1/d), c_L = sqrt((lambda + 2 mu)/rho_L), rho_L = rho0/J;
    // with solver.rkpm.time_step "nearest", h_L no more than the distance to
    // the nearest node: a node cloud flattened by plastic flow (J ~ 1) has
    // its spacing, not h0, along the compressed direction (docs/theory.md).
    double h = h0 * math::pow(J, 1.0 / D);
    if (nearest) h = math::min(h, double(nearest[i]));
    const double step = h * slowness / math::sqrt(J);
    const Real a = support[i];
    return StepStats<D, Real>{v2, squared_norm(x + v * Real(dt) - build_position[i]), a, reach[i] - a, Real(step), n, x,
                              x};
  }
};

}  // namespace mfsd::rkpm
