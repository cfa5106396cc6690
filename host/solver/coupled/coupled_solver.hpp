// A scene whose bodies use both methods (bodies[].method): one TLSPH and one
// ULSPH solver, each over its part of the scene (host/scene/method_part.hpp),
// stepped together with one dt, and the contact between the two particle
// sets. Each step: dt = the smaller of the two solvers' steps and of the
// contact's bound; both solvers advance to their contact (begin_step); the
// contact between parts acts on both at the half-step positions, like each
// solver's own contact (kernels/contact); both finish the step (end_step).
// Outputs are those of one scene: bodies, probes, measure planes and
// boundary forces in scene order, particle ids of the whole scene.
// Include after the backend header.
#pragma once
#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "host/scene/method_part.hpp"
#include "host/solver/common/particle_solver.hpp"

namespace mfsd {

template <class B, int D, class Real>
class CoupledSolver : public Solver {
 public:
  using Part = ParticleSolver<B, D, Real>;
  using PartFactory = std::unique_ptr<Part> (*)(const Scene&, const InitialParticles&, const SolverOptions&);
  static constexpr size_t kParts = 2;  // TLSPH, ULSPH
  static constexpr const char* kPrefix[kParts] = {"tlsph/", "ulsph/"};

  CoupledSolver(const Scene& scene, const InitialParticles& init, const SolverOptions& options, PartFactory tlsph,
                PartFactory ulsph)
      : scene_(scene),
        parts_{method_part(scene, init, Method::tlsph), method_part(scene, init, Method::ulsph)},
        rigid_markers_(init.rigid_markers) {
    solvers_[0] = tlsph(parts_[0].scene, parts_[0].particles, options);
    solvers_[1] = ulsph(parts_[1].scene, parts_[1].particles, options);
    for (size_t q = 0; q < kParts; ++q) {  // each solver holds its own copy of the particles
      part_size_[q] = long(parts_[q].particles.size());
      parts_[q].particles = InitialParticles{};
    }
  }

  void initialize() override {
    for (auto& s : solvers_) s->initialize();
    if (scene_.contact.enabled) {
      std::vector<ContactPartSetup<Real>> cp;
      for (size_t q = 0; q < kParts; ++q) {
        cp.push_back(solvers_[q]->contact_part());
        for (size_t& b : cp.back().scene_body) b = parts_[q].scene_body[b];
      }
      if (!cp[0].scene_body.empty() && !cp[1].scene_body.empty()) between_.setup(scene_, rigid_markers_, cp, true);
    }
    merge_timers();
  }

  void step() override {
    const long round_trips_before = round_trips();
    const double dt = next_dt();
    for (auto& s : solvers_) s->limit_next_dt(dt);
    size_t q = 0;
    try {
      for (q = 0; q < kParts; ++q) solvers_[q]->begin_step();
      if (between_.enabled()) {
        const int id = own_timers_.id("contact_between");
        clock_.start(id);
        const std::array<Kinematics<D, Real>, kParts> views{solvers_[0]->contact_view(), solvers_[1]->contact_view()};
        // Its sums travel with the last solver's (no host wait of its own).
        between_.apply(views.data(), time(), dt, solvers_[kParts - 1]->step_results());
        clock_.stop(id, own_timers_);
        clock_.collect(own_timers_);
      }
      for (q = 0; q < kParts; ++q) solvers_[q]->end_step();
      between_.collect(solvers_[kParts - 1]->step_results());
    } catch (const NumericalFailure& f) {
      // The part's particle id in the whole scene's numbering.
      const long id = f.particle_id();
      throw f.renumbered(id >= 0 && size_t(id) < parts_[q].id.size() ? parts_[q].id[size_t(id)] : id);
    }
    round_trips_ += round_trips() - round_trips_before;
    merge_timers();
  }

  void limit_next_dt(double dt_max) override {
    for (auto& s : solvers_) s->limit_next_dt(dt_max);
  }
  // The smaller of the two solvers' steps and of the contact between them
  // (its bound with the smaller CFL number, kernels/contact/contact_force.hpp).
  double next_dt() const override {
    double dt = std::min(solvers_[0]->next_dt(), solvers_[1]->next_dt());
    if (between_.inverse_stable_step() > 0)
      dt = std::min(dt, std::min(solvers_[0]->cfl(), solvers_[1]->cfl()) / between_.inverse_stable_step());
    return dt;
  }
  double time() const override { return solvers_[0]->time(); }
  long steps() const override { return solvers_[0]->steps(); }

  Snapshot snapshot() override {
    Snapshot out;
    std::array<Snapshot, kParts> s;
    for (size_t q = 0; q < kParts; ++q) s[q] = solvers_[q]->snapshot();
    std::vector<std::string> names;  // every field of either method, in first-seen order
    for (auto& one : s)
      for (auto& f : one.fields)
        if (std::find(names.begin(), names.end(), f.name) == names.end()) names.push_back(f.name);
    for (auto& name : names) out.fields.push_back({name, {}});
    for (size_t q = 0; q < kParts; ++q) {
      out.n += s[q].n;
      for (size_t i = 0; i < s[q].n; ++i) {
        out.id.push_back(parts_[q].id[size_t(s[q].id[i])]);
        out.body.push_back(int(parts_[q].scene_body[size_t(s[q].body[i])]));
      }
      out.constrained.insert(out.constrained.end(), s[q].constrained.begin(), s[q].constrained.end());
      out.position.insert(out.position.end(), s[q].position.begin(), s[q].position.end());
      out.displacement.insert(out.displacement.end(), s[q].displacement.begin(), s[q].displacement.end());
      out.velocity.insert(out.velocity.end(), s[q].velocity.begin(), s[q].velocity.end());
      // A field the other method lacks is 0 on its particles.
      for (auto& f : out.fields) {
        const std::vector<double>* v = s[q].field(f.name);
        if (v)
          f.values.insert(f.values.end(), v->begin(), v->end());
        else
          f.values.insert(f.values.end(), s[q].n, 0.0);
      }
    }
    return out;
  }

  EnergySample energies() override {
    EnergySample e;
    e.bodies.resize(scene_.bodies.size());
    double hourglass_sum = 0;
    long particles = 0;
    for (size_t q = 0; q < kParts; ++q) {
      const EnergySample s = solvers_[q]->energies();
      const long n = part_size_[q];
      e.kinetic += s.kinetic;
      e.strain += s.strain;
      for (int a = 0; a < 3; ++a) e.momentum[a] += s.momentum[a];
      e.hourglass_max = std::max(e.hourglass_max, s.hourglass_max);
      hourglass_sum += s.hourglass_mean * double(n);
      particles += n;
      e.with_fracture = e.with_fracture || s.with_fracture;
      e.with_active = e.with_active || s.with_active;
      e.with_audit = e.with_audit || s.with_audit;
      for (size_t b = 0; b < s.bodies.size(); ++b) e.bodies[parts_[q].scene_body[b]] = s.bodies[b];
    }
    e.hourglass_mean = particles ? hourglass_sum / double(particles) : 0;
    for (size_t b = 0; b < e.bodies.size(); ++b) e.bodies[b].contact_work += between_.work(b);
    return e;
  }

  // Each probe is the mean over its particles in both parts.
  std::vector<ProbeSample> probes() override {
    std::vector<ProbeSample> out(scene_.probes.size());
    std::vector<double> weight(out.size(), 0.0);
    for (auto& o : out) o.phase_field = 0;
    for (size_t q = 0; q < kParts; ++q) {
      const std::vector<ProbeSample> s = solvers_[q]->probes();
      for (size_t k = 0; k < out.size(); ++k) {
        const double n = double(parts_[q].probe_count[k]);
        if (n == 0) continue;
        for (int a = 0; a < 3; ++a) {
          out[k].position[a] += n * s[k].position[a];
          out[k].displacement[a] += n * s[k].displacement[a];
          out[k].velocity[a] += n * s[k].velocity[a];
        }
        out[k].von_mises += n * s[k].von_mises;
        out[k].jacobian += n * s[k].jacobian;
        out[k].von_mises_strain += n * s[k].von_mises_strain;
        out[k].plastic_strain += n * s[k].plastic_strain;
        out[k].phase_field += n * s[k].phase_field;
        weight[k] += n;
      }
    }
    for (size_t k = 0; k < out.size(); ++k) {
      const double w = 1.0 / weight[k];
      for (int a = 0; a < 3; ++a) {
        out[k].position[a] *= w;
        out[k].displacement[a] *= w;
        out[k].velocity[a] *= w;
      }
      out[k].von_mises *= w;
      out[k].jacobian *= w;
      out[k].von_mises_strain *= w;
      out[k].plastic_strain *= w;
      out[k].phase_field *= w;
    }
    return out;
  }

  // Clamps, conditions and loads, walls, then the rigid bodies in contact, in
  // scene order; a wall or rigid body that touches both parts sums both.
  std::vector<BoundaryForceSample> boundary_forces() override {
    std::map<std::string, Point3> sum;
    for (auto& s : solvers_)
      for (const BoundaryForceSample& f : s->boundary_forces())
        for (int a = 0; a < 3; ++a) sum[f.name][a] += f.force[a];
    std::vector<BoundaryForceSample> out;
    auto add = [&](const std::string& name) {
      Point3 f = sum.count(name) ? sum[name] : Point3{0, 0, 0};
      out.push_back({name, f});
    };
    for (auto& c : scene_.clamps) add(c.name);
    for (auto& c : scene_.conditions) add(c.name);
    for (auto& w : scene_.walls) add(w.name);
    if (scene_.contact.enabled)
      for (auto& r : scene_.contact.rigid_bodies) add(r);
    return out;
  }

  // Mean displacement and total force over each plane's particles in both parts.
  std::vector<MeasureSample> measures() override {
    std::vector<MeasureSample> out(scene_.measure_planes.size());
    std::vector<double> weight(out.size(), 0.0);
    for (size_t q = 0; q < kParts; ++q) {
      const std::vector<MeasureSample> s = solvers_[q]->measures();
      for (size_t k = 0; k < out.size(); ++k) {
        const double n = double(parts_[q].measure_count[k]);
        if (n == 0) continue;
        for (int a = 0; a < 3; ++a) {
          out[k].displacement[a] += n * s[k].displacement[a];
          out[k].force[a] += s[k].force[a];
        }
        weight[k] += n;
      }
    }
    for (size_t k = 0; k < out.size(); ++k)
      for (int a = 0; a < 3; ++a) out[k].displacement[a] /= weight[k];
    return out;
  }

  // Fracture is TLSPH's (ULSPH bodies fail by tension): its crack tips in scene order.
  std::vector<CrackTipSample> crack_tips() override { return solvers_[0]->crack_tips(); }

  const StageTimers& timers() const override { return timers_; }
  void reset_timers() override {
    for (auto& s : solvers_) s->reset_timers();
    own_timers_.reset();
    round_trips_ = 0;
    merge_timers();
  }

  SetupReport setup_report() const override {
    SetupReport r;
    r.body_particles.assign(scene_.bodies.size(), 0);
    r.min_neighbors = std::numeric_limits<long>::max();
    double bytes = 0;
    for (size_t q = 0; q < kParts; ++q) {
      const SetupReport s = solvers_[q]->setup_report();
      r.particles += s.particles;
      for (size_t b = 0; b < s.body_particles.size(); ++b)
        r.body_particles[parts_[q].scene_body[b]] = s.body_particles[b];
      r.pairs += s.pairs;
      r.min_neighbors = std::min(r.min_neighbors, s.min_neighbors);
      r.max_neighbors = std::max(r.max_neighbors, s.max_neighbors);
      r.regularized_corrections += s.regularized_corrections;
      if (s.pair_loop != "full") r.pair_loop = s.pair_loop;
      if (s.pair_layout != "csr") r.pair_layout = s.pair_layout;
      bytes += s.bytes_per_particle * double(s.particles);
    }
    r.mean_neighbors = r.particles ? double(r.pairs) / double(r.particles) : 0;
    r.bytes_per_particle = r.particles ? bytes / double(r.particles) : 0;
    return r;
  }

  // Each solver's state under its method's prefix, the contact between them at the top.
  void attach_ghosts(std::shared_ptr<GhostExchange>) override {
    throw UsageError("a scene of several methods does not run on several processes yet (docs/distributed.md)");
  }

  void save_state(StateArchive& archive) override {
    for (size_t q = 0; q < kParts; ++q) {
      StateArchive a;
      solvers_[q]->save_state(a);
      for (const auto& [name, bytes] : a.blobs()) archive.put_bytes(kPrefix[q] + name, bytes);
    }
    between_.save(archive);
  }
  void restore_state(const StateArchive& archive) override {
    for (size_t q = 0; q < kParts; ++q) {
      StateArchive a;
      const std::string prefix = kPrefix[q];
      for (const auto& [name, bytes] : archive.blobs())
        if (name.compare(0, prefix.size(), prefix) == 0) a.put_bytes(name.substr(prefix.size()), bytes);
      solvers_[q]->restore_state(a);
    }
    between_.restore(archive);
  }

 private:
  // The stages of both solvers under their method's prefix, and the contact between them.
  void merge_timers() {
    StageTimers t;
    for (size_t q = 0; q < kParts; ++q)
      for (const auto& [name, seconds] : solvers_[q]->timers().stages()) t.add(t.id(kPrefix[q] + name), seconds);
    for (const auto& [name, seconds] : own_timers_.stages()) t.add(t.id(name), seconds);
    t.add_round_trips(round_trips_);
    timers_ = t;
  }

  Scene scene_;
  std::array<MethodPart, kParts> parts_;
  std::array<long, kParts> part_size_{};  // particles of each part
  std::vector<std::vector<Point3>> rigid_markers_;
  std::array<std::unique_ptr<Part>, kParts> solvers_;
  Contact<B, D, Real> between_;
  StageClock<B> clock_;
  StageTimers own_timers_, timers_;
  long round_trips_ = 0;
};

}  // namespace mfsd
