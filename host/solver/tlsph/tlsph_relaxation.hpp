// Dynamic relaxation of a TLSPH run on one backend (scene solver.relaxation;
// kernels/tlsph/relaxation.hpp): the colouring of the reference cells built
// once, the random choice of the steps that relax, the two sweeps of such a
// step, and per body the energy the relaxation took (energies.csv;
// RelaxationWorkFunctor). Runs last of the velocity updates, after the velocity
// conditions and clamps: their particles are held (not changed) and their
// prescribed velocities pull on their free neighbours.
// Include after the backend header.
#pragma once
#include <thrust/copy.h>
#include <thrust/functional.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <sstream>
#include <vector>

#include "host/backend/algorithms.hpp"
#include "host/backend/device_results.hpp"
#include "host/particles/particle_set.hpp"
#include "host/scene/scene.hpp"
#include "host/solver/solver.hpp"
#include "host/solver/tlsph/reference_neighbor_list.hpp"
#include "host/solver/tlsph/tlsph_views.hpp"
#include "kernels/tlsph/relaxation.hpp"

namespace mfsd {

template <class B, int D, class Real>
class TlsphRelaxation {
 public:
  bool enabled() const { return spec_.enabled; }

  // `position`: reference positions in the solver's order; `density` and
  // `viscosity`: rho0 and eta per body; `support`: the largest support radius 2h of the bodies; `held`:
  // per particle, whether a clamp or velocity condition sets its velocity
  // (empty: none).
  void setup(const RelaxationSpec& spec, const std::vector<BodyRange>& ranges, const std::vector<double>& density,
             const std::vector<double>& viscosity, const std::vector<Vec<D, Real>>& position, double support,
             const std::vector<unsigned char>& held = {}) {
    spec_ = spec;
    ranges_ = ranges;
    density_ = density;
    dissipation_.assign(ranges.size(), 0.0);
    if (!spec_.enabled) return;
    before_.resize(position.size());
    random_.seed(spec_.seed);
    // Cells of edge `support` over the reference bounding box (the grid of the neighbour search).
    double lo[D], hi[D];
    for (int a = 0; a < D; ++a) {
      lo[a] = hi[a] = position.empty() ? 0.0 : double(position[0].v[a]);
      for (const auto& x : position) lo[a] = std::min(lo[a], double(x.v[a])), hi[a] = std::max(hi[a], double(x.v[a]));
    }
    const CellGrid<D> grid = make_cell_grid<D>(lo, hi, support);  // coordinates only: no storage per cell
    struct Entry {
      int colour;
      int body;
      std::int64_t cell;
      Index particle;
    };
    std::vector<Entry> entries;
    for (size_t b = 0; b < ranges.size(); ++b)
      for (Index p = ranges[b].begin; p < ranges[b].end; ++p) {
        int c[D];
        int colour = 0;
        for (int a = D - 1; a >= 0; --a) {
          c[a] = grid.coordinate(a, double(position[size_t(p)].v[a]));
          colour = colour * 3 + c[a] % 3;
        }
        entries.push_back(Entry{colour, int(b), grid.linear(c), p});
      }
    std::sort(entries.begin(), entries.end(), [](const Entry& x, const Entry& y) {
      if (x.colour != y.colour) return x.colour < y.colour;
      if (x.body != y.body) return x.body < y.body;
      if (x.cell != y.cell) return x.cell < y.cell;
      return x.particle < y.particle;
    });
    std::vector<Index> offset{0}, particle;
    std::vector<Real> item_density, item_viscosity;
    colour_first_.assign(size_t(kColours) + 1, 0);
    Index items = 0;
    for (size_t k = 0; k < entries.size(); ++k) {
      const Entry& e = entries[k];
      particle.push_back(e.particle);
      const bool last = k + 1 == entries.size() || entries[k + 1].colour != e.colour || entries[k + 1].body != e.body ||
                        entries[k + 1].cell != e.cell;
      if (!last) continue;
      offset.push_back(Index(particle.size()));
      item_density.push_back(Real(density[size_t(e.body)]));
      item_viscosity.push_back(Real(viscosity[size_t(e.body)]));
      colour_first_[size_t(e.colour) + 1] = ++items;
    }
    for (int c = 1; c <= kColours; ++c)
      colour_first_[size_t(c)] = std::max(colour_first_[size_t(c)], colour_first_[size_t(c) - 1]);
    from_host<B>(offset, item_offset_);
    from_host<B>(particle, item_particle_);
    host_offset_ = offset;
    host_particle_ = particle;
    from_host<B>(item_density, item_density_);
    from_host<B>(item_viscosity, item_viscosity_);
    if (std::find(held.begin(), held.end(), 1) != held.end()) from_host<B>(held, held_);
  }

  // The relaxation of the step [t, t + dt]: with probability p, both sweeps
  // with eta / p (seed 003 ref. [68], random choice), in the window only.
  void apply(const TlsphViews<D, Real>& view, double t, double dt, DeviceResults<B>& results) {
    if (!spec_.enabled || t < spec_.t_start || t >= spec_.t_end) return;
    const double u = double(random_() >> 11) * 0x1.0p-53;  // uniform in [0, 1), the same on every platform
    if (u >= spec_.random_ratio) return;
    ++relaxed_steps_;
    thrust::copy(BackendTraits<B>::policy(), view.velocity, view.velocity + before_.size(), raw(before_));
    const Real step = Real(dt / spec_.random_ratio);  // 2 tau / p with tau = dt/2
    RelaxationSweepFunctor<D, Real> f{view.pairs,
                                      view.velocity,
                                      view.volume,
                                      raw(item_offset_),
                                      raw(item_particle_),
                                      raw(item_density_),
                                      raw(item_viscosity_),
                                      held_.empty() ? nullptr : raw(held_),
                                      step,
                                      true};
    for (int c = 0; c < kColours; ++c) parallel_for<B>(colour_first_[size_t(c)], colour_first_[size_t(c) + 1], f);
    f.forward = false;
    for (int c = kColours - 1; c >= 0; --c) parallel_for<B>(colour_first_[size_t(c)], colour_first_[size_t(c) + 1], f);
    pending_.clear();
    for (size_t b = 0; b < ranges_.size(); ++b)
      pending_.push_back(results.reduce(ranges_[b].begin, ranges_[b].end,
                                        RelaxationWorkFunctor<D, Real>{raw(before_), view.velocity, view.acceleration,
                                                                       view.volume, Real(density_[b]), Real(dt)},
                                        Real(0), thrust::plus<Real>{}));
  }

  // After results.fetch(): the energy this step's sweeps took.
  void collect(const DeviceResults<B>& results) {
    for (size_t b = 0; b < pending_.size(); ++b) dissipation_[b] += double(results.get(pending_[b]));
    pending_.clear();
  }

  // Energy the relaxation took from body b so far, J (2-D: per metre of depth).
  double dissipation(size_t b) const { return dissipation_[b]; }

  long relaxed_steps() const { return relaxed_steps_; }

  // The random generator's state, the dissipation sums and the count (checkpoints).
  void save(StateArchive& a) const {
    std::ostringstream engine;
    engine << random_;
    a.put_bytes("relaxation/random", engine.str());
    a.put("relaxation/dissipation", dissipation_);
    a.put_value("relaxation/relaxed_steps", relaxed_steps_);
  }
  void restore(const StateArchive& a) {
    std::istringstream engine(a.bytes("relaxation/random"));
    engine >> random_;
    if (!engine) throw StateMismatch("checkpoint part 'relaxation/random' is not a generator state");
    dissipation_ = a.get<double>("relaxation/dissipation", long(dissipation_.size()));
    relaxed_steps_ = a.get_value<long>("relaxation/relaxed_steps");
  }

  // The particles of each cell of colour c (tests check that they touch disjoint particles).
  std::vector<std::vector<Index>> items_of_colour(int c) const {
    std::vector<std::vector<Index>> out;
    for (Index k = colour_first_[size_t(c)]; k < colour_first_[size_t(c) + 1]; ++k)
      out.emplace_back(host_particle_.begin() + host_offset_[size_t(k)],
                       host_particle_.begin() + host_offset_[size_t(k) + 1]);
    return out;
  }

 private:
  static constexpr int kColours = D == 2 ? 9 : 27;
  RelaxationSpec spec_;
  std::mt19937_64 random_;
  std::vector<Index> colour_first_;  // items of colour c: [colour_first_[c], colour_first_[c + 1])
  std::vector<Index> host_offset_, host_particle_;
  DeviceVector<B, Index> item_offset_, item_particle_;
  DeviceVector<B, Real> item_density_, item_viscosity_;
  DeviceVector<B, unsigned char> held_;
  DeviceVector<B, Vec<D, Real>> before_;  // v before the sweeps
  std::vector<BodyRange> ranges_;
  std::vector<double> density_, dissipation_;
  std::vector<ResultSlot<Real>> pending_;  // this step's dissipation per body, in DeviceResults
  long relaxed_steps_ = 0;
};

}  // namespace mfsd
