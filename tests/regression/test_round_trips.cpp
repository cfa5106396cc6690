// A step waits for the device once: every sum of the step (conditions' forces
// and work, contact's step limit and rigid-body loads, relaxation's work, the
// time-step maxima) lands in backend memory and comes to the host in one copy
// (issue 20; docs/architecture.md, "What synchronises"). The algorithms count
// their host waits the same way on every backend, so this CPU test asserts
// the count the GPU sees, for every shipped scene and every test scene.
// ULSPH adds two per neighbour rebuild (the cell grids go up, the pair count
// comes down to size the pair arrays); the test runs its scenes with
// single-criterion stepping, a rebuild every step after the first. A scene
// of both methods waits once per solver.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "host/backend/round_trips.hpp"
#include "host/scene/particle_generator.hpp"
#include "host/scene/scene_reader.hpp"
#include "host/solver/solver.hpp"

using namespace mfsd;

namespace {

// Smaller resolutions for the scenes whose default is large.
const std::map<std::string, std::vector<std::string>> kSmaller = {
    {"cantilever_plate_3d.json", {"constants.dp=0.004"}},
    {"crack_branching_2d.json", {"constants.dp=0.5e-3"}},
    {"four_point_bending_3d.json", {"constants.dp=2e-3", "constants.eps0=0.5e-3"}},
    {"kalthoff_winkler_2d.json", {"constants.dp=1e-3", "constants.eps0=0.25e-3"}},
    {"taylor_bar_3d_square.json", {"constants.H_over_dp=5"}},
    {"taylor_bar_seed001_3d.json", {"constants.R_over_dp=4"}},
    {"twisting_column_seed001_3d.json", {"constants.dp=0.25"}},
};

std::vector<std::filesystem::path> scenes() {
  std::vector<std::filesystem::path> files;
  for (const char* dir : {"/configs", "/tests/regression/scenes"})
    for (const auto& e : std::filesystem::directory_iterator(std::string(MFSD_SOURCE_DIR) + dir))
      if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

TEST(RoundTrips, OnePerStepInEveryScene) {
  const long kSteps = 6;
  int scenes_run = 0;
  for (const auto& path : scenes()) {
    SCOPED_TRACE(path.filename().string());
    const auto it = kSmaller.find(path.filename().string());
    std::vector<std::string> overrides = it == kSmaller.end() ? std::vector<std::string>{} : it->second;
    const Scene given = load_scene_file(path.string(), overrides).scene;
    const bool mixed = mixed_methods(given);
    bool ulsph = false;
    for (const BodySpec& b : given.bodies) ulsph = ulsph || b.method == Method::ulsph;
    if (ulsph) overrides.push_back("solver.ulsph.time_stepping=single");
    const SceneDocument doc = load_scene_file(path.string(), overrides);
    const InitialParticles particles = generate_particles(doc.scene);
    ASSERT_LT(particles.size(), 60000u) << "add a smaller resolution for this scene to kSmaller";
    SolverOptions o;
    o.threads = 1;
    auto solver = make_solver(doc.scene, particles, o);
    solver->initialize();
    solver->reset_timers();
    const long before = round_trips();
    for (long s = 0; s < kSteps; ++s) solver->step();
    // The process-wide count and the solver's own (timing.json's) agree.
    // A scene of both methods: one per solver (the contact between them travels with the ULSPH solver's).
    const long expected = kSteps * (mixed ? 2 : 1) + (ulsph ? 2 * (kSteps - 1) : 0);
    if (given.solver.method == Method::rkpm) {
      // RKPM rebuilds its list when the skin is used up (not every step): two
      // more per rebuild (the grids' upload, the count's scan), at most one
      // rebuild per step after the first.
      const long extra = round_trips() - before - kSteps;
      EXPECT_TRUE(extra >= 0 && extra % 2 == 0 && extra <= 2 * (kSteps - 1)) << extra;
      EXPECT_EQ(solver->timers().round_trips(), round_trips() - before);
      ++scenes_run;
      continue;
    }
    EXPECT_EQ(round_trips() - before, expected);
    EXPECT_EQ(solver->timers().round_trips(), expected);
    ++scenes_run;
  }
  EXPECT_GE(scenes_run, 20);
}
