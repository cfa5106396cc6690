// Reproducers of the hostile inputs found by scripts/fuzz.py (issue 19):
// each was a crash, a hang, an "internal error" (exit 1) or a wrong number;
// each must now be an input error (exit 2) whose message names the JSON path
// (or the file with line:column), with no output folder left behind, or a
// valid scene with a sound summary.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_shell.hpp"

namespace fs = std::filesystem;

namespace {

using mfsd::test::Result;
Result run(const std::string& args, const std::string& shell_prefix = "") {
  return mfsd::test::run_mfsd(args, shell_prefix);
}

const std::string kPlate = std::string(MFSD_SOURCE_DIR) + "/configs/oscillating_plate_2d.json";

class HostileInput : public mfsd::test::ScratchTest {
 protected:
  std::string write(const std::string& text) {
    const fs::path f = dir_ / "scene.json";
    std::ofstream(f) << text;
    return f.string();
  }

  // A small valid 2-D scene (50 particles) with `clamps` as its clamps array text.
  std::string block(const std::string& clamps = "[]", const std::string& name = "block") {
    return write(R"({
  "name": ")" + name +
                 R"(",
  "dimension": 2,
  "solver": {"end_time": 0.002},
  "bodies": [{
    "name": "block", "spacing": 0.01,
    "geometry": {"box": {"min": [0, 0], "max": [0.1, 0.05]}},
    "material": {"model": "neo_hookean", "density": 1000, "youngs_modulus": 1e6, "poisson_ratio": 0.3}
  }],
  "clamps": )" + clamps +
                 R"(,
  "output": {"interval": 0.001}
})");
  }

  // The same block with `constants` as the text of its constants object.
  std::string with_constants(const std::string& constants) {
    std::string text = R"({
  "name": "block", "dimension": 2,
  "constants": {)" + constants +
                       R"(},
  "solver": {"end_time": 0.002},
  "bodies": [{
    "name": "block", "spacing": 0.01,
    "geometry": {"box": {"min": [0, 0], "max": [0.1, 0.05]}},
    "material": {"model": "neo_hookean", "density": 1000, "youngs_modulus": 1e6, "poisson_ratio": 0.3}
  }],
  "output": {"interval": 0.001}
})";
    return write(text);
  }

  std::string out() const { return (dir_ / "out").string(); }

  // `mfsd check ARGS` and `mfsd run ARGS -o OUT` are input errors naming `message_part`.
  void expect_input_error(const std::string& args, const std::string& message_part) {
    for (const std::string command : {"check ", "run "}) {
      const Result r = run(command + args + (command == "run " ? " -q --max-steps 1 -o " + out() : ""));
      EXPECT_EQ(r.code, 2) << command << args << "\n" << r.output;
      EXPECT_NE(r.output.find("mfsd: error: " + message_part), std::string::npos) << "message was: " << r.output;
      EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
      EXPECT_FALSE(fs::exists(out())) << "an output folder was left behind";
    }
  }
};

}  // namespace

// Was "internal error: expression compiler: 'bad$name' cannot be a constant name" (exit 1).
TEST_F(HostileInput, MalformedConstantNamesAreInputErrors) {
  expect_input_error(with_constants(R"j("bad$name": 1)j"),
                     "/constants/bad$name: got \"bad$name\", a character other than a letter, digit or '_' at "
                     "column 4");
  expect_input_error(with_constants(R"j("sin": 1)j"), "/constants/sin: got \"sin\", the name of a function");
  expect_input_error(with_constants(R"j("skip": 1)j"), "/constants/skip: got \"skip\", a reserved word");
  expect_input_error(with_constants(R"j("a b": 1)j"), "/constants/a b: got \"a b\", a character other");
}

// A constant or a derived body constant that is not finite. The material
// one was "internal error: expression compiler: constant 'c0' is not finite".
TEST_F(HostileInput, NonFiniteConstantsAreInputErrors) {
  expect_input_error(with_constants(R"j("a": "exp(1000)")j"),
                     "/constants/a: in expression \"exp(1000)\": column 1: non-finite result in 'exp'");
  expect_input_error(with_constants(R"j("a": 1)j") + " --set 'constants.a=\"1e308*10\"'",
                     "/constants/a: in expression \"1e308*10\"");
  expect_input_error(kPlate + " --set bodies.0.material.density=1e-300 --set bodies.0.material.youngs_modulus=1e308",
                     "/bodies/0/material: got density 1e-300, youngs_modulus 1e+308 and poisson_ratio 0.3 (c0 = inf)");
  expect_input_error(kPlate + " --set constants.dp=5e-324", "/bodies/0/spacing: got 4.94066e-324 (dp^d = 0)");
}

// A --set of a constant the scene does not define changed nothing and ran
// the default (a resolution study of constants.dpp): now an error naming the
// nearest constant. Misspelt keys elsewhere say "did you mean" too.
TEST_F(HostileInput, MisspeltNamesSayDidYouMean) {
  expect_input_error(kPlate + " --set constants.dpp=0.002",
                     "--set constants.dpp: got no constant 'dpp' in the scene (did you mean 'dp'?); expected one of "
                     "its constants: L, H, H_over_dp, dp,");
  expect_input_error(block() + " --set constants.dp=0.002",
                     "--set constants.dp: got no constant 'dp' in the scene; expected a scene with constants (this one "
                     "has none)");
  expect_input_error(kPlate + " --set solver.endtime=1",
                     "/solver/endtime: got an unknown key; did you mean 'end_time'?; expected one of:");
  expect_input_error(
      block() + " --set bodies.block.material.poison_ratio=0.3 --set bodies.block.material.poisson_ratio=null",
      "/bodies/0/material/poisson_ratio: got nothing, but 'poison_ratio', an unknown key; expected this "
      "key (it is required); did you mean 'poisson_ratio'?");
  expect_input_error(kPlate + " --set bodies.plat.spacing=0.001",
                     "--set bodies.plat.spacing: got no element 'plat' at /bodies/plat (did you mean 'plate'?)");
  // An existing constant is still set, and a valid key the file leaves out may still be given.
  const Result ok = run("check " + kPlate + " --set constants.dp=0.004 --set output.checkpoint_interval=0.5");
  EXPECT_EQ(ok.code, 0) << ok.output;
}

// An initial speed of 1.6e16 m/s (vf = tan(pi/2)) printed "about
// -9223372036854775808 steps" (llround overflow).
TEST_F(HostileInput, StepEstimateNeverOverflows) {
  const Result r = run("check " + kPlate + " --set 'constants.vf=\"tan(pi/2)\"'");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("-9223372036854775808"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("about 4.8e+20 steps"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("warning: about 4.8e+20 steps at the initial time step"), std::string::npos) << r.output;
  // The plain scene keeps whole numbers and no warning.
  const Result plain = run("check " + kPlate);
  ASSERT_EQ(plain.code, 0) << plain.output;
  EXPECT_NE(plain.output.find("about 31052 steps"), std::string::npos) << plain.output;
  EXPECT_EQ(plain.output.find("warning"), std::string::npos) << plain.output;
}

// A spacing or a geometry whose lattice no memory holds was std::bad_alloc
// (exit 1) or a hang; a box to 1e308 overflowed the cell count.
TEST_F(HostileInput, HugeLatticesAreRefusedBeforeAllocating) {
  expect_input_error(kPlate + " --set constants.dp=1e-9",
                     "/bodies/0/spacing: got 1e-09 for a bounding box of [-0.06, -0.01] to [0.2, 0.01] (2.6e+08 x "
                     "2e+07 = 5.2e+15 lattice cells); expected a spacing and a geometry that give at most 4e+09");
  expect_input_error(kPlate + " --set 'bodies.0.geometry={\"box\": {\"min\": [-1e308, 0], \"max\": [1e308, 1]}}'",
                     "/bodies/0/spacing: got 0.002 for a bounding box of [-1e+308, 0] to [1e+308, 1] (inf x 500");
  // Within the cell limit but beyond memory (2 GB of address space here):
  // refused while filling, with the estimate and what is available.
  const Result r = run("check " + kPlate + " --set constants.dp=2e-5", "ulimit -v 2000000; ");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("mfsd: error: /bodies/0/spacing: got 2e-05 ("), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("expected a scene whose particles fit in memory (2.05 GB available to mfsd)"),
            std::string::npos)
      << r.output;
}

// Legal but implausible materials in SI units run, with a warning that
// names the cost (the steel plate at 7.8 kg/m^3 takes 32x the steps).
TEST_F(HostileInput, ImplausibleMaterialsAreWarned) {
  const Result slip = run("check " + kPlate + " --set bodies.plate.material.density=7.8");
  EXPECT_EQ(slip.code, 0) << slip.output;
  EXPECT_NE(slip.output.find("warning: /bodies/0/material: density 7.8 kg/m^3 is outside what solids have in SI units "
                             "(about 25 to 23,000 kg/m^3); 7.8 looks like g/cm^3 (7800 kg/m^3). With c0 = 462 m/s the "
                             "run takes about 334964 steps, 32x what it takes at 7800 kg/m^3"),
            std::string::npos)
      << slip.output;
  const Result fast = run("check " + kPlate + " --set bodies.plate.material.youngs_modulus=2.5e11");
  EXPECT_NE(fast.output.find("c0 14433.8 m/s"), std::string::npos) << fast.output;
  EXPECT_EQ(fast.output.find("warning"), std::string::npos) << "14.4 km/s is a plausible solid's: " << fast.output;
  const Result faster = run("check " + kPlate + " --set bodies.plate.material.youngs_modulus=2.5e12");
  EXPECT_NE(faster.output.find("warning: /bodies/0/material: c0 = 45644 m/s is faster than sound in any solid"),
            std::string::npos)
      << faster.output;
  // The plate as shipped, and seed 000's muscle cube in its own units, run without one.
  EXPECT_EQ(run("check " + kPlate).output.find("warning"), std::string::npos);
  const Result muscle = run("check " + std::string(MFSD_SOURCE_DIR) + "/configs/muscle_contraction_3d.json");
  EXPECT_EQ(muscle.output.find("warning"), std::string::npos) << muscle.output;
}

// A 7 GB scene under a 4 GB address-space limit ended in "internal error:
// std::bad_alloc" (exit 1): refused with its size before it is read. The
// file is sparse (truncate), so the test writes nothing to disk.
TEST_F(HostileInput, SceneFileBeyondTheMemoryLimit) {
  const std::string big = write(std::string(100, ' '));
  fs::resize_file(big, 7000000000ULL);
  const Result r = run("check " + big, "ulimit -v 4000000; ");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("mfsd: error: " + big +
                          ": got a file of 7000000000 bytes; expected a scene file that fits "
                          "in the memory this process may use (its address space is limited to 4096000000 bytes"),
            std::string::npos)
      << r.output;
}

// 100,000 clamps, one of them nested 1,000 deep, aborted with std::bad_alloc:
// the nesting is refused before parsing, and 100,000 plain clamps work.
TEST_F(HostileInput, HundredThousandClamps) {
  const std::string clamp = R"({"body": "block", "region": {"box": {"min": [0, 0], "max": [0.02, 0.05]}}})";
  std::string deep = R"({"body": "block", "region": )";
  for (int k = 0; k < 1000; ++k) deep += R"({"union": [)";
  deep += R"({"box": {"min": [0, 0], "max": [0.02, 0.05]}})";
  for (int k = 0; k < 1000; ++k) deep += "]}";
  deep += "}";
  std::string clamps = "[" + deep;
  for (int k = 1; k < 100000; ++k) clamps += ", " + clamp;
  clamps += "]";
  const std::string scene = block(clamps);
  expect_input_error(scene, scene + ":10:1438: invalid scene: arrays and objects nested deeper than 256 levels");

  clamps = "[" + clamp;
  for (int k = 1; k < 100000; ++k) clamps += ", " + clamp;
  clamps += "]";
  const Result r = run("check " + block(clamps));
  EXPECT_EQ(r.code, 0) << r.output.substr(0, 2000);
  EXPECT_NE(r.output.find("clamp 'clamp99999' on body 'block': 0 particles"), std::string::npos);
}

// 100,000 constants took minutes to parse (each key inserted in O(keys)) and
// to evaluate (each constant compiled against all earlier ones).
TEST_F(HostileInput, ManyConstants) {
  auto scene = [&](int n) {
    std::string c = "{\"k0\": 1";
    for (int k = 1; k < n; ++k) c += ", \"k" + std::to_string(k) + "\": \"k" + std::to_string(k - 1) + " + 1\"";
    c += "}";
    std::string s = std::string(R"({"name": "many", "dimension": 2, "constants": )") + c + R"(,
  "solver": {"end_time": 0.002},
  "bodies": [{"name": "block", "spacing": 0.01, "geometry": {"box": {"min": [0, 0], "max": [0.1, "k)" +
                    std::to_string(n - 1) + R"( / 1e5"]}},
    "material": {"model": "neo_hookean", "density": 1000, "youngs_modulus": 1e6, "poisson_ratio": 0.3}}]})";
    return write(s);
  };
  const std::string big = scene(100000);
  expect_input_error(big, big + ":1:");
  const Result many = run("check " + big);
  EXPECT_NE(many.output.find("invalid scene: an object with more than 10000 keys"), std::string::npos)
      << many.output.substr(0, 500);
  // 9,000 constants, k8999 = 9000: a box 0.09 high.
  const Result r = run("check " + scene(9000));
  EXPECT_EQ(r.code, 0) << r.output.substr(0, 2000);
  EXPECT_NE(r.output.find("body 'block': 90 particles"), std::string::npos) << r.output.substr(0, 2000);
}

// A number beyond double range names its line and column.
TEST_F(HostileInput, NumberBeyondRangeNamesLineAndColumn) {
  const std::string scene = block(R"([{"body": "block", "region": {"box": {"min": [0, -1e999], "max": [1, 1]}}}])");
  expect_input_error(scene, scene + ":10:62: invalid JSON: number overflow parsing '-1e999'");
}

// Names that become file names: a 50,001-character measure plane name was
// "internal error: cannot write '.../measure_---...csv': File name too long"
// (exit 1) after the output folder was made.
TEST_F(HostileInput, NamesThatNameFilesAreChecked) {
  const std::string long_name(50001, '-');
  const std::string plane =
      R"({"name": "block", "dimension": 2, "solver": {"end_time": 0.002},
  "bodies": [{"name": "block", "spacing": 0.01, "geometry": {"box": {"min": [0, 0], "max": [0.1, 0.05]}},
    "material": {"model": "neo_hookean", "density": 1000, "youngs_modulus": 1e6, "poisson_ratio": 0.3}}],
  "measure_planes": [{"name": ")" +
      long_name + R"(", "points": [[0.05, 0], [0.05, 0.05]]}]})";
  expect_input_error(write(plane), "/measure_planes/0/name: got \"------");
  expect_input_error(block("[]", std::string(300, 'n')), "/name: got \"nnnnnn");
  expect_input_error(block("[]", ".."), "/name: got \"..\" (2 characters)");
}

// A --set value that is not UTF-8 reached run.json (written as JSON) or an
// error message (the value quoted as JSON): "internal error:
// [json.exception.type_error.316] invalid UTF-8 byte".
TEST_F(HostileInput, SetValueThatIsNotUtf8) {
  expect_input_error(block() + " --set \"description=$(printf '\\377')\"",
                     "--set \"description\": got bytes that are not UTF-8");
  expect_input_error(block() + " --set \"solver.hourglass=$(printf '\\377')\"",
                     "--set \"solver.hourglass\": got bytes that are not UTF-8");
}

// A velocity condition whose expression fails at t = 0 (here 1/0 at the
// first particle column) stopped the run's set-up with "internal error"
// (exit 1) after the output folder was made; `check` said the scene was valid.
TEST_F(HostileInput, VelocityConditionFailingAtTimeZero) {
  const std::string scene = block("[]");
  const std::string condition =
      R"x(--set 'velocity_conditions=[{"body": "block", "where": "x0 < 0.02", "y": "1/(x0 - 0.005)"}]')x";
  expect_input_error(scene + " " + condition,
                     "/velocity_conditions/0/y: expression \"1/(x0 - 0.005)\": division by zero at column 2 ('/') at "
                     "t = 0, x0 = [0.005, 0.005]");
  // Active from t = 0.001 only, it is not evaluated before the run.
  const Result later =
      run("check " + scene + " " +
          R"x(--set 'velocity_conditions=[{"body": "block", "where": "x0 < 0.02", "y": "1/(x0 - 0.005)",)x"
          R"x( "t_start": 0.001}]')x");
  EXPECT_EQ(later.code, 0) << later.output;
}
