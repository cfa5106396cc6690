// One rank's share of a scene's particles in a distributed run (issue 25,
// docs/distributed.md): the particles it owns under the recursive coordinate
// bisection of the reference positions, then its ghosts (the other ranks'
// particles within the halo radius of its box, halo.hpp), body by body so that
// each body stays one index range, in ascending global index. The lists of conditions, clamps, probes
// and measure planes keep the owned particles only: their sums are taken once,
// on the owner. And the exchange plan: which owned particles go to which rank,
// which ghosts come from which, in the same global order on both sides, so
// that no message about the plan is needed. Host-side, no MPI: every rank
// computes every rank's plan from the same particles.
#pragma once
#include <unordered_map>
#include <vector>

#include "host/distributed/rcb.hpp"
#include "host/scene/particle_generator.hpp"

namespace mfsd::distributed {

struct LocalPart {
  InitialParticles particles;         // owned and ghost particles of each body, by global index
  std::vector<long> global_id;        // per local id: the particle's index in the whole scene
  std::vector<unsigned char> ghost;   // per local id: 1 for a ghost
  std::vector<long> send_ids;         // local ids of owned particles, grouped by destination rank
  std::vector<int> send_counts;       // per rank
  std::vector<long> receive_ids;      // local ids of ghosts, grouped by source rank
  std::vector<int> receive_counts;    // per rank
  long owned = 0;                     // particles this rank owns
  std::vector<long> probe_members;    // per probe: its owned particles here
  std::vector<long> measure_members;  // per measure plane: its owned particles here
  std::vector<double> body_boxes;     // per body: lo[3], hi[3] of all its particles
  Decomposition decomposition;
};

// The part of `all` that rank `rank` of `ranks` holds, with ghosts within
// `halo_radius` of its box.
LocalPart local_part(const InitialParticles& all, int rank, int ranks, double halo_radius);

// The lists of `all` (probes, clamps, measure planes, conditions) over the
// owned particles of a part (`local_of`: global index -> local id), by local
// id, into `p`; the probes' and planes' member counts here.
void map_lists(const InitialParticles& all, const std::unordered_map<long, long>& local_of,
               const std::vector<unsigned char>& ghost, InitialParticles& p, std::vector<long>& probe_members,
               std::vector<long>& measure_members);

}  // namespace mfsd::distributed
