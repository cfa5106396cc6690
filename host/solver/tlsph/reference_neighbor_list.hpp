// Total-Lagrangian reference neighbour list: one cell-list search in the
// reference configuration (host/neighbors/cell_list_search.hpp), with the
// sort-based reordering of every particle field, then a CSR list (count,
// scan, fill) with the per-pair reference data of reference_pair_fill.hpp
// (design.md, "Neighbour search"). Built once per run.
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "host/neighbors/cell_list_search.hpp"
#include "host/particles/field_names.hpp"
#include "host/particles/particle_set.hpp"
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
  const auto host_x = to_host<B>(particles.template buffer<Vec<D, double>>(field::reference_position_double));
  std::vector<double> lo(bodies.size() * D), hi(bodies.size() * D);
  for (size_t k = 0; k < bodies.size(); ++k) {
    const BodyRange r = bodies[k].range;
    for (int a = 0; a < D; ++a) {
      double& l = lo[k * D + size_t(a)];
      double& h = hi[k * D + size_t(a)];
      l = h = r.size() ? host_x[size_t(r.begin)].v[a] : 0.0;
      for (Index i = r.begin; i < r.end; ++i)
        l = std::min(l, host_x[size_t(i)].v[a]), h = std::max(h, host_x[size_t(i)].v[a]);
    }
  }
  CellIndex<B, D> index;
  sort_into_cells<B, D, double>(particles, field::reference_position_double, body_cell_grids<D>(bodies, lo, hi),
                                reorder, index);
  CellNeighborhood<D> hood = cell_neighborhood<B, D, double>(particles, field::reference_position_double, index);
  DeviceVector<B, Notch<D>> notch_buffer;
  if (!notches.empty()) {
    from_host<B>(notches, notch_buffer);
    hood.notches = NotchSet<D>{raw(notch_buffer), int(notches.size())};
  }
  ReferenceNeighborList<B, D, Real> list;
  list.cells = index.cells;
  DeviceVector<B, Index> count;
  const PairIndex total = count_pairs<B, D, double>(hood, bodies, n, count, list.offsets);
  list.neighbor.resize(size_t(total) + kPairPrefetchDistance, 0);  // padded for the prefetch
  list.grad.resize(size_t(total));
  list.stretch.resize(size_t(total));
  list.gradient_sum.resize(size_t(n));
  if (with_beta) list.beta.resize(size_t(total));
  for (const auto& b : bodies) {
    hood.radius2 = support_radius2<double>(b.smoothing_length);
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
