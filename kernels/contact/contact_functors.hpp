// Contact stage functors (design.md: contact between bodies searches the
// current configuration each step). The candidates are the particles of the
// bodies that take part in contact, then the surface markers of the rigid
// bodies that do. Per step:
//   ContactCandidateFunctor  current position and velocity of each candidate,
//                            one launch per particle set (part) and one for the
//                            markers (particles: X + u at t + dt/2 and v^n = v - dt a,
//                            the velocity at the start of the step; markers:
//                            the prescribed placement x = A X + b and
//                            v = A' X + b' at t + dt/2). Not the velocity
//                            after the force stage: it holds dt times the
//                            internal force that the contact force balances,
//                            and the dashpot would take that for approach
//                            (the punch force then changed 4 % with dt).
//   ContactKeyFunctor        bucket of a spatial hash of cells of edge >= the
//                            reach of the largest d0; keys are sorted with the
//                            candidate index, each bucket's [start, end) found
//                            (CellRangeFunctor)
//   ContactForceFunctor      per candidate, the pair forces of the candidates
//                            in the 3^D cells around it (contact_force.hpp),
//                            gathered without atomics; returns the particle's
//                            inverse stable step (ContactRates), reduced to max
//   ContactApplyFunctor      per body particle: v += dt f / m, a += f / m, and
//                            the power of the contact force (step_force.hpp,
//                            as loads)
#pragma once
#include <cstdint>

#include "kernels/bc/step_force.hpp"
#include "kernels/contact/contact_force.hpp"
#include "kernels/core/mat.hpp"
#include "kernels/neighbors/cell_list.hpp"

namespace mfsd {

// What the candidates of one body or rigid body share.
template <class Real>
struct ContactGroup {
  Real spacing;      // dp (rigid body: its marker spacing)
  Real modulus;      // rho0 c0^2 (rigid body: 0 = infinitely stiff)
  Real support2;     // self-contact needs |X_i - X_j|^2 >= support2 (kernel support squared)
  int self_contact;  // 1: pairs within the group may touch (deformable bodies only)
  int rigid;         // 1: a rigid body's markers
  // Groups of one part never touch each other: the contact between the
  // particle sets of two methods (host/solver/coupled/) gives each set's
  // groups its part; the contact of one set gives each group its own.
  int part;
};

// The placement of a rigid body at the contact time: x = A X + b, v = A' X + b'.
template <int D, class Real>
struct RigidPlacement {
  Mat<D, Real> A, A_rate;
  Vec<D, Real> b, b_rate;
};

// Candidates [first, first + launch size): below `particles` those of one
// particle set (particle[c] indexes its fields), from it the markers.
template <int D, class Real>
struct ContactCandidateFunctor {
  Index first;
  Index particles;        // candidates below it are body particles
  const Index* particle;  // candidate -> particle index in its set
  const Vec<D, Real>* reference_position;
  const Vec<D, Real>* displacement;
  const Vec<D, Real>* velocity;
  const Vec<D, Real>* acceleration;
  Real dt;
  const Vec<D, Real>* marker_position;  // markers (candidates from `particles` on), shape as given
  const int* group;
  int first_rigid_group;
  const RigidPlacement<D, Real>* placement;  // per rigid body
  Vec<D, Real>* x;
  Vec<D, Real>* v;
  Vec<D, Real>* X;  // the particles' reference positions (self-contact test)

  MFSD_HD void operator()(Index k) const {
    const Index c = first + k;
    if (c < particles) {
      const Index p = particle[c];
      X[c] = reference_position[p];
      x[c] = reference_position[p] + displacement[p];
      v[c] = velocity[p] - acceleration[p] * dt;  // v^n
      return;
    }
    const RigidPlacement<D, Real>& P = placement[group[c] - first_rigid_group];
    const Vec<D, Real>& X = marker_position[c - particles];
    x[c] = P.A * X + P.b;
    v[c] = P.A_rate * X + P.b_rate;
  }
};

// Spatial hash of the current positions: cells of edge `cell` (>= the reach
// of the largest contact distance) hashed into a table of 2^k buckets. No
// bounding box: a particle that flies far away costs one bucket, not a coarser
// grid (a dense grid over the bounding box, widened to a few cells per
// candidate, put the octopus showcase's whole body into a handful of cells
// once a particle had escaped: 15 ms per step instead of 0.3). Two cells may
// share a bucket; a visitor checks the candidate's own cell.
template <int D, class Real>
struct ContactHashGrid {
  Real inv_cell;       // in Real: float runs hash in float (docs/floating-point.md)
  std::uint64_t mask;  // buckets - 1

  MFSD_HD void cell(const Vec<D, Real>& x, long long* c) const {
    for (int a = 0; a < D; ++a) c[a] = (long long)math::floor(x.v[a] * inv_cell);
  }
  MFSD_HD std::int64_t bucket(const long long* c) const {
    std::uint64_t h = std::uint64_t(c[0]) * 73856093ull ^ std::uint64_t(c[1]) * 19349663ull;
    if (D == 3) h ^= std::uint64_t(c[D - 1]) * 83492791ull;
    return std::int64_t(h & mask);
  }
};

template <int D, class Real>
struct ContactKeyFunctor {
  ContactHashGrid<D, Real> grid;
  const Vec<D, Real>* x;
  std::int64_t* key;
  MFSD_HD void operator()(Index c) const {
    long long cell[D];
    grid.cell(x[c], cell);
    key[c] = grid.bucket(cell);
  }
};

// Pairs closer than this many d0 count in the time-step bound: within one
// step particles approach by less than h v / (c0 + v) < 0.6 d0 (h <= 1.2 dp
// at h/dp = 1.15), so the step on which a pair first touches is stable.
// Without it the flyer plates' first contact step (omega dt = 3.3) threw the
// surface rows back at 470 m/s and added 8 MJ/m.
constexpr double kContactRateReach = 1.6;

template <int D, class Real>
struct ContactForceFunctor {
  ContactHashGrid<D, Real> grid;
  const Index* start;  // per bucket, into `order`
  const Index* end;
  const Index* order;  // cell-sorted position -> candidate
  const Vec<D, Real>* x;
  const Vec<D, Real>* v;
  const Vec<D, Real>* X;  // reference positions of the candidates (self-contact groups are particles)
  const Real* mass;       // 0 for markers
  const int* group;
  const ContactGroup<Real>* groups;
  ContactPairLaw<Real> law;
  Real stiffness_factor;  // kappa (contcoeff)
  Vec<D, Real>* force;
  // Distributed runs: 1 per ghost candidate (null: none). A rigid body's
  // markers leave the ghosts out, so that the ranks' sums of the force on
  // it count each particle once (on its owner).
  const unsigned char* ghost = nullptr;

  MFSD_HD Real operator()(Index i) const {
    const Vec<D, Real> xi = x[i], vi = v[i];
    const int gi = group[i];
    const ContactGroup<Real> Gi = groups[gi];
    const Real mi = mass[i];
    long long c[D];
    grid.cell(xi, c);
    Vec<D, Real> f = Vec<D, Real>::zero();
    ContactRates<Real> rates{Real(0), Real(0)};
    long long cc[D];
    auto visit_cell = [&]() {
      const std::int64_t k = grid.bucket(cc);
      for (Index s = start[k]; s < end[k]; ++s) {
        const Index j = order[s];
        if (j == i) continue;
        long long cj[D];
        grid.cell(x[j], cj);
        bool same = true;
        for (int a = 0; a < D; ++a) same = same && cj[a] == cc[a];
        if (!same) continue;  // another cell in this bucket
        const int gj = group[j];
        const ContactGroup<Real> Gj = groups[gj];
        if (Gi.rigid && Gj.rigid) continue;
        if (Gi.rigid && ghost && ghost[j]) continue;
        if (gi == gj && (!Gi.self_contact || squared_norm(X[i] - X[j]) < Gi.support2)) continue;
        if (gi != gj && Gi.part == Gj.part) continue;
        const Vec<D, Real> r = xi - x[j];
        const Real d0 = Real(0.5) * (Gi.spacing + Gj.spacing);
        const Real r2 = squared_norm(r);
        const Real reach = Real(kContactRateReach) * d0;
        if (!(r2 < reach * reach) || r2 == Real(0)) continue;
        Real k = stiffness_factor * contact_modulus(Gi.modulus, Gj.modulus);
        if (D == 3) k *= d0;  // k = kappa M dp^(D-2)
        const Real m_eff = contact_reduced_mass(mi, mass[j]);
        add_contact_rates(law, k, m_eff, rates);
        if (!(r2 < d0 * d0)) continue;
        const Real distance = math::sqrt(r2);
        f += contact_pair_force<D, Real>(law, r, distance, d0 - distance, vi - v[j], k, m_eff);
      }
    };
    if constexpr (D == 2) {
      for (cc[1] = c[1] - 1; cc[1] <= c[1] + 1; ++cc[1])
        for (cc[0] = c[0] - 1; cc[0] <= c[0] + 1; ++cc[0]) visit_cell();
    } else {
      for (cc[2] = c[2] - 1; cc[2] <= c[2] + 1; ++cc[2])
        for (cc[1] = c[1] - 1; cc[1] <= c[1] + 1; ++cc[1])
          for (cc[0] = c[0] - 1; cc[0] <= c[0] + 1; ++cc[0]) visit_cell();
    }
    force[i] = f;
    return rates.inverse_step();
  }
};

// Power and force sum of the contact on one body (or a rigid body's markers),
// in Real like every per-step sum (docs/floating-point.md).
template <class Real>
struct ContactSums {
  Real power;
  Real force[3];
  MFSD_HD static ContactSums zero() { return ContactSums{Real(0), {Real(0), Real(0), Real(0)}}; }
};

struct ContactSumsCombine {
  template <class Real>
  MFSD_HD ContactSums<Real> operator()(const ContactSums<Real>& a, const ContactSums<Real>& b) const {
    ContactSums<Real> r;
    r.power = a.power + b.power;
    for (int k = 0; k < 3; ++k) r.force[k] = a.force[k] + b.force[k];
    return r;
  }
};

// The candidates' masses from the method's current volumes, m_c = rho_c
// V[particle[c]] (a method whose masses change: RKPM's row-sum mass).
template <class Real>
struct ContactMassFunctor {
  Index first;
  const Index* particle;
  const Real* density;
  const Real* volume;
  Real* mass;
  MFSD_HD void operator()(Index k) const {
    const Index c = first + k;
    mass[c] = density[c] * volume[particle[c]];
  }
};

// Candidates [begin, end) of one body: c -> particle[c].
template <int D, class Real>
struct ContactApplyFunctor {
  const Index* particle;
  const Vec<D, Real>* force;
  const Real* mass;
  Real dt;
  Vec<D, Real>* velocity;
  Vec<D, Real>* acceleration;
  const unsigned char* ghost = nullptr;  // distributed runs: ghosts change, but count nothing

  MFSD_HD ContactSums<Real> operator()(Index c) const {
    ContactSums<Real> s = ContactSums<Real>::zero();
    const Vec<D, Real> f = force[c];
    const Index p = particle[c];
    const Real power = add_step_force(f, mass[c], dt, velocity[p], acceleration[p]);
    if (ghost && ghost[c]) return s;
    s.power = power;
    for (int a = 0; a < D; ++a) s.force[a] = f.v[a];
    return s;
  }
};

// Force sum over a rigid body's markers [begin, end) (the force the bodies
// exert on it).
template <int D, class Real>
struct ContactForceSumFunctor {
  const Vec<D, Real>* force;
  MFSD_HD ContactSums<Real> operator()(Index c) const {
    ContactSums<Real> s = ContactSums<Real>::zero();
    for (int a = 0; a < D; ++a) s.force[a] = force[c].v[a];
    return s;
  }
};

}  // namespace mfsd
