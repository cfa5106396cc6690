// Total-Lagrangian reference neighbour list: one cell-list search in the
// reference configuration (host/neighbors/cell_list_search.hpp), with the
// sort-based reordering of every particle field, then a CSR list (count,
// scan, fill) with the per-pair reference data of reference_pair_fill.hpp
// (design.md, "Neighbour search"). Built once per run.
#pragma once
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "host/neighbors/cell_list_search.hpp"
#include "host/particles/field_names.hpp"
#include "host/particles/particle_set.hpp"
#include "kernels/neighbors/sliced_pairs.hpp"
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
  // The same half list with float pair data (a double run's --pair-precision
  // float, issue 24 item 4): filled instead of half_grad/half_stretch/half_beta.
  DeviceVector<B, Vec<D, float>> half_grad_f;
  DeviceVector<B, float> half_stretch_f, half_beta_f;
  bool half_float = false;

  ReferencePairs<D, float> half_view_f() const {
    return ReferencePairs<D, float>{raw(half_offsets), raw(half_neighbor),
                                    raw(half_grad_f),  raw(half_stretch_f),
                                    nullptr,           half_beta_f.empty() ? nullptr : raw(half_beta_f)};
  }

  PairIndex total_pairs = 0;  // of the full list (kept when its rows are released)
  bool full_rows = true;      // false after release_full_rows()
  // The sliced layout of the full rows (make_sliced_layout, issue 24 item 3):
  // per row its first pair and count; neighbor, grad, stretch and beta then
  // hold the sliced order, `offsets` still the compressed rows' counts.
  DeviceVector<B, PairIndex> sliced_first;
  DeviceVector<B, Index> sliced_count;
  Index slice_height = 0;  // 0: compressed rows

  PairIndex pairs() const { return total_pairs; }

  // After set-up, where every per-step pass runs the half-pair loop: the full
  // rows' pair data go (offsets and gradient sums stay). Their views are null
  // afterwards, so a pass that still read them would fail at once.
  void release_full_rows() {
    DeviceVector<B, Index>().swap(neighbor);
    DeviceVector<B, Vec<D, Real>>().swap(grad);
    DeviceVector<B, Real>().swap(stretch);
    DeviceVector<B, Real>().swap(beta);
    full_rows = false;
  }

  ReferencePairs<D, Real> half_view() const {
    return ReferencePairs<D, Real>{raw(half_offsets), raw(half_neighbor), raw(half_grad),
                                   raw(half_stretch), raw(gradient_sum),  half_beta.empty() ? nullptr : raw(half_beta)};
  }

  // Of the full rows as stored (compressed or sliced, with the padding), and
  // the per-particle offsets and gradient sums.
  double full_bytes() const {
    return double(grad.size()) * (sizeof(Index) + sizeof(Vec<D, Real>) + sizeof(Real)) +
           double(beta.size()) * sizeof(Real) + double(offsets.size()) * sizeof(PairIndex) +
           double(gradient_sum.size()) * sizeof(Vec<D, Real>) + double(sliced_first.size()) * sizeof(PairIndex) +
           double(sliced_count.size()) * sizeof(Index);
  }

  double half_bytes() const {
    return double(half_grad.size()) * (sizeof(Index) + sizeof(Vec<D, Real>) + sizeof(Real)) +
           double(half_beta.size()) * sizeof(Real) + double(half_offsets.size()) * sizeof(PairIndex) +
           double(half_grad_f.size()) * (sizeof(Index) + sizeof(Vec<D, float>) + sizeof(float)) +
           double(half_beta_f.size()) * sizeof(float);
  }

  ReferencePairs<D, Real> view() const {
    if (!full_rows) return ReferencePairs<D, Real>{raw(offsets), nullptr, nullptr, nullptr, raw(gradient_sum), nullptr};
    ReferencePairs<D, Real> v{raw(offsets), raw(neighbor),     raw(grad),
                              raw(stretch), raw(gradient_sum), beta.empty() ? nullptr : raw(beta)};
    if (slice_height > 0) {
      v.offsets = raw(sliced_first);
      v.count = raw(sliced_count);
      v.stride = slice_height;
    }
    return v;
  }
};

// The largest j - i of the half-pair list's pairs (its bandwidth), CPU.
template <int D, class Real>
Index half_pair_bandwidth(const ReferenceNeighborList<Cpu, D, Real>& list, Index n) {
  const PairIndex* offsets = raw(list.half_offsets);
  const Index* neighbor = raw(list.half_neighbor);
  Index bandwidth = 0;
#pragma omp parallel for schedule(static) reduction(max : bandwidth)
  for (Index i = 0; i < n; ++i)
    for (PairIndex p = offsets[i]; p < offsets[i + 1]; ++p) bandwidth = std::max(bandwidth, neighbor[p] - i);
  return bandwidth;
}

// The half-pair list of `list` (see ReferenceNeighborList), once, CPU backend
// only: read and written in place (no host copies, so the set-up's peak holds
// the two lists and nothing more). False, and nothing built, where a row is
// not sorted by j (a search without reordering): the pair loops then take the
// full gather.
template <int D, class Real>
bool build_half_pair_list(ReferenceNeighborList<Cpu, D, Real>& list, Index n) {
  const PairIndex* offsets = raw(list.offsets);
  const Index* neighbor = raw(list.neighbor);
  bool sorted = true;
  std::vector<PairIndex> first(static_cast<size_t>(n));  // the first pair with j > i, per row
#pragma omp parallel for schedule(static) reduction(&& : sorted)
  for (Index i = 0; i < n; ++i) {
    PairIndex u = offsets[i + 1];
    for (PairIndex p = offsets[i]; p < offsets[i + 1]; ++p) {
      if (p > offsets[i] && neighbor[p] <= neighbor[p - 1]) sorted = false;
      if (neighbor[p] > i && u == offsets[i + 1]) u = p;
    }
    first[size_t(i)] = u;
  }
  if (!sorted) return false;
  std::vector<PairIndex> half_offsets(static_cast<size_t>(n) + 1, 0);
  for (Index i = 0; i < n; ++i)
    half_offsets[size_t(i) + 1] = half_offsets[size_t(i)] + (offsets[i + 1] - first[size_t(i)]);
  const size_t total = size_t(half_offsets.back());
  list.half_offsets.resize(half_offsets.size());
  std::copy(half_offsets.begin(), half_offsets.end(), raw(list.half_offsets));
  list.half_neighbor.resize(total + kPairPrefetchDistance, 0);  // padded for the prefetch
  list.half_grad.resize(total);
  list.half_stretch.resize(total);
  if (!list.beta.empty()) list.half_beta.resize(total);
  const Vec<D, Real>* grad = raw(list.grad);
  const Real* stretch = raw(list.stretch);
  const Real* beta = list.beta.empty() ? nullptr : raw(list.beta);
  Index* hn = raw(list.half_neighbor);
  Vec<D, Real>* hg = raw(list.half_grad);
  Real* hs = raw(list.half_stretch);
  Real* hb = beta ? raw(list.half_beta) : nullptr;
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    PairIndex q = half_offsets[size_t(i)];
    for (PairIndex p = first[size_t(i)]; p < offsets[i + 1]; ++p, ++q) {
      hn[q] = neighbor[p];
      hg[q] = grad[p];
      hs[q] = stretch[p];
      if (hb) hb[q] = beta[p];
    }
  }
  list.bandwidth = half_pair_bandwidth(list, n);
  return true;
}

// The full rows of `list` in the sliced layout (kernels/neighbors/sliced_pairs.hpp)
// with slices of `height` rows, in place of the compressed ones; any backend.
// Returns the padding: stored entries / pairs.
template <class B, int D, class Real>
double make_sliced_layout(ReferenceNeighborList<B, D, Real>& list, Index n, Index height) {
  if (!list.full_rows || list.slice_height > 0 || height < 1)
    throw std::logic_error("the sliced layout needs compressed full rows and a positive height");
  const Index slices = (n + height - 1) / height;
  DeviceVector<B, PairIndex> size(static_cast<size_t>(slices)), start(static_cast<size_t>(slices));
  parallel_for<B>(slices, SliceSizeFunctor{raw(list.offsets), n, height, raw(size)});
  const PairIndex total = exclusive_scan<B, PairIndex, PairIndex>(size, start);
  list.sliced_first.resize(static_cast<size_t>(n));
  list.sliced_count.resize(static_cast<size_t>(n));
  parallel_for<B>(
      n, SlicedRowFunctor{raw(list.offsets), raw(start), height, raw(list.sliced_first), raw(list.sliced_count)});
  // Padded with zeros: the prefetch reads kPairPrefetchDistance pairs ahead.
  DeviceVector<B, Index> neighbor(size_t(total) + size_t(kPairPrefetchDistance) * size_t(height), 0);
  DeviceVector<B, Vec<D, Real>> grad(size_t(total), Vec<D, Real>::zero());
  DeviceVector<B, Real> stretch(size_t(total), Real(0)), beta(list.beta.empty() ? 0 : size_t(total), Real(0));
  parallel_for<B>(n, SlicedScatterFunctor<D, Real>{raw(list.offsets), raw(list.sliced_first), height,
                                                   raw(list.neighbor), raw(list.grad), raw(list.stretch),
                                                   list.beta.empty() ? nullptr : raw(list.beta), raw(neighbor),
                                                   raw(grad), raw(stretch), list.beta.empty() ? nullptr : raw(beta)});
  list.neighbor.swap(neighbor);
  list.grad.swap(grad);
  list.stretch.swap(stretch);
  list.beta.swap(beta);
  list.slice_height = height;
  return list.total_pairs > 0 ? double(total) / double(list.total_pairs) : 1.0;
}

// Sorts particles by (body, cell) and, when `reorder`, permutes every field of
// the set accordingly; then builds the CSR list. Reads the set-up field
// reference_position_double, the body ids and the volumes. Pairs that a notch
// cuts are left out (kernels/fracture/notch.hpp), before the gradient sums
// and the moment matrices (into the field `moment_field` where named: B0's
// inverse, correction_matrix.hpp) are formed over each neighbourhood.
// With `half_only` (CPU backend, with `reorder`) only the half-pair list is
// stored, filled straight from the search: the full rows' pair data are never
// allocated (their offsets are kept: the neighbour counts), so the set-up's
// peak holds one list, half the full one (issue 24, item 6). With
// `half_float` its pair data are stored in float (issue 24, item 4).
template <class B, int D, class Real>
ReferenceNeighborList<B, D, Real> build_reference_neighbor_list(ParticleSet<B>& particles,
                                                                const std::vector<BodySearch>& bodies, bool reorder,
                                                                bool with_beta,
                                                                const std::vector<Notch<D>>& notches = {},
                                                                const char* moment_field = nullptr,
                                                                bool half_only = false, bool half_float = false) {
  if (half_only && !(std::is_same<B, Cpu>::value && reorder))
    throw std::logic_error("a half-pair list alone needs the CPU backend and the reordering search");
  if (half_float && !half_only) throw std::logic_error("float pair data are stored by a half-pair list alone");
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
      if (bodies[k].fixed_box) l = bodies[k].box[size_t(a)], h = bodies[k].box[3 + size_t(a)];
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
  PairIndex half_total = 0;
  const PairIndex total = count_pairs<B, D, double>(hood, bodies, n, count, list.offsets,
                                                    half_only ? &list.half_offsets : nullptr, &half_total);
  DeviceVector<B, Index>().swap(count);
  list.total_pairs = total;
  const size_t stored = size_t(half_only ? half_total : total);
  auto& neighbor = half_only ? list.half_neighbor : list.neighbor;
  neighbor.resize(stored + kPairPrefetchDistance, 0);  // padded for the prefetch
  list.gradient_sum.resize(size_t(n));
  Mat<D, Real>* moment = moment_field ? particles.template get<Mat<D, Real>>(moment_field) : nullptr;
  // The pair data in P (Real, or float for the half list of a double run).
  auto fill = [&](auto& grad, auto& stretch, auto& beta) {
    using P = typename std::remove_reference_t<decltype(stretch)>::value_type;
    grad.resize(stored);
    stretch.resize(stored);
    if (with_beta) beta.resize(stored);
    for (const auto& b : bodies) {
      hood.radius2 = support_radius2<double>(b.smoothing_length);
      ReferencePairFillFunctor<D, Real, P> f{hood,
                                             WendlandC2<D, double>::make(b.smoothing_length),
                                             particles.template get<Real>(field::volume),
                                             raw(half_only ? list.half_offsets : list.offsets),
                                             raw(neighbor),
                                             raw(grad),
                                             raw(stretch),
                                             raw(list.gradient_sum),
                                             with_beta ? raw(beta) : nullptr,
                                             moment,
                                             half_only};
      parallel_for<B>(b.range.begin, b.range.end, f);
    }
  };
  list.half_float = half_float;
  bool filled = false;
  if constexpr (std::is_same<B, Cpu>::value) {  // the CPU's half loop alone stores float pairs
    if (half_float) {
      fill(list.half_grad_f, list.half_stretch_f, list.half_beta_f);
      filled = true;
    }
  }
  if (!filled) {
    if (half_only)
      fill(list.half_grad, list.half_stretch, list.half_beta);
    else
      fill(list.grad, list.stretch, list.beta);
  }
  if constexpr (std::is_same<B, Cpu>::value) {
    if (half_only) {
      list.full_rows = false;
      list.bandwidth = half_pair_bandwidth(list, n);
    }
  }
  return list;
}

}  // namespace mfsd
