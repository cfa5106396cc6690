// Bad input to an RKPM scene (issue 23 item 8): each stops before the run
// with exit 2 and the scene path of the culprit.
#include <gtest/gtest.h>

#include <string>

#include "cli_shell.hpp"

using namespace mfsd::test;

namespace {

const std::string kPlate = std::string(MFSD_SOURCE_DIR) + "/configs/oscillating_plate_rkpm_2d.json";

Result check(const std::string& sets) { return run_mfsd("run " + kPlate + " -q --max-steps 1 -o /dev/null " + sets); }

class RkpmRun : public ScratchTest {};

}  // namespace

TEST_F(RkpmRun, SupportTooSmallForTheLinearBasis) {
  // a = 1.05 dp: the face points see fewer than d + 1 = 3 kernels.
  const Result r = run_mfsd("run " + kPlate + " -q --max-steps 1 -o " + (dir_ / "out").string() +
                            " --set solver.rkpm.support_factor=1.05");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("/solver/rkpm/support_factor"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("fewer than 3 kernels"), std::string::npos) << r.output;
}

TEST(RkpmInput, MaterialsOfOtherMethods) {
  for (const char* model : {"neo_hookean", "saint_venant_kirchhoff", "j2_mandel"}) {
    const Result r = check(std::string("--set bodies.plate.material.model=") + model +
                           (std::string(model) == "j2_mandel" ? " --set bodies.plate.material.yield_stress=1e5" : ""));
    EXPECT_EQ(r.code, 2) << model << ": " << r.output;
    EXPECT_NE(r.output.find("/bodies/0/material/model"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("with solver.method \"rkpm\""), std::string::npos) << r.output;
  }
  // and RKPM's Drucker-Prager is refused by the SPH methods
  const Result r =
      run_mfsd("run " + std::string(MFSD_SOURCE_DIR) +
               "/configs/oscillating_plate_2d.json -q --max-steps 1 -o /dev/null "
               "--set bodies.plate.material.model=drucker_prager --set bodies.plate.material.cohesion=1e4");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("\"drucker_prager\" with solver.method \"tlsph\""), std::string::npos) << r.output;
}

TEST(RkpmInput, NsniCoefficientOutOfRange) {
  for (const char* value : {"-0.5", "5"}) {
    const Result r = check(std::string("--set solver.rkpm.nsni_scale=") + value);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("/solver/rkpm/nsni_scale"), std::string::npos) << r.output;
  }
}

TEST(RkpmInput, SettingsOfOtherMethods) {
  const Result h = check("--set solver.hourglass=genog");
  EXPECT_EQ(h.code, 2) << h.output;
  EXPECT_NE(h.output.find("/solver/hourglass"), std::string::npos) << h.output;
  const Result q = check("--set solver.rkpm.quasi_linear=sometimes");
  EXPECT_EQ(q.code, 2) << q.output;
  EXPECT_NE(q.output.find("/solver/rkpm/quasi_linear"), std::string::npos) << q.output;
}
