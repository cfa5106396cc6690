// What a solver sees of a distributed run (issue 25, docs/distributed.md):
// which of its particles are ghosts (copies of particles other ranks own) and
// a transport that refreshes the ghosts' copies of a field from their owners.
// Particles are named by local id, their index in the InitialParticles the
// solver was made with; the solver maps ids to its own (reordered) indices.
// No MPI here: the MPI transport implements this in mpi_ghost_exchange.cpp.
#pragma once
#include <array>
#include <cstddef>
#include <vector>

#include "host/scene/particle_generator.hpp"

namespace mfsd {

class GhostExchange {
 public:
  virtual ~GhostExchange() = default;
  // Per local id: 1 where the particle is a ghost, 0 where this rank owns it.
  virtual const std::vector<unsigned char>& ghost_mask() const = 0;
  // The owned particles whose values go out, grouped by destination rank in
  // rank order, and the ghosts that receive, grouped by source rank: local ids.
  virtual const std::vector<long>& send_ids() const = 0;
  virtual const std::vector<long>& receive_ids() const = 0;
  // How many of send_ids() go to each rank, and of receive_ids() come from each.
  virtual const std::vector<int>& send_counts() const = 0;
  virtual const std::vector<int>& receive_counts() const = 0;
  // Per body: the box of its particles in the whole scene (lo[3], hi[3]), for
  // the cell grid of the reference search (the single-process run's cells).
  virtual const std::vector<double>& body_boxes() const = 0;
  // `send` holds element_bytes per particle of send_ids(), grouped by
  // destination rank as they are; `receive` gets element_bytes per particle of
  // receive_ids(), grouped by source rank (within a rank's block the layout is
  // the caller's). Collective: every rank calls it for the same fields in the
  // same order.
  virtual void exchange(const std::vector<char>& send, size_t element_bytes, std::vector<char>& receive) = 0;
  // The maxima over the ranks, element by element (the time step's statistics:
  // the step is a function of the scene's max |v|, max |a|, max |F^-1| together).
  virtual void max_over_ranks(std::vector<double>& values) = 0;
  virtual void sum_over_ranks(std::vector<double>& values) = 0;
  // Every rank's `values` (of any length), in rank order.
  virtual std::vector<std::vector<double>> gather_all(const std::vector<double>& values) = 0;
  // Collective: to_rank[q] (any length, empty: nothing) goes to rank q; the
  // blocks the other ranks sent this one come back one after the other, in
  // rank order (the contact's remote candidates, host/solver/common/contact.hpp).
  virtual std::vector<char> exchange_blocks(const std::vector<std::vector<char>>& to_rank) = 0;
  virtual int rank() const = 0;
  // A particle's index in the whole scene.
  virtual long global_id(long local_id) const = 0;

  // Migration, for methods whose particles move through the cut (ULSPH;
  // docs/distributed.md, "Migration"). Collective. In: this rank's owned
  // particles (local ids), their current positions and one record each of
  // `record_bytes` (the caller's layout). Every rank decomposes the gathered
  // positions (host/distributed/migration.hpp) and each record travels to its
  // new owner and to every rank whose halo of `radius` now holds it. Out: the
  // particles this rank now holds, grouped by the rank they came from, each
  // group in ascending global index.
  struct Arrivals {
    std::vector<long> global_id;
    std::vector<unsigned char> ghost;
    std::vector<char> records;
  };
  virtual Arrivals migrate(const std::vector<long>& owned, const std::vector<std::array<double, 3>>& position,
                           const std::vector<char>& records, size_t record_bytes, double radius) = 0;
  // The held particles' new order (their global indices; each one's position
  // is its new local id) after a migration: the exchange plan, the ghost mask
  // and the lists follow it.
  virtual void adopt(const std::vector<long>& global_id) = 0;
  // The scene's lists (conditions, clamps, probes, measure planes) over this
  // rank's owned particles, by local id (those of the set-up, or of the last
  // adopt()).
  virtual const InitialParticles& lists() const = 0;
};

}  // namespace mfsd
