// Resource problems are input errors found before anything is written (issue
// 19): a run whose estimated memory exceeds what mfsd may use, a scene name
// too long for the file system, checkpoint intervals below the run's
// resolution; heavy but legal outputs are accepted with a warning.
#include <filesystem>
#include <string>

#include "cli_shell.hpp"

namespace fs = std::filesystem;

namespace {

using mfsd::test::Result;
using mfsd::test::shell;

class Resources : public mfsd::test::ScratchTest {
 protected:
  // `mfsd run` exits 2 naming `part` and leaves no output folder.
  void expect_refused(const std::string& prefix, const std::string& args, const std::string& part) {
    const std::string out = (dir_ / "out").string();
    const Result r = shell(prefix + std::string(MFSD_BINARY) + " run " + args + " -q -o " + out);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(part), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out)) << "an output folder was left behind";
  }
};

const std::string kColumn = std::string(MFSD_SOURCE_DIR) + "/configs/twisting_column_3d.json";
const std::string kPlate = std::string(MFSD_SOURCE_DIR) + "/configs/oscillating_plate_2d.json";

}  // namespace

// 1,306,800 particles need about 2.7 GB (388,800 now fit: the half-pair list
// alone, issue 24 item 6); under a 1.5 GB limit the run is refused
// with the estimate, before the solver allocates anything.
TEST_F(Resources, RunTooBigForMemoryIsRefusedWithTheEstimate) {
  expect_refused("ulimit -v 1500000; ", kColumn + " --set constants.H_over_dp=60", "/bodies/0/spacing");
  expect_refused("ulimit -v 1500000; ", kColumn + " --set constants.H_over_dp=60", "GB");
}

TEST_F(Resources, SceneNameTooLongForFileNamesIsRefused) {
  expect_refused("", kPlate + " --set name=" + std::string(300, 'a'), "/name");
  expect_refused("", kPlate + " --set name=" + std::string(250, 'a'), "/name");
}

TEST_F(Resources, CheckpointIntervalBelowTheRunsResolutionIsRefused) {
  expect_refused("", kPlate + " --set output.checkpoint_interval=1e-300", "/output/checkpoint_interval");
  expect_refused("", kPlate + " --set output.checkpoint_interval=-1", "/output/checkpoint_interval");
}

TEST_F(Resources, HeavyOutputsAreAcceptedWithAWarning) {
  const Result r = shell(std::string(MFSD_BINARY) + " check " + kPlate + " --set output.interval=1e-7");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: /output/interval: the run writes about 1e+07 snapshots"), std::string::npos)
      << r.output;
}
