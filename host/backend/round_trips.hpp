// Host round trips: every operation after which the host has waited for the
// device (a result copied to the host, a blocking upload). The backend-generic
// algorithms count them the same way on every backend, so that a CPU test can
// assert the count the GPU will see (docs/architecture.md, "What synchronises").
#pragma once

namespace mfsd {

// Round trips of this process so far.
long round_trips();
// Counts one (called by the algorithms that wait).
void count_round_trip();

}  // namespace mfsd
