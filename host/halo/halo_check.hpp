// Brute-force check of a distributed run's halo (issue 25): every particle of
// the scene within the support of one of this rank's owned particles (same
// body) must be held here, owned or as a ghost. Gathers every rank's owned
// positions (O(N) per rank): a test of the migration, switched on by the
// environment variable MFSD_VERIFY_HALO=1, not a production path.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "host/halo/ghost_exchange.hpp"

namespace mfsd::distributed {

// Collective. Per local particle: global index, ghost flag, body and current
// position; `support` per body. Empty when complete, else the first partner
// missing ("particle g misses partner k at distance d").
// With `across_bodies`, partners of any body count (the contact's reach,
// `support` then being per body of the owned particle).
std::string missing_partner(GhostExchange& exchange, const std::vector<long>& global,
                            const std::vector<unsigned char>& ghost, const std::vector<int>& body,
                            const std::vector<std::array<double, 3>>& x, const std::vector<double>& support, int dim,
                            bool across_bodies = false);

// Whether MFSD_VERIFY_HALO asks for the check.
bool halo_check_requested();
// MFSD_MIGRATE=0 switches migration off: the test that the check finds the
// partners a run without migration misses. Never for production runs.
bool migration_switched_off();

}  // namespace mfsd::distributed
