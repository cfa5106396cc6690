// The build without MPI (MFSD_MPI=OFF): every run is one process.
#include <cstdio>
#include <cstdlib>

#include "host/distributed/distribution.hpp"
#include "host/scene/scene_error.hpp"

namespace mfsd {

std::unique_ptr<Distribution> make_distribution() { return nullptr; }

MpiSession::MpiSession(int&, char**&) {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* v = std::getenv(name))
      if (std::atoi(v) > 1)
        throw UsageError(
            "this mfsd was built without MPI, so mpirun would start several copies of one run: build with "
            "-DMFSD_MPI=ON (scripts/test.sh --mpi installs OpenMPI)");
}
MpiSession::~MpiSession() = default;
bool MpiSession::active() { return false; }
int MpiSession::rank() { return 0; }
void MpiSession::abort(const std::string& message, int code) {
  if (!message.empty()) std::fprintf(stderr, "mfsd: %s\n", message.c_str());
  std::exit(code);
}

}  // namespace mfsd
