// The distributed engine's point-to-point exchange of byte blocks (issue 25):
// `to_rank[q]` goes to rank q (this rank's own entry is not sent); returns
// what the other ranks sent here, concatenated in rank order. Collective.
// The migrations and the contact's remote candidates of a distributed run
// travel through it (distribution_mpi.cpp, common/contact.hpp), and so does
// the MPI loopback test (tests/mpi/test_halo_exchange.cpp). Defined in MPI
// builds only.
#pragma once
#include <vector>

namespace mfsd::distributed {

// `bytes_sent` (optional) grows by the bytes this rank sent.
std::vector<char> exchange_blocks(const std::vector<std::vector<char>>& to_rank, double* bytes_sent = nullptr);

}  // namespace mfsd::distributed
