// Contact of a run on one backend, any method (scene.contact): the candidates (the
// particles of the bodies in contact, then the surface markers of the rigid
// bodies that push them), the current-configuration cell search of each step
// and the pair forces of kernels/contact. The particles may come from
// several particle sets (parts: the solvers of a scene of two methods, each
// with its own numbering and Kinematics view); `between_parts` then keeps only
// the pairs of two different parts (the contact within a part is that
// solver's own). Runs after the force stage, at the
// half-step positions, like a load. Keeps per body the work of the contact
// forces (energies.csv) and per rigid body the force it exerts on the bodies
// (boundary_forces.csv). Include after the backend header.
#pragma once
#include <thrust/copy.h>
#include <thrust/fill.h>
#include <thrust/functional.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "host/backend/algorithms.hpp"
#include "host/backend/device_results.hpp"
#include "host/scene/body_properties.hpp"
#include "host/scene/particle_generator.hpp"
#include "host/scene/rigid_body.hpp"
#include "host/solver/common/kinematics.hpp"
#include "host/solver/solver.hpp"
#include "kernels/contact/contact_functors.hpp"

namespace mfsd {

// One particle set of a contact: its bodies (scene index of each of its
// bodies, their index ranges and properties), the particles' volumes in the
// set's (reordered) order and which can touch (`near_surface`: the surface
// layer, one kernel support deep: interior particles never meet another body).
template <class Real>
struct ContactPartSetup {
  std::vector<size_t> scene_body;
  std::vector<BodyRange> ranges;
  std::vector<BodyProperties> props;
  std::vector<Real> volume;
  std::vector<unsigned char> near_surface;
  // Distributed runs: 1 per ghost particle (empty: none). Ghosts take part
  // as partners of the owned particles; the sums (work, rigid-body forces)
  // leave them out: their owners count them.
  std::vector<unsigned char> ghost;
};

template <class B, int D, class Real>
class Contact {
 public:
  bool enabled() const { return enabled_; }

  // The contact of one solver's particles: scene.contact's bodies, the
  // rigid bodies that push them, self-contact.
  void setup(const Scene& scene, const InitialParticles& init, const std::vector<BodyRange>& ranges,
             const std::vector<BodyProperties>& props, const std::vector<Real>& volume,
             const std::vector<unsigned char>& near_surface) {
    ContactPartSetup<Real> part{{}, ranges, props, volume, near_surface};
    for (size_t b = 0; b < scene.bodies.size(); ++b) part.scene_body.push_back(b);
    setup(scene, init.rigid_markers, {part}, false);
  }

  // `between_parts`: only the pairs of bodies of two different parts, no
  // rigid bodies and no self-contact.
  void setup(const Scene& scene, const std::vector<std::vector<Point3>>& rigid_markers,
             const std::vector<ContactPartSetup<Real>>& parts, bool between_parts) {
    const ContactSpec& spec = scene.contact;
    enabled_ = spec.enabled;
    work_.assign(scene.bodies.size(), 0.0);
    if (!enabled_) return;
    law_ = ContactPairLaw<Real>{Real(contact_damping_ratio(spec.restitution)), Real(spec.friction)};
    stiffness_factor_ = spec.stiffness;
    // From scratch: a distributed run sets the contact up again after its
    // particles migrated (ParticleSolver::setup_contact_again).
    body_spans_.clear();
    rigid_spans_.clear();
    rigid_names_.clear();
    motion_.clear();
    max_spacing_ = 0;
    std::map<std::string, size_t> rigid_index;
    for (size_t r = 0; r < scene.rigid_bodies.size(); ++r) rigid_index[scene.rigid_bodies[r].name] = r;

    std::vector<Index> particle;
    std::vector<Real> mass, density;
    std::vector<int> group;
    std::vector<unsigned char> ghost;
    std::vector<ContactGroup<Real>> groups;
    part_begin_.assign(1, 0);
    for (size_t q = 0; q < parts.size(); ++q) {
      const ContactPartSetup<Real>& P = parts[q];
      for (const std::string& name : spec.bodies) {  // in contact.bodies order
        size_t lb = 0;
        while (lb < P.scene_body.size() && scene.bodies[P.scene_body[lb]].name != name) ++lb;
        if (lb == P.scene_body.size()) continue;  // a body of another part
        const size_t b = P.scene_body[lb];
        const bool self = !between_parts && std::find(spec.self_contact.begin(), spec.self_contact.end(), name) !=
                                                spec.self_contact.end();
        const double support = 2.0 * P.props[lb].h;
        const double rho = scene.bodies[b].material.density;
        const int g = int(groups.size());
        groups.push_back(ContactGroup<Real>{Real(scene.bodies[b].spacing), Real(rho * P.props[lb].c0 * P.props[lb].c0),
                                            Real(support * support), self ? 1 : 0, 0, between_parts ? int(q) : g});
        Span s{b, Index(particle.size()), 0, q};
        for (Index p = P.ranges[lb].begin; p < P.ranges[lb].end; ++p) {
          if (!P.near_surface[size_t(p)]) continue;
          particle.push_back(p);
          ghost.push_back(P.ghost.empty() ? 0 : P.ghost[size_t(p)]);
          mass.push_back(Real(rho * double(P.volume[size_t(p)])));
          density.push_back(Real(rho));
          group.push_back(g);
        }
        s.end = Index(particle.size());
        body_spans_.push_back(s);
        max_spacing_ = std::max(max_spacing_, scene.bodies[b].spacing);
      }
      part_begin_.push_back(Index(particle.size()));
    }
    particles_ = Index(particle.size());
    first_rigid_group_ = int(groups.size());
    std::vector<Vec<D, Real>> markers;
    for (const std::string& name : between_parts ? std::vector<std::string>{} : spec.rigid_bodies) {
      const size_t r = rigid_index.at(name);
      const RigidBodySpec& rs = scene.rigid_bodies[r];
      groups.push_back(ContactGroup<Real>{Real(rs.marker_spacing), Real(0), Real(0), 0, 1, int(groups.size())});
      motion_.emplace_back(rs, scene.constants, "/rigid_bodies/" + std::to_string(r));
      Span s{r, Index(particles_ + markers.size()), 0, 0};
      for (const Point3& X : rigid_markers[r]) {
        Vec<D, Real> x;
        for (int a = 0; a < D; ++a) x.v[a] = Real(X[a]);
        markers.push_back(x);
        mass.push_back(Real(0));
        ghost.push_back(0);
        group.push_back(int(groups.size() - 1));
      }
      s.end = Index(particles_ + markers.size());
      rigid_spans_.push_back(s);
      rigid_names_.push_back(name);
      max_spacing_ = std::max(max_spacing_, rs.marker_spacing);
    }
    rigid_force_.assign(rigid_spans_.size(), Point3{0, 0, 0});
    count_ = local_count_ = Index(particle.size() + markers.size());
    remote_ = nullptr;
    from_host<B>(particle, particle_);
    from_host<B>(markers, marker_position_);
    from_host<B>(mass, mass_);
    from_host<B>(density, density_);
    from_host<B>(group, group_);
    has_ghosts_ = std::count(ghost.begin(), ghost.end(), (unsigned char)1) > 0;
    from_host<B>(ghost, ghost_);
    from_host<B>(groups, groups_);
    placement_.resize(rigid_spans_.size());
    x_.resize(size_t(count_));
    v_.resize(size_t(count_));
    X_.resize(size_t(count_));
    force_.resize(size_t(count_));
    keys_.resize(size_t(count_));
    order_.resize(size_t(count_));
  }

  // Distributed runs of a method whose ghosts are not the current
  // configuration's neighbours (TLSPH: those of the reference
  // configuration), with contact between bodies or self-contact: at every
  // step each rank's candidates within the contact's reach of another rank's
  // candidates go to that rank as remote candidates, partners of its own and
  // nothing more (no force applied to them, none counted). Set up after
  // setup(), which forgets it.
  void attach_remote(GhostExchange* exchange) { remote_ = exchange; }

  // For a method whose masses change (RKPM's row-sum mass): the candidates
  // of part q take rho V from `volume` (the part's kinematic volumes) now,
  // so that the contact's forces change the momentum M v by exactly their
  // impulse. Without it the masses stay rho V of the set-up.
  void refresh_masses(const Real* volume, size_t q = 0) {
    if (!enabled_ || q + 1 >= part_begin_.size()) return;
    const Index first = part_begin_[q], n = part_begin_[q + 1] - first;
    if (n > 0) parallel_for<B>(n, ContactMassFunctor<Real>{first, raw(particle_), raw(density_), volume, raw(mass_)});
  }

  // Contact forces at the half-step positions (t: start of the step); v and a
  // of the touching particles change like under a load. The sums (time-step
  // bound, work, rigid-body forces) stay in `results` until collect().
  void apply(const Kinematics<D, Real>& view, double t, double dt, DeviceResults<B>& results) {
    apply(&view, t, dt, results);
  }

  // views[q]: part q's fields, every part at the same point of the same step.
  void apply(const Kinematics<D, Real>* views, double t, double dt, DeviceResults<B>& results) {
    if (!enabled_ || count_ == 0) return;
    place_rigid_bodies(t, dt);
    auto candidates = [&](Index first, Index end, const Kinematics<D, Real>& view, Index launch) {
      if (launch > 0)
        parallel_for<B>(launch, ContactCandidateFunctor<D, Real>{
                                    first, end, raw(particle_), view.reference_position, view.displacement,
                                    view.velocity, view.acceleration, Real(dt), raw(marker_position_), raw(group_),
                                    first_rigid_group_, raw(placement_), raw(x_), raw(v_), raw(X_)});
    };
    for (size_t q = 0; q + 1 < part_begin_.size(); ++q)
      candidates(part_begin_[q], part_begin_[q + 1], views[q], part_begin_[q + 1] - part_begin_[q]);
    candidates(particles_, particles_, views[0], local_count_ - particles_);  // the markers
    if (remote_) append_remote();
    const ContactHashGrid<D, Real> grid = make_grid();
    parallel_for<B>(count_, ContactKeyFunctor<D, Real>{grid, raw(x_), raw(keys_)});
    sequence<B, Index>(order_);
    stable_sort_by_key<B, std::int64_t, Index>(keys_, order_);
    thrust::fill(BackendTraits<B>::policy(), start_.begin(), start_.begin() + cells_, Index(0));
    thrust::fill(BackendTraits<B>::policy(), end_.begin(), end_.begin() + cells_, Index(0));
    parallel_for<B>(count_, CellRangeFunctor{raw(keys_), count_, raw(start_), raw(end_)});
    const ContactForceFunctor<D, Real> f{grid,        raw(start_),
                                         raw(end_),   raw(order_),
                                         raw(x_),     raw(v_),
                                         raw(X_),     raw(mass_),
                                         raw(group_), raw(groups_),
                                         law_,        Real(stiffness_factor_),
                                         raw(force_), has_ghosts_ ? raw(ghost_) : nullptr};
    pending_.clear();
    pending_.dt = dt;
    // The rows of this rank's candidates and markers; remote candidates are partners only.
    pending_.inverse_step = results.reduce(Index(0), local_count_, f, Real(0), thrust::maximum<Real>{});
    for (const Span& s : body_spans_)
      pending_.body.push_back(results.reduce(
          s.begin, s.end,
          ContactApplyFunctor<D, Real>{raw(particle_), raw(force_), raw(mass_), Real(dt), views[s.part].velocity,
                                       views[s.part].acceleration, has_ghosts_ ? raw(ghost_) : nullptr},
          ContactSums<Real>::zero(), ContactSumsCombine{}));
    for (const Span& s : rigid_spans_)
      pending_.rigid.push_back(results.reduce(s.begin, s.end, ContactForceSumFunctor<D, Real>{raw(force_)},
                                              ContactSums<Real>::zero(), ContactSumsCombine{}));
    pending_.ready = true;
  }

  // After results.fetch(): the step's contact step bound, work and forces.
  void collect(const DeviceResults<B>& results) {
    if (!pending_.ready) return;
    pending_.ready = false;
    inverse_step_ = double(results.get(pending_.inverse_step));
    for (size_t k = 0; k < body_spans_.size(); ++k)
      work_[body_spans_[k].index] += double(results.get(pending_.body[k]).power) * pending_.dt;
    for (size_t r = 0; r < rigid_spans_.size(); ++r) {
      const ContactSums<Real> sum = results.get(pending_.rigid[r]);
      for (int a = 0; a < 3; ++a) rigid_force_[r][a] = -double(sum.force[a]);  // on the bodies
    }
  }

  // 1 / the largest stable step of the last step's contacts (0 without
  // contacts; contact_force.hpp).
  double inverse_stable_step() const { return inverse_step_; }
  // The work sums, the rigid bodies' last forces and the contact step bound (checkpoints).
  void save(StateArchive& a) const {
    a.put("contact/work", work_);
    a.put("contact/rigid_force", rigid_force_);
    a.put_value("contact/inverse_step", inverse_step_);
  }
  void restore(const StateArchive& a) {
    work_ = a.get<double>("contact/work", long(work_.size()));
    rigid_force_ = a.get<Point3>("contact/rigid_force", long(rigid_force_.size()));
    inverse_step_ = a.get_value<double>("contact/inverse_step");
  }

  double work(size_t body) const { return enabled_ ? work_[body] : 0.0; }

  // The force each rigid body in contact exerts on the bodies, last step.
  std::vector<BoundaryForceSample> forces() const {
    std::vector<BoundaryForceSample> out;
    for (size_t r = 0; r < rigid_names_.size(); ++r) out.push_back({rigid_names_[r], rigid_force_[r]});
    return out;
  }

 private:
  struct Span {
    size_t index;  // scene body or rigid body
    Index begin, end;
    size_t part;  // the particle set of a body
  };
  // This step's sums, waiting in DeviceResults.
  struct Pending {
    bool ready = false;
    double dt = 0;
    ResultSlot<Real> inverse_step;
    std::vector<ResultSlot<ContactSums<Real>>> body, rigid;
    void clear() {
      body.clear();
      rigid.clear();
    }
  };

  // The remote candidates of this step (attach_remote): rows x, v, X, mass,
  // group from the ranks whose candidates' box comes within the contact's
  // reach of this rank's, appended after the markers, flagged as ghosts.
  void append_remote() {
    struct Row {
      Vec<D, Real> x, v, X;
      Real mass;
      int group;
    };
    const std::vector<Vec<D, Real>> x = to_host<B>(x_), v = to_host<B>(v_), X = to_host<B>(X_);
    const std::vector<Real> mass = to_host<B>(mass_);
    const std::vector<int> group = to_host<B>(group_);
    std::vector<double> box(6, 0.0);  // lo[3], hi[3] of this rank's candidates (empty: lo > hi)
    for (int a = 0; a < 3; ++a) box[size_t(a)] = 1e300, box[size_t(3 + a)] = -1e300;
    for (Index c = 0; c < particles_; ++c)
      for (int a = 0; a < D; ++a) {
        box[size_t(a)] = std::min(box[size_t(a)], double(x[size_t(c)].v[a]));
        box[size_t(3 + a)] = std::max(box[size_t(3 + a)], double(x[size_t(c)].v[a]));
      }
    const std::vector<std::vector<double>> boxes = remote_->gather_all(box);
    const double reach = kContactRateReach * max_spacing_;
    std::vector<std::vector<char>> out(boxes.size());
    for (size_t q = 0; q < boxes.size(); ++q) {
      if (int(q) == remote_->rank()) continue;
      for (Index c = 0; c < particles_; ++c) {
        double d2 = 0;
        for (int a = 0; a < D; ++a) {
          const double xa = double(x[size_t(c)].v[a]);
          const double d = std::max({boxes[q][size_t(a)] - xa, xa - boxes[q][size_t(3 + a)], 0.0});
          d2 += d * d;
        }
        if (!(d2 < reach * reach)) continue;
        const Row r{x[size_t(c)], v[size_t(c)], X[size_t(c)], mass[size_t(c)], group[size_t(c)]};
        const char* p = reinterpret_cast<const char*>(&r);
        out[q].insert(out[q].end(), p, p + sizeof(Row));
      }
    }
    const std::vector<char> in = remote_->exchange_blocks(out);
    const size_t remote = in.size() / sizeof(Row);
    std::vector<Vec<D, Real>> rx(remote), rv(remote), rX(remote);
    std::vector<Real> rmass(remote);
    std::vector<int> rgroup(remote);
    for (size_t k = 0; k < remote; ++k) {
      Row r;
      std::memcpy(static_cast<void*>(&r), in.data() + k * sizeof(Row), sizeof(Row));
      rx[k] = r.x, rv[k] = r.v, rX[k] = r.X, rmass[k] = r.mass, rgroup[k] = r.group;
    }
    count_ = local_count_ + Index(remote);
    auto tail = [&](auto& device, const auto& host) {
      device.resize(size_t(local_count_));
      std::remove_reference_t<decltype(device)> extra;
      from_host<B>(host, extra);
      device.resize(size_t(count_));
      thrust::copy(extra.begin(), extra.end(), device.begin() + local_count_);
    };
    tail(x_, rx);
    tail(v_, rv);
    tail(X_, rX);
    tail(mass_, rmass);
    tail(group_, rgroup);
    tail(ghost_, std::vector<unsigned char>(remote, 1));
    has_ghosts_ = has_ghosts_ || remote > 0;
    force_.resize(size_t(count_));
    keys_.resize(size_t(count_));
    order_.resize(size_t(count_));
  }

  // A table of at least 2 buckets per candidate (a power of two); cell edge
  // = the reach of the largest contact distance (pairs about to touch enter
  // the time-step bound).
  ContactHashGrid<D, Real> make_grid() {
    std::uint64_t buckets = 64;
    while (buckets < 2 * std::uint64_t(count_)) buckets *= 2;
    if (start_.size() < buckets) {
      start_.resize(buckets);
      end_.resize(buckets);
    }
    cells_ = size_t(buckets);
    return ContactHashGrid<D, Real>{Real(1.0 / (kContactRateReach * max_spacing_)), buckets - 1};
  }

  // x = A X + b at t + dt/2; rates from the motion over the step.
  void place_rigid_bodies(double t, double dt) {
    if (motion_.empty()) return;
    std::vector<RigidPlacement<D, Real>> host(motion_.size());
    for (size_t r = 0; r < motion_.size(); ++r) {
      auto affine = [&](double time, Mat<D, double>& A, Vec<D, double>& b) {
        const Point3 o = motion_[r].position(Point3{0, 0, 0}, time);
        for (int i = 0; i < D; ++i) b.v[i] = o[i];
        for (int j = 0; j < D; ++j) {
          Point3 e{0, 0, 0};
          e[j] = 1;
          const Point3 x = motion_[r].position(e, time);
          for (int i = 0; i < D; ++i) A.m[i][j] = x[i] - o[i];
        }
      };
      Mat<D, double> A, A0, A1;
      Vec<D, double> b, b0, b1;
      affine(t + 0.5 * dt, A, b);
      affine(t, A0, b0);
      affine(t + dt, A1, b1);
      for (int i = 0; i < D; ++i) {
        host[r].b.v[i] = Real(b.v[i]);
        host[r].b_rate.v[i] = Real((b1.v[i] - b0.v[i]) / dt);
        for (int j = 0; j < D; ++j) {
          host[r].A.m[i][j] = Real(A.m[i][j]);
          host[r].A_rate.m[i][j] = Real((A1.m[i][j] - A0.m[i][j]) / dt);
        }
      }
    }
    staging_.upload(host.data(), host.size(), raw(placement_));  // no host wait
  }

  bool enabled_ = false;
  ContactPairLaw<Real> law_{};
  double stiffness_factor_ = 1, max_spacing_ = 0, inverse_step_ = 0;
  Index particles_ = 0, count_ = 0;
  Index local_count_ = 0;            // candidates and markers of this rank (count_ adds the remote ones)
  GhostExchange* remote_ = nullptr;  // attach_remote()
  int first_rigid_group_ = 0;
  size_t cells_ = 0;
  std::vector<Span> body_spans_, rigid_spans_;
  std::vector<Index> part_begin_{0};  // part q's candidates are [part_begin_[q], part_begin_[q + 1])
  std::vector<std::string> rigid_names_;
  std::vector<RigidBodyMotion> motion_;
  std::vector<Point3> rigid_force_;
  std::vector<double> work_;
  DeviceVector<B, Index> particle_, order_, start_, end_;
  DeviceVector<B, Vec<D, Real>> marker_position_, x_, v_, X_, force_;
  DeviceVector<B, Real> mass_;
  DeviceVector<B, Real> density_;  // rho of each candidate (refresh_masses)
  DeviceVector<B, int> group_;
  DeviceVector<B, unsigned char> ghost_;  // per candidate (distributed runs)
  bool has_ghosts_ = false;
  DeviceVector<B, ContactGroup<Real>> groups_;
  DeviceVector<B, RigidPlacement<D, Real>> placement_;
  HostStaging<B> staging_;
  Pending pending_;
  DeviceVector<B, std::int64_t> keys_;
};

}  // namespace mfsd
