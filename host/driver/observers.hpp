// The scene's observers during a run (issue 28; ObserverSpec): each output
// row interpolates the named particle fields at the observers' points
// (host/output/observer_weights.hpp) and becomes a row of observers.csv.
// Frozen observers keep the particles and weights of the reference
// configuration (the initial positions X); the others find them at the
// current positions X + u at each row. Any method whose solver shows its
// fields (Solver::fields: TLSPH, ULSPH, RKPM in one process).
#pragma once
#include <string>
#include <vector>

#include "host/output/observer_weights.hpp"
#include "host/scene/scene.hpp"
#include "host/solver/solver.hpp"

namespace mfsd {

class Observers {
 public:
  // Checks every observer's fields against the solver's (SceneError naming
  // the JSON path) and weighs the frozen ones.
  Observers(const Scene& scene, Solver& solver);
  // time, then <name>[.<point>].<field>[.<component>].
  std::vector<std::string> columns() const;
  std::vector<double> row(Solver& solver, double time) const;

 private:
  struct Observed {
    ObserverSpec spec;
    int body = -1;  // -1: every body
    double radius = 0;
    std::vector<int> components;                      // per field
    std::vector<std::vector<ObserverWeight>> frozen;  // per point (freeze)
  };
  int dim_ = 2;
  std::vector<Observed> observed_;
};

}  // namespace mfsd
