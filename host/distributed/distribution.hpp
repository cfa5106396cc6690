// The run driver's view of a distributed run (issue 25, docs/distributed.md):
// `mpirun -np N mfsd run SCENE` with an MPI build (MFSD_MPI=ON). Null from
// make_distribution() in a single-process run, which then is unchanged; the
// MPI implementation is distribution_mpi.cpp, the build without MPI links
// distribution_none.cpp. The driver includes no MPI header.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "host/output/snapshot.hpp"
#include "host/scene/particle_generator.hpp"
#include "host/scene/scene.hpp"
#include "host/solver/solver.hpp"

namespace mfsd {

class Distribution {
 public:
  virtual ~Distribution() = default;
  virtual int rank() const = 0;
  virtual int ranks() const = 0;
  bool root() const { return rank() == 0; }
  // SceneError where the scene uses what distributed runs lack yet.
  virtual void check(const Scene& scene) const = 0;
  // This rank's particles (owned and ghosts, body by body) out of all of them.
  virtual InitialParticles local_particles(const Scene& scene, const InitialParticles& all) = 0;
  // The solver of the local particles, its ghosts attached, in the solver
  // that makes its answers global (reductions, global ids, owned particles).
  virtual std::unique_ptr<Solver> distribute(std::unique_ptr<Solver> local) = 0;
  // Logical or of a flag over the ranks (interruptions end every rank at the same step).
  virtual bool any(bool flag) const = 0;
  virtual void barrier() const = 0;
  // Rank 0 prints the decomposition and the exchange's bytes per step.
  virtual void print_report(long steps) const = 0;
};

// Null unless this process is one of several ranks of an MPI run.
std::unique_ptr<Distribution> make_distribution();

// The process's MPI session: initialised under mpirun/mpiexec in an MPI
// build, finalised at its end. Under a launcher of several ranks without MPI
// built in, a UsageError (N copies of one run would write one folder).
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  static bool active();
  static int rank();
  // Prints `message` (prefixed by the rank) to stderr and ends every rank with `code`.
  [[noreturn]] static void abort(const std::string& message, int code);
};

}  // namespace mfsd
