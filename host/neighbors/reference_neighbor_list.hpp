// Total-Lagrangian reference neighbour list: one cell-list search in the
// reference configuration, with the sort-based reordering of every particle
// field, then a CSR list (count, scan, fill) with the per-pair reference data
// (design.md, "Neighbour search"). Built once per run.
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "host/particles/field_names.hpp"
#include "host/particles/particle_set.hpp"
#include "kernels/neighbors/cell_list.hpp"
#include "kernels/tlsph/reference_pair_fill.hpp"

namespace mfsd {

template <class B, int D, class Real>
struct ReferenceNeighborList {
  DeviceVector<B, PairIndex> offsets;
  DeviceVector<B, Index> neighbor;
  DeviceVector<B, Vec<D, Real>> grad;
  DeviceVector<B, Real> stretch, beta;
  DeviceVector<B, Vec<D, Real>> gradient_sum;  // per particle
  std::int64_t cells = 0;                      // of the search's grids (set-up memory: 2 indices each)

  PairIndex pairs() const { return PairIndex(grad.size()); }

  ReferencePairs<D, Real> view() const {
    return ReferencePairs<D, Real>{raw(offsets), raw(neighbor),     raw(grad),
                                   raw(stretch), raw(gradient_sum), beta.empty() ? nullptr : raw(beta)};
  }
};

struct BodySearch {
  BodyRange range;
  double smoothing_length;  // support radius = 2 h
};

// The grid over [lo, hi] with cells of edge `cell_size`, its keys from `first_key`.
template <int D>
CellGrid<D> make_cell_grid(const double* lo, const double* hi, double cell_size, std::int64_t first_key = 0) {
  CellGrid<D> g;
  g.inv_cell_size = 1.0 / cell_size;
  std::int64_t cells = 1;
  for (int a = 0; a < D; ++a) {
    g.origin[a] = lo[a] - 1e-9 * cell_size;
    g.dims[a] = std::max(1, int(std::floor((hi[a] - g.origin[a]) / cell_size)) + 1);
    cells *= g.dims[a];
  }
  g.cells = cells;
  g.first_key = first_key;
  return g;
}

// Sorts particles by (body, cell) and, when `reorder`, permutes every field of
// the set accordingly; then builds the CSR list. Reads the set-up field
// reference_position_double, the body ids and the volumes. Pairs that a notch
// cuts are left out (kernels/fracture/notch.hpp), before B0 and the gradient
// sums are formed from the list.
template <class B, int D, class Real>
ReferenceNeighborList<B, D, Real> build_reference_neighbor_list(ParticleSet<B>& particles,
                                                                const std::vector<BodySearch>& bodies, bool reorder,
                                                                bool with_beta,
                                                                const std::vector<Notch<D>>& notches = {}) {
  const Index n = particles.size();
  // One grid per body over its own bounding box, cell edge = its support
  // radius: memory follows the bodies' volumes, not the space between them.
  const auto host_x = to_host<B>(particles.template buffer<Vec<D, double>>(field::reference_position_double));
  std::vector<CellGrid<D>> host_grids;
  std::int64_t cells = 0;
  for (const auto& b : bodies) {
    double lo[D], hi[D];
    for (int a = 0; a < D; ++a) {
      lo[a] = hi[a] = b.range.size() ? host_x[size_t(b.range.begin)].v[a] : 0.0;
      for (Index i = b.range.begin; i < b.range.end; ++i)
        lo[a] = std::min(lo[a], host_x[size_t(i)].v[a]), hi[a] = std::max(hi[a], host_x[size_t(i)].v[a]);
    }
    host_grids.push_back(make_cell_grid<D>(lo, hi, 2.0 * b.smoothing_length, cells));
    cells += host_grids.back().cells;
  }
  DeviceVector<B, CellGrid<D>> grids;
  from_host<B>(host_grids, grids);

  DeviceVector<B, std::int64_t> keys(static_cast<size_t>(n));
  DeviceVector<B, Index> order(static_cast<size_t>(n));
  sequence<B, Index>(order);
  parallel_for<B>(
      n, CellKeyFunctor<D>{raw(grids), particles.template get<Vec<D, double>>(field::reference_position_double),
                           particles.template get<int>(field::body), raw(keys)});
  sort_by_key<B, std::int64_t, Index>(keys, order);
  if (reorder) {
    particles.permute(order);
    sequence<B, Index>(order);
  }
  DeviceVector<B, Index> start(size_t(cells), 0);
  DeviceVector<B, Index> end(size_t(cells), 0);
  parallel_for<B>(n, CellRangeFunctor{raw(keys), n, raw(start), raw(end)});

  CellNeighborhood<D> hood{raw(grids),
                           particles.template get<Vec<D, double>>(field::reference_position_double),
                           particles.template get<int>(field::body),
                           raw(start),
                           raw(end),
                           reorder ? nullptr : raw(order),
                           0.0,
                           NotchSet<D>{}};
  DeviceVector<B, Notch<D>> notch_buffer;
  if (!notches.empty()) {
    from_host<B>(notches, notch_buffer);
    hood.notches = NotchSet<D>{raw(notch_buffer), int(notches.size())};
  }
  DeviceVector<B, Index> count(size_t(n), 0);
  for (const auto& b : bodies) {
    hood.radius2 = std::pow(2.0 * b.smoothing_length, 2);
    parallel_for<B>(b.range.begin, b.range.end, NeighborCountFunctor<D>{hood, raw(count)});
  }
  ReferenceNeighborList<B, D, Real> list;
  list.cells = cells;
  list.offsets.resize(size_t(n) + 1);
  const PairIndex total = exclusive_scan<B, Index, PairIndex>(count, list.offsets);
  list.offsets[size_t(n)] = total;
  list.neighbor.resize(size_t(total) + kPairPrefetchDistance, 0);  // padded for the prefetch
  list.grad.resize(size_t(total));
  list.stretch.resize(size_t(total));
  list.gradient_sum.resize(size_t(n));
  if (with_beta) list.beta.resize(size_t(total));
  for (const auto& b : bodies) {
    hood.radius2 = std::pow(2.0 * b.smoothing_length, 2);
    ReferencePairFillFunctor<D, Real> fill{hood,
                                           WendlandC2<D, double>::make(b.smoothing_length),
                                           particles.template get<Real>(field::volume),
                                           raw(list.offsets),
                                           raw(list.neighbor),
                                           raw(list.grad),
                                           raw(list.stretch),
                                           raw(list.gradient_sum),
                                           with_beta ? raw(list.beta) : nullptr};
    parallel_for<B>(b.range.begin, b.range.end, fill);
  }
  return list;
}

}  // namespace mfsd
