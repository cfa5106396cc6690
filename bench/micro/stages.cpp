// Microbenchmarks (Google Benchmark) of the TLSPH building blocks at a fixed
// size, so that a regression in one stage shows on its own: reference
// neighbour-list build (cell list, sort, reorder, CSR fill), reordering of the
// particle fields, and the stress, force and deformation-rate stages with
// genog and a neo-Hookean material, in float and double, on the CPU backend.
// Run: scripts/bench.sh micro   (or build/bench/mfsd_microbench directly).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "host/backend/cpu.hpp"
#include "host/solver/tlsph/reference_neighbor_list.hpp"
#include "host/particles/field_names.hpp"
#include "kernels/materials/neo_hookean.hpp"
#include "kernels/tlsph/acceleration.hpp"
#include "kernels/tlsph/deformation_rate.hpp"
#include "kernels/tlsph/stress.hpp"

namespace {

using namespace mfsd;
constexpr int kSide = 44;  // 44^3 = 85,184 particles, about 52 neighbours each
constexpr double kDp = 0.1, kH = 1.15 * kDp;

// A slightly sheared, jittered lattice block with every TLSPH field.
template <class Real>
struct Block {
  ParticleSet<Cpu> particles{Index(kSide * kSide * kSide)};
  ReferenceNeighborList<Cpu, 3, Real> pairs;
  Index n = Index(kSide * kSide * kSide);

  explicit Block(bool build_pairs = true) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> jitter(-0.05 * kDp, 0.05 * kDp);
    const size_t count = static_cast<size_t>(n);
    std::vector<Vec<3, double>> xd(count);
    std::vector<Vec<3, Real>> x(count), v(count);
    std::vector<Index> id(count);
    for (Index k = 0; k < n; ++k) {
      const int c[3] = {k % kSide, (k / kSide) % kSide, k / (kSide * kSide)};
      for (int a = 0; a < 3; ++a) xd[size_t(k)].v[a] = (c[a] + 0.5) * kDp + jitter(rng);
    }
    std::shuffle(xd.begin(), xd.end(), rng);  // the generator's order is not the cell order
    for (size_t k = 0; k < count; ++k) {
      x[k] = cast<Real>(xd[k]);
      for (int a = 0; a < 3; ++a) v[k].v[a] = Real(0.1 * xd[k].v[(a + 1) % 3]);
      id[k] = Index(k);
    }
    particles.add<Index>(field::id);
    from_host<Cpu>(id, particles.buffer<Index>(field::id));
    particles.add<int>(field::body);
    from_host<Cpu>(std::vector<int>(size_t(n), 0), particles.buffer<int>(field::body));
    particles.add<Vec<3, double>>(field::reference_position_double);
    from_host<Cpu>(xd, particles.buffer<Vec<3, double>>(field::reference_position_double));
    particles.add<Vec<3, Real>>(field::reference_position);
    from_host<Cpu>(x, particles.buffer<Vec<3, Real>>(field::reference_position));
    particles.add<Vec<3, Real>>(field::velocity);
    from_host<Cpu>(v, particles.buffer<Vec<3, Real>>(field::velocity));
    particles.add<Vec<3, Real>>(field::displacement);
    particles.add<Real>(field::volume);
    from_host<Cpu>(std::vector<Real>(size_t(n), Real(kDp * kDp * kDp)), particles.buffer<Real>(field::volume));
    for (const char* f : {field::deformation_gradient, field::deformation_rate, field::correction_matrix,
                          field::force_stress, field::shear_stress, field::inverse_deformation_gradient})
      particles.add<Mat<3, Real>>(f);
    particles.add<Vec<3, Real>>(field::acceleration);
    particles.add<GenogNeighborRecord<Real>>(field::genog_neighbor_record);
    if (build_pairs) build();
    auto* F = particles.get<Mat<3, Real>>(field::deformation_gradient);
    auto* B0 = particles.get<Mat<3, Real>>(field::correction_matrix);
    for (Index i = 0; i < n; ++i) {
      F[i] = Mat<3, Real>::identity();
      F[i].m[0][1] = Real(0.02);
      B0[i] = Mat<3, Real>::identity();
    }
  }

  void build() { pairs = build_reference_neighbor_list<Cpu, 3, Real>(particles, {{{0, n}, kH}}, true, false); }

  template <class T>
  T* f(const char* name) {
    return particles.get<T>(name);
  }

  bool packed = false;  // the CPU force loop's packed neighbour record (as the solver uses)

  StressFunctor<3, Real, NeoHookean<3, Real>, HourglassGenog> stress(Real half_dt) {
    return {NeoHookean<3, Real>{Real(5.7e7), Real(5.9e6)},
            {Real(1e3), Real(1e2)},
            Real(1),
            false,
            half_dt,
            f<Mat<3, Real>>(field::deformation_gradient),
            f<Vec<3, Real>>(field::displacement),
            f<Vec<3, Real>>(field::velocity),
            f<Mat<3, Real>>(field::deformation_rate),
            f<Mat<3, Real>>(field::correction_matrix),
            f<Mat<3, Real>>(field::force_stress),
            nullptr,
            f<Mat<3, Real>>(field::shear_stress),
            f<Mat<3, Real>>(field::inverse_deformation_gradient),
            packed ? f<GenogNeighborRecord<Real>>(field::genog_neighbor_record) : nullptr};
  }
};

void report(benchmark::State& state, Index n) {
  state.SetItemsProcessed(int64_t(state.iterations()) * n);  // items = particles (particle-steps/s per stage)
}

template <class Real>
void BM_NeighborListBuild(benchmark::State& state) {
  Block<Real> block(false);
  for (auto _ : state) {
    block.build();
    benchmark::DoNotOptimize(block.pairs.pairs());
  }
  report(state, block.n);
}

template <class Real>
void BM_Reorder(benchmark::State& state) {
  Block<Real> block(false);
  std::vector<Index> perm(static_cast<size_t>(block.n));
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(5));
  DeviceVector<Cpu, Index> order;
  from_host<Cpu>(perm, order);
  for (auto _ : state) block.particles.permute(order);
  report(state, block.n);
}

template <class Real>
void BM_Stress(benchmark::State& state) {
  Block<Real> block;
  const auto f = block.stress(Real(0));
  for (auto _ : state) parallel_for<Cpu>(block.n, f);
  report(state, block.n);
}

// Argument: 1 = packed neighbour record (the solver's CPU path), 0 = scalar path.
template <class Real>
void BM_Force(benchmark::State& state) {
  Block<Real> block;
  block.packed = state.range(0) != 0;
  parallel_for<Cpu>(block.n, block.stress(Real(0)));
  AccelerationFunctor<3, Real, HourglassGenog> f{
      block.pairs.view(),
      block.template f<Mat<3, Real>>(field::force_stress),
      nullptr,
      block.template f<Mat<3, Real>>(field::shear_stress),
      block.template f<Mat<3, Real>>(field::inverse_deformation_gradient),
      block.template f<Vec<3, Real>>(field::displacement),
      block.packed ? block.template f<GenogNeighborRecord<Real>>(field::genog_neighbor_record) : nullptr,
      Real(1.0 / 1100),
      Vec<3, Real>::zero(),
      GenogWeight<Real>{GenogLimiter::capped, Real(0)},
      Real(0),
      block.template f<Vec<3, Real>>(field::acceleration),
      block.template f<Vec<3, Real>>(field::velocity)};
  for (auto _ : state) parallel_for<Cpu>(block.n, f);
  report(state, block.n);
}

template <class Real>
void BM_DeformationRate(benchmark::State& state) {
  Block<Real> block;
  StepStatisticsFunctor<3, Real> stats{block.template f<Vec<3, Real>>(field::reference_position),
                                       block.template f<Vec<3, Real>>(field::displacement),
                                       block.template f<Vec<3, Real>>(field::velocity),
                                       block.template f<Vec<3, Real>>(field::acceleration),
                                       nullptr,
                                       nullptr,
                                       Vec<3, Real>::zero(),
                                       Vec<3, Real>::zero(),
                                       block.n};
  for (int a = 0; a < 3; ++a) stats.lower.v[a] = Real(-100), stats.upper.v[a] = Real(100);
  RateHalfStepFunctor<3, Real> f{block.pairs.view(),
                                 block.template f<Vec<3, Real>>(field::velocity),
                                 block.template f<Mat<3, Real>>(field::correction_matrix),
                                 block.template f<Mat<3, Real>>(field::deformation_rate),
                                 block.template f<Mat<3, Real>>(field::deformation_gradient),
                                 block.template f<Vec<3, Real>>(field::displacement),
                                 Real(0),
                                 stats};
  for (auto _ : state) {
    auto s = transform_reduce<Cpu>(0, block.n, f, StepStatistics<Real>{Real(0), Real(0), Real(0), Real(0), block.n},
                                   StepStatisticsCombine<Real>{});
    benchmark::DoNotOptimize(s);
  }
  report(state, block.n);
}

}  // namespace

BENCHMARK_TEMPLATE(BM_NeighborListBuild, double)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(BM_Reorder, double)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(BM_Stress, double)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(BM_Stress, float)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(BM_Force, double)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(BM_Force, float)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(BM_DeformationRate, double)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(BM_DeformationRate, float)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
