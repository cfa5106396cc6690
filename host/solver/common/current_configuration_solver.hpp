// What the current-configuration methods (ULSPH, RKPM) share beyond the
// particle platform (particle_solver.hpp), written once: the list searched
// in the current positions (cells, rows, the bodies' searches) and its
// rebuild flag, the field accessors, and the distributed bookkeeping of
// particles that move through the cut (docs/distributed.md, "Migration"):
// a search migrates first when the travel since the last migration may
// have taken a partner past the ghosts, and with contact every step checks
// (MFSD_VERIFY_HALO=1) that the contact's partners are held. A method
// gives its recipe and its stages (forces, advance, finish_step), when a
// migration is due and its radius. Include after the backend header.
#pragma once
#include <string>
#include <vector>

#include "host/halo/halo_check.hpp"
#include "host/neighbors/cell_list_search.hpp"
#include "host/solver/common/particle_solver.hpp"

namespace mfsd {

template <class B, int D, class Real>
class CurrentConfigurationSolver : public ParticleSolver<B, D, Real> {
  using Base = ParticleSolver<B, D, Real>;

 public:
  using Base::Base;

 protected:
  bool ghosts_supported() const override { return true; }
  bool ghosts_are_current_neighbours() const override { return true; }

  // Distributed runs: the particles go to the ranks whose regions hold them
  // now, before a search whose rows may reach past the ghosts.
  void migrate_if_due() {
    if (!rebuild_due_ || !this->ghosts_ || distributed::migration_switched_off() || !migration_due()) return;
    this->run("migrate", [&] { this->migrate_particles(migration_radius()); });
    migration_travelled_ = 0;
  }
  // Whether the travel since the last migration (migration_travelled_, the
  // sum of dt max|v|) may have taken a partner past the ghosts, and the
  // halo radius of the next migration.
  virtual bool migration_due() = 0;
  virtual double migration_radius() = 0;

  // MFSD_VERIFY_HALO=1 with contact: at every step, every particle of any
  // body within the contact's reach of an owned particle is held here (the
  // contact searches its pairs at every step, at positions x = X + u moved
  // since the last search).
  void before_contact() override {
    if (!this->ghosts_ || !distributed::halo_check_requested()) return;
    double spacing = 0;
    for (const auto& b : this->scene_.bodies) spacing = std::max(spacing, b.spacing);
    auto x = to_host<B>(this->particles_.template buffer<Vec<D, Real>>(field::reference_position));
    const auto u = to_host<B>(this->particles_.template buffer<Vec<D, Real>>(field::displacement));
    for (size_t i = 0; i < x.size(); ++i) x[i] = x[i] + u[i];
    Base::verify_halo(x, std::vector<double>(this->scene_.bodies.size(), kContactRateReach * spacing), true);
  }

  // After a migration: the searches' ranges, what the method keeps by index
  // (migrated()), and the contact's candidates (every particle of a body in
  // contact: its surface moves).
  void after_migration() override {
    for (size_t b = 0; b < search_.size(); ++b) search_[b].range = this->ranges_[b];
    migrated();
    if (this->scene_.contact.enabled)
      this->setup_contact_again(std::vector<unsigned char>(size_t(this->particles_.size()), 1));
  }
  virtual void migrated() {}

  Real* real(const char* name) { return this->particles_.template get<Real>(name); }
  Mat<D, Real>* mat(const char* name) { return this->particles_.template get<Mat<D, Real>>(name); }
  Vec<D, Real>* velocity() { return this->particles_.template get<Vec<D, Real>>(field::velocity); }
  Vec<D, Real>* acceleration() { return this->particles_.template get<Vec<D, Real>>(field::acceleration); }
  Vec<D, Real>* displacement() { return this->particles_.template get<Vec<D, Real>>(field::displacement); }
  const Vec<D, Real>* reference() { return this->particles_.template get<Vec<D, Real>>(field::reference_position); }

  std::vector<BodySearch> search_;  // per body: its range and search radius
  CellIndex<B, D, Real> cells_;
  DeviceVector<B, Index> count_;
  DeviceVector<B, PairIndex> offsets_;
  DeviceVector<B, Index> neighbor_;
  PairIndex pairs_ = 0;
  bool rebuild_due_ = false;        // the next step searches
  std::vector<double> body_total_;  // particles of each body in the whole scene (distributed runs: all ranks')
  double migration_travelled_ = 0;  // distributed runs: sum dt |v|max since the last migration
  std::vector<double> gravity_at_start_;
};

}  // namespace mfsd
