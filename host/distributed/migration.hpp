// Migration of particles between ranks (issue 25, docs/distributed.md,
// "Migration"): for methods whose particles move through the cut (ULSPH),
// the decomposition of the particles' current positions. The cuts stay
// (a particle's owner is found by walking the cut tree) until their
// imbalance passes a threshold; then the current positions are bisected
// again (the rebalance). The halos follow the new owners. Host-side, no MPI:
// every rank computes the same result from the gathered positions.
#pragma once
#include <cstddef>
#include <vector>

#include "host/distributed/rcb.hpp"

namespace mfsd::distributed {

// The imbalance (max count / mean) above which a migration re-cuts.
constexpr double kRebalanceThreshold = 1.10;

struct Repartition {
  Decomposition decomposition;
  std::vector<int> owner;                      // per global index
  std::vector<std::vector<std::size_t>> halo;  // per rank: its ghosts, ascending
  bool rebalanced = false;
};

// `points` by global index; `radius` the halo radius.
Repartition repartition(const Decomposition& current, const std::vector<Point>& points, double radius,
                        double threshold = kRebalanceThreshold);

// Per rank: the particles it holds after `r` (owned and ghosts), ascending.
std::vector<std::vector<long>> holdings(const Repartition& r);

// A decomposition as numbers and back (the checkpoints of a run whose
// particles migrated: its continuation keeps the same cuts).
std::vector<double> to_numbers(const Decomposition& d);
Decomposition decomposition_from(const std::vector<double>& numbers);

}  // namespace mfsd::distributed
