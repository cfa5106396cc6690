// Total-Lagrangian reference neighbour list: one cell-list search in the
// reference configuration (host/neighbors/cell_list_search.hpp), with the
// sort-based reordering of every particle field, then a CSR list (count,
// scan, fill) with the per-pair reference data of reference_pair_fill.hpp
// (design.md, "Neighbour search"). Built once per run.
#pragma once
#include <algorithm>
#include <cmath>
#include <type_traits>
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
  // The half-pair loop's list (CPU backend; build_half_pair_list): for each
  // row i its pairs with j > i, with their data, stored apart so that the
  // loop streams them (read in place, every row's lower half skipped, the
  // force stage ran 1.6x slower than the full gather: docs/performance.md);
  // bandwidth = the largest j - i. Empty, bandwidth -1, unless built.
  DeviceVector<B, PairIndex> half_offsets;
  DeviceVector<B, Index> half_neighbor;
  DeviceVector<B, Vec<D, Real>> half_grad;
  DeviceVector<B, Real> half_stretch, half_beta;
  Index bandwidth = -1;

  PairIndex pairs() const { return PairIndex(grad.size()); }

  ReferencePairs<D, Real> half_view() const {
    return ReferencePairs<D, Real>{raw(half_offsets), raw(half_neighbor), raw(half_grad),
                                   raw(half_stretch), raw(gradient_sum),  half_beta.empty() ? nullptr : raw(half_beta)};
  }

  double half_bytes() const {
    return double(half_grad.size()) * (sizeof(Index) + sizeof(Vec<D, Real>) + sizeof(Real)) +
           double(half_beta.size()) * sizeof(Real) + double(half_offsets.size()) * sizeof(PairIndex);
  }

  ReferencePairs<D, Real> view() const {
    return ReferencePairs<D, Real>{raw(offsets), raw(neighbor),     raw(grad),
                                   raw(stretch), raw(gradient_sum), beta.empty() ? nullptr : raw(beta)};
  }
};

// The half-pair list of `list` (see ReferenceNeighborList), on the host, once.
// False, and nothing built, where a row is not sorted by j (a search without
// reordering): the pair loops then take the full gather.
template <class B, int D, class Real>
bool build_half_pair_list(ReferenceNeighborList<B, D, Real>& list, Index n) {
  const auto offsets = to_host<B>(list.offsets);
  const auto neighbor = to_host<B>(list.neighbor);
  for (Index i = 0; i < n; ++i)
    for (PairIndex p = offsets[size_t(i)] + 1; p < offsets[size_t(i) + 1]; ++p)
      if (neighbor[size_t(p)] <= neighbor[size_t(p) - 1]) return false;
  const auto grad = to_host<B>(list.grad);
  const auto stretch = to_host<B>(list.stretch);
  const auto beta = to_host<B>(list.beta);
  std::vector<PairIndex> half_offsets(static_cast<size_t>(n) + 1, 0);
  std::vector<Index> half_neighbor;
  std::vector<Vec<D, Real>> half_grad;
  std::vector<Real> half_stretch, half_beta;
  const size_t expected = size_t(offsets.back() / 2 + 1);
  half_neighbor.reserve(expected + kPairPrefetchDistance);
  half_grad.reserve(expected);
  half_stretch.reserve(expected);
  Index bandwidth = 0;
  for (Index i = 0; i < n; ++i) {
    for (PairIndex p = offsets[size_t(i)]; p < offsets[size_t(i) + 1]; ++p) {
      const Index j = neighbor[size_t(p)];
      if (j <= i) continue;
      bandwidth = std::max(bandwidth, j - i);
      half_neighbor.push_back(j);
      half_grad.push_back(grad[size_t(p)]);
      half_stretch.push_back(stretch[size_t(p)]);
      if (!beta.empty()) half_beta.push_back(beta[size_t(p)]);
    }
    half_offsets[size_t(i) + 1] = PairIndex(half_grad.size());
  }
  half_neighbor.resize(half_neighbor.size() + kPairPrefetchDistance, 0);  // padded for the prefetch
  from_host<B>(half_offsets, list.half_offsets);
  from_host<B>(half_neighbor, list.half_neighbor);
  from_host<B>(half_grad, list.half_grad);
  from_host<B>(half_stretch, list.half_stretch);
  from_host<B>(half_beta, list.half_beta);
  list.bandwidth = bandwidth;
  return true;
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
