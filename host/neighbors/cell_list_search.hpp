// Cell-list neighbour search with sort-based reordering and a CSR builder
// whose pair data a method plugs in (design.md, "Neighbour search"); used by
// the TLSPH reference list (once, in double, host/solver/tlsph/) and by the
// ULSPH current-configuration list (every advection step, in Real):
//   sort_into_cells   key = body's first key + cell, sort, optionally
//                     permute every particle field (the re-index hook tells
//                     the owners of stored indices), then each key's range
//   count_pairs       neighbours per particle within its body's radius,
//                     scanned into CSR offsets; returns the number of pairs
// after which the method runs its own fill functor over each body's range
// with the neighbourhood (kernels/tlsph/reference_pair_fill.hpp, ...).
// Only particles of the same body are neighbours; bodies meet by contact.
#pragma once
#include <thrust/fill.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "host/backend/algorithms.hpp"
#include "host/particles/field_names.hpp"
#include "host/particles/particle_set.hpp"
#include "kernels/neighbors/cell_list.hpp"

namespace mfsd {

struct BodySearch {
  BodyRange range;
  double smoothing_length;  // support radius = 2 h
  // The cell grid's box (lo[0..2], hi[0..2]) where `fixed_box`, else the box
  // of the range's particles. A distributed run gives each rank the whole
  // body's box: the same cells, hence the same order of every row's
  // neighbours as the single-process run (docs/distributed.md).
  std::array<double, 6> box{};
  bool fixed_box = false;
};

// The squared search radius (2h)^2 in the positions' precision: the count
// and every fill of a list must use this same value, or a borderline pair
// is counted and not filled (or the reverse).
template <class P>
P support_radius2(double smoothing_length) {
  return P(std::pow(2.0 * smoothing_length, 2));
}

// The grid over [lo, hi] with cells of edge `cell_size`, its keys from `first_key`.
template <int D, class P = double>
CellGrid<D, P> make_cell_grid(const double* lo, const double* hi, double cell_size, std::int64_t first_key = 0) {
  CellGrid<D, P> g;
  g.inv_cell_size = P(1.0 / cell_size);
  std::int64_t cells = 1;
  for (int a = 0; a < D; ++a) {
    const double origin = lo[a] - 1e-9 * cell_size;
    g.origin[a] = P(origin);
    g.dims[a] = std::max(1, int(std::floor((hi[a] - origin) / cell_size)) + 1);
    cells *= g.dims[a];
  }
  g.cells = cells;
  g.first_key = first_key;
  return g;
}

// One grid per body over the box [lo_b, hi_b] (per body, D values each), cell
// edge = its support radius: memory follows the bodies' volumes, not the
// space between them.
template <int D, class P = double>
std::vector<CellGrid<D, P>> body_cell_grids(const std::vector<BodySearch>& bodies, const std::vector<double>& lo,
                                            const std::vector<double>& hi) {
  std::vector<CellGrid<D, P>> grids;
  std::int64_t first = 0;
  for (size_t b = 0; b < bodies.size(); ++b) {
    grids.push_back(make_cell_grid<D, P>(&lo[b * D], &hi[b * D], 2.0 * bodies[b].smoothing_length, first));
    first += grids.back().cells;
  }
  return grids;
}

// The state of one search, kept between rebuilds so that buffers are reused.
template <class B, int D, class P = double>
struct CellIndex {
  DeviceVector<B, CellGrid<D, P>> grids;
  DeviceVector<B, std::int64_t> keys;
  DeviceVector<B, Index> order;  // sorted position -> particle index (identity after a reorder)
  DeviceVector<B, Index> start, end;
  std::int64_t cells = 0;
  bool reordered = false;
};

// Does nothing with the permutation (a caller with no stored indices).
struct NoReindex {
  template <class Order>
  void operator()(const Order&) const {}
};

// Sorts the particles by (body, cell) of the field `position` (Vec<D, P>).
// With `reorder`, every field of the set is permuted into that order and
// reindex(order) is called first (order[new] = old), so that whoever stores
// particle indices can map them; the order then becomes the identity.
template <class B, int D, class P, class Reindex = NoReindex>
void sort_into_cells(ParticleSet<B>& particles, const char* position, const std::vector<CellGrid<D, P>>& host_grids,
                     bool reorder, CellIndex<B, D, P>& index, Reindex&& reindex = {}) {
  const Index n = particles.size();
  std::int64_t cells = 0;
  for (const auto& g : host_grids) cells = std::max(cells, g.first_key + g.cells);
  from_host<B>(host_grids, index.grids);
  index.keys.resize(size_t(n));
  index.order.resize(size_t(n));
  sequence<B, Index>(index.order);
  parallel_for<B>(n, CellKeyFunctor<D, P>{raw(index.grids), particles.template get<Vec<D, P>>(position),
                                          particles.template get<int>(field::body), raw(index.keys)});
  // Stable: particles of one cell keep their order (a distributed run's
  // subset of a body then sorts as in the single-process run).
  stable_sort_by_key<B, std::int64_t, Index>(index.keys, index.order);
  index.reordered = reorder;
  if (reorder) {
    reindex(index.order);
    particles.permute(index.order);
    sequence<B, Index>(index.order);
  }
  if (index.cells != cells || index.start.size() != size_t(cells)) {
    index.start.assign(size_t(cells), 0);
    index.end.assign(size_t(cells), 0);
  } else {
    thrust::fill(BackendTraits<B>::policy(), index.start.begin(), index.start.end(), Index(0));
    thrust::fill(BackendTraits<B>::policy(), index.end.begin(), index.end.end(), Index(0));
  }
  index.cells = cells;
  parallel_for<B>(n, CellRangeFunctor{raw(index.keys), n, raw(index.start), raw(index.end)});
}

// The neighbourhood of a sorted index over the field `position`, radius unset.
template <class B, int D, class P>
CellNeighborhood<D, P> cell_neighborhood(ParticleSet<B>& particles, const char* position,
                                         const CellIndex<B, D, P>& index) {
  return CellNeighborhood<D, P>{raw(index.grids),
                                particles.template get<Vec<D, P>>(position),
                                particles.template get<int>(field::body),
                                raw(index.start),
                                raw(index.end),
                                index.reordered ? nullptr : raw(index.order),
                                P(0),
                                NotchSet<D>{}};
}

// CSR offsets (n + 1) of the pairs within each body's support radius;
// returns their number. `count` is scratch of n entries. Where `upper_offsets`
// is given, also the offsets of each row's pairs with j > i (a half-pair list)
// and their number in *upper_total.
template <class B, int D, class P>
PairIndex count_pairs(CellNeighborhood<D, P> hood, const std::vector<BodySearch>& bodies, Index n,
                      DeviceVector<B, Index>& count, DeviceVector<B, PairIndex>& offsets,
                      DeviceVector<B, PairIndex>* upper_offsets = nullptr, PairIndex* upper_total = nullptr) {
  count.assign(size_t(n), 0);
  DeviceVector<B, Index> upper;
  if (upper_offsets) upper.assign(size_t(n), 0);
  for (const auto& b : bodies) {
    hood.radius2 = support_radius2<P>(b.smoothing_length);
    parallel_for<B>(b.range.begin, b.range.end,
                    NeighborCountFunctor<D, P>{hood, raw(count), upper_offsets ? raw(upper) : nullptr});
  }
  offsets.resize(size_t(n) + 1);
  const PairIndex total = exclusive_scan<B, Index, PairIndex>(count, offsets);
  offsets[size_t(n)] = total;
  if (upper_offsets) {
    upper_offsets->resize(size_t(n) + 1);
    *upper_total = exclusive_scan<B, Index, PairIndex>(upper, *upper_offsets);
    (*upper_offsets)[size_t(n)] = *upper_total;
  }
  return total;
}

}  // namespace mfsd
