// Test helper: a CPU particle set from host positions, with the reference
// neighbour list built by the production code.
#pragma once
#include <random>
#include <vector>

#include "host/backend/cpu.hpp"
#include "host/particles/field_names.hpp"
#include "host/solver/tlsph/reference_neighbor_list.hpp"

namespace mfsd::test {

template <int D>
std::vector<Vec<D, double>> lattice(const int* n, double dp, double jitter, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter * dp, jitter * dp);
  std::vector<Vec<D, double>> x;
  const int nz = D == 3 ? n[2] : 1;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        Vec<D, double> p;
        p.v[0] = (i + 0.5) * dp + u(rng);
        p.v[1] = (j + 0.5) * dp + u(rng);
        if constexpr (D == 3) p.v[2] = (k + 0.5) * dp + u(rng);
        x.push_back(p);
      }
  return x;
}

template <int D, class Real>
struct Fixture {
  ParticleSet<Cpu> particles;
  ReferenceNeighborList<Cpu, D, Real> pairs;

  // All particles in body 0 unless `body` is given; uniform volume dp^D
  // unless `volume` is given. With `moments` the search leaves each particle's
  // moment matrix in the field correction_matrix; `half_only` stores only the
  // half-pair list (build_reference_neighbor_list).
  Fixture(const std::vector<Vec<D, double>>& x, double dp, double h, bool reorder, std::vector<int> body = {},
          bool beta = false, const std::vector<Notch<D>>& notches = {}, std::vector<Real> volume = {},
          bool moments = false, bool half_only = false)
      : particles(Index(x.size())) {
    const size_t n = x.size();
    if (body.empty()) body.assign(n, 0);
    std::vector<Index> id(n);
    std::vector<Vec<D, Real>> xr(n);
    for (size_t i = 0; i < n; ++i) {
      id[i] = Index(i);
      xr[i] = cast<Real>(x[i]);
    }
    particles.add<Index>(field::id);
    from_host<Cpu>(id, particles.buffer<Index>(field::id));
    particles.add<int>(field::body);
    from_host<Cpu>(body, particles.buffer<int>(field::body));
    particles.add<Vec<D, double>>(field::reference_position_double);
    from_host<Cpu>(x, particles.buffer<Vec<D, double>>(field::reference_position_double));
    particles.add<Vec<D, Real>>(field::reference_position);
    from_host<Cpu>(xr, particles.buffer<Vec<D, Real>>(field::reference_position));
    particles.add<Real>(field::volume);
    if (volume.empty()) volume.assign(n, Real(std::pow(dp, D)));
    from_host<Cpu>(volume, particles.buffer<Real>(field::volume));
    if (moments) particles.add<Mat<D, Real>>(field::correction_matrix);
    int bodies = 1;
    for (int b : body) bodies = std::max(bodies, b + 1);
    // Bodies must be contiguous ranges in the input.
    std::vector<BodySearch> search;
    for (int b = 0; b < bodies; ++b) {
      Index lo = Index(n), hi = 0;
      for (size_t i = 0; i < n; ++i)
        if (body[i] == b) lo = std::min(lo, Index(i)), hi = std::max(hi, Index(i + 1));
      search.push_back(BodySearch{BodyRange{lo, hi}, h});
    }
    pairs = build_reference_neighbor_list<Cpu, D, Real>(particles, search, reorder, beta, notches,
                                                        moments ? field::correction_matrix : nullptr, half_only);
  }

  template <class T>
  std::vector<T> host(const char* name) {
    return to_host<Cpu>(particles.buffer<T>(name));
  }
};

}  // namespace mfsd::test
