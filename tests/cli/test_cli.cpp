// The mfsd binary end to end: exit codes (0 ok, 2 bad input, 3 numerical
// failure), one-line error messages naming the JSON path, no output folder
// left behind on bad input, the documented output files and their columns.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli_shell.hpp"

namespace fs = std::filesystem;

namespace {

using mfsd::test::Result;
Result run(const std::string& args) { return mfsd::test::run_mfsd(args); }

class Cli : public mfsd::test::ScratchTest {
 protected:
  // A small valid 2-D scene; `patch` edits it as JSON text replacements.
  std::string scene(const std::string& from = "", const std::string& to = "") {
    std::string s = R"({
  "name": "cli_block",
  "dimension": 2,
  "solver": {"hourglass": "genog", "end_time": 0.002},
  "bodies": [{
    "name": "block", "spacing": 0.01,
    "geometry": {"box": {"min": [0, 0], "max": [0.1, 0.05]}},
    "material": {"model": "neo_hookean", "density": 1000, "youngs_modulus": 1e6, "poisson_ratio": 0.3},
    "initial_velocity": {"x": "0", "y": "x0"}
  }],
  "clamps": [{"body": "block", "region": {"box": {"min": [0, 0], "max": [0.02, 0.05]}}}],
  "probes": [{"name": "tip", "point": [0.1, 0.025], "fields": ["position", "von_mises"]}],
  "output": {"interval": 0.001}
})";
    if (!from.empty()) {
      const auto at = s.find(from);
      EXPECT_NE(at, std::string::npos) << from;
      s.replace(at, from.size(), to);
    }
    const fs::path f = dir_ / "scene.json";
    std::ofstream(f) << s;
    return f.string();
  }
  std::string out() const { return (dir_ / "out").string(); }

  void expect_input_error(const std::string& args, const std::string& message_part) {
    const Result r = run(args);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(message_part), std::string::npos) << "message was: " << r.output;
    EXPECT_FALSE(fs::exists(out())) << "an output folder was left behind";
    // One message line (plus at most the usage hint).
    EXPECT_LE(std::count(r.output.begin(), r.output.end(), '\n'), 2) << r.output;
  }
};

}  // namespace

TEST_F(Cli, VersionAndHelp) {
  const Result v = run("--version");
  EXPECT_EQ(v.code, 0);
  EXPECT_NE(v.output.find("mfsd "), std::string::npos);
  EXPECT_NE(v.output.find("backends: cpu"), std::string::npos);
  const Result h = run("--help");
  EXPECT_EQ(h.code, 0);
  EXPECT_NE(h.output.find("mfsd run"), std::string::npos);
  EXPECT_NE(h.output.find("--set"), std::string::npos);
  EXPECT_EQ(run("frobnicate").code, 2);
  EXPECT_EQ(run("run --threads 0").code, 2);
  EXPECT_EQ(run("run --backend opencl").code, 2);
}

TEST_F(Cli, RunWritesTheDocumentedOutputs) {
  const Result r = run("run " + scene() + " -o " + out() + " --threads 2");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("particle-steps/s"), std::string::npos);
  for (const char* f : {"run.json", "timing.json", "probes.csv", "energies.csv", "snapshots.pvd"})
    EXPECT_TRUE(fs::exists(fs::path(out()) / f)) << f;
  std::ifstream probes(fs::path(out()) / "probes.csv");
  std::string header;
  std::getline(probes, header);
  EXPECT_EQ(header, "time,tip.position.x,tip.position.y,tip.von_mises");
  std::ifstream energies(fs::path(out()) / "energies.csv");
  std::getline(energies, header);
  EXPECT_EQ(header,
            "time,kinetic,strain,total,hourglass_max,hourglass_mean,external_work,boundary_work,plastic,fracture,"
            "contact_work,gravity_work,damping,relaxation,balance,momentum.x,momentum.y,block.kinetic,block.strain,"
            "block.plastic,block.fracture,"
            "block.external_work,block.boundary_work,block.contact_work,block.gravity_work,block.damping,block."
            "relaxation,block.balance,block.momentum.x,"
            "block.momentum.y");
  std::ifstream forces(fs::path(out()) / "boundary_forces.csv");
  std::getline(forces, header);
  EXPECT_EQ(header, "time,clamp0.x,clamp0.y");
  const auto timing = nlohmann::json::parse(std::ifstream(fs::path(out()) / "timing.json"));
  for (const char* k : {"particles", "steps", "wall_seconds", "particle_steps_per_second", "stages"})
    EXPECT_TRUE(timing.contains(k)) << k;
  EXPECT_EQ(timing["particles"].get<long>(), 50);
  EXPECT_GT(timing["steps"].get<long>(), 0);
  const auto runj = nlohmann::json::parse(std::ifstream(fs::path(out()) / "run.json"));
  EXPECT_EQ(runj["status"], "completed");
  EXPECT_EQ(runj["threads"], 2);
  EXPECT_EQ(runj["scene"]["solver"]["h_over_dp"], 1.15);  // defaults are resolved
  // Snapshots at t = 0, 0.001, 0.002.
  size_t vtu = 0;
  for (auto& e : fs::directory_iterator(fs::path(out()) / "snapshots")) vtu += e.path().extension() == ".vtu";
  EXPECT_EQ(vtu, 3u);
}

// --warmup-steps leaves the first steps out of the rates; the step-time
// distribution covers the timed steps only.
TEST_F(Cli, WarmupStepsAreNotTimed) {
  const Result r = run("run " + scene() + " -o " + out() + " -q --max-steps 7 --warmup-steps 3");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto timing = nlohmann::json::parse(std::ifstream(fs::path(out()) / "timing.json"));
  EXPECT_EQ(timing["steps"].get<long>(), 7);
  EXPECT_EQ(timing["warmup_steps"].get<long>(), 3);
  EXPECT_EQ(timing["timed_steps"].get<long>(), 4);
  const auto& st = timing["step_microseconds"];
  EXPECT_LE(st["min"].get<double>(), st["median"].get<double>());
  EXPECT_LE(st["median"].get<double>(), st["max"].get<double>());
  const double per_step = timing["microseconds_per_step"].get<double>();
  EXPECT_NEAR(per_step, 1e6 * timing["step_seconds"].get<double>() / 4, 1e-6 * per_step);
  EXPECT_EQ(run("run " + scene() + " -o " + out() + "_bad --warmup-steps -1").code, 2);
  EXPECT_FALSE(fs::exists(out() + "_bad"));
}

TEST_F(Cli, SetOverridesSceneValues) {
  const Result r = run("run " + scene() + " -o " + out() +
                       " -q --set solver.hourglass=laplacian --set bodies.block.material.poisson_ratio=0.4");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto runj = nlohmann::json::parse(std::ifstream(fs::path(out()) / "run.json"));
  EXPECT_EQ(runj["scene"]["solver"]["hourglass"], "laplacian");
  EXPECT_EQ(runj["scene"]["bodies"][0]["material"]["poisson_ratio"], 0.4);
  // A JSON value with commas is one value.
  fs::remove_all(out());
  const Result j = run("run " + scene() + " -o " + out() + " -q --set 'solver.gravity=[0,-9.81]'");
  ASSERT_EQ(j.code, 0) << j.output;
  const auto runk = nlohmann::json::parse(std::ifstream(fs::path(out()) / "run.json"));
  EXPECT_EQ(runk["scene"]["solver"]["gravity"][1], -9.81);
  fs::remove_all(out());
  expect_input_error("run " + scene() + " -o " + out() + " --set bodies.9.spacing=1", "--set bodies.9.spacing");
}

TEST_F(Cli, CheckPrintsTheResolvedScene) {
  const Result r = run("check " + scene());
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("body 'block': 50 particles (10 clamped)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("probe 'tip'"), std::string::npos);
}

// --recipe: the step's stages with their equations and the ghost fields a
// distributed run refreshes around them (host/solver/<method>/<method>_recipe.cpp),
// one recipe per method in a scene of two.
TEST_F(Cli, CheckPrintsTheStepRecipe) {
  const Result plain = run("check " + scene());
  EXPECT_EQ(plain.output.find("step (stages in order"), std::string::npos) << plain.output;
  const Result t = run("check " + scene() + " --recipe");
  EXPECT_EQ(t.code, 0) << t.output;
  EXPECT_NE(t.output.find("tlsph step (stages in order"), std::string::npos) << t.output;
  EXPECT_NE(t.output.find("deformation_rate"), std::string::npos) << t.output;
  EXPECT_NE(t.output.find("halo before: velocity acceleration"), std::string::npos) << t.output;
  EXPECT_NE(t.output.find("halo after: displacement deformation_gradient deformation_rate"), std::string::npos)
      << t.output;
  EXPECT_EQ(t.output.find("phase_field"), std::string::npos) << t.output;  // no fracturing body
  const Result mixed = run("check " + std::string(MFSD_SOURCE_DIR) + "/configs/colliding_rings_mixed_2d.json --recipe");
  EXPECT_EQ(mixed.code, 0) << mixed.output;
  EXPECT_NE(mixed.output.find("tlsph step"), std::string::npos) << mixed.output;
  EXPECT_NE(mixed.output.find("ulsph step"), std::string::npos) << mixed.output;
  EXPECT_NE(mixed.output.find("halo after: pressure shear_stress velocity_gradient plastic_scale failed"),
            std::string::npos)
      << mixed.output;
}

// The energy audit measures the ULSPH shear force: in a scene without a ULSPH
// body it is refused with the rest of solver.ulsph.
TEST_F(Cli, EnergyAuditNeedsAUlsphBody) {
  expect_input_error("check " + scene() + " --set solver.ulsph.energy_audit=true",
                     "/solver/ulsph: got ULSPH settings in a scene without ULSPH bodies");
}

TEST_F(Cli, MalformedJsonNamesLineAndColumn) {
  expect_input_error("run " + scene("\"dimension\": 2,", "\"dimension\": 2,,") + " -o " + out(),
                     "scene.json:3:18: invalid JSON");
}

TEST_F(Cli, UnknownKey) {
  expect_input_error("run " + scene("\"end_time\": 0.002", "\"end_time\": 0.002, \"ned_time\": 1") + " -o " + out(),
                     "/solver/ned_time: got an unknown key");
}

TEST_F(Cli, WrongType) {
  expect_input_error("run " + scene("\"spacing\": 0.01", "\"spacing\": [0.01]") + " -o " + out(),
                     "/bodies/0/spacing: got an array");
}

TEST_F(Cli, PoissonRatioOutOfRange) {
  expect_input_error("run " + scene("\"poisson_ratio\": 0.3", "\"poisson_ratio\": 0.5") + " -o " + out(),
                     "/bodies/0/material/poisson_ratio: got 0.5; expected a number in (-1, 0.5)");
}

TEST_F(Cli, BadPlasticMaterials) {
  const std::string nh = R"("model": "neo_hookean")";
  expect_input_error("run " + scene(nh, R"("model": "j2")") + " -o " + out(),
                     "/bodies/0/material/yield_stress: got nothing; expected this key (it is required)");
  expect_input_error(
      "run " + scene(nh, R"("model": "j2", "yield_stress": 2e4, "saturation_stress": 1e4, "saturation_exponent": 5)") +
          " -o " + out(),
      "/bodies/0/material/saturation_stress: got 10000.000000; expected a value >= yield_stress");
  expect_input_error("run " + scene(nh, R"("model": "j2", "yield_stress": 2e4)") + " -o " + out() +
                         " --set solver.hourglass=laplacian",
                     "the Laplacian form of seed 003 is defined for elastic bodies only");
  expect_input_error("run " +
                         scene(nh, R"("model": "j2", "yield_stress": 2e4, "hardening_modulus": 1e5, "viscosity": 10)") +
                         " -o " + out(),
                     "/bodies/0/material/viscosity: got hardening as well; expected either hardening");
  expect_input_error("run " + scene(nh, R"("model": "neo_hookean", "yield_stress": 2e4)") + " -o " + out(),
                     "/bodies/0/material/yield_stress: got an unknown key");
  expect_input_error(
      "run " + scene(nh, R"("model": "j2_mandel", "yield_stress": 2e4, "viscosity": 10)") + " -o " + out(),
      "/bodies/0/material/viscosity: got an unknown key");
  expect_input_error("run " + scene(nh, R"("model": "j2_mandel", "yield_stress": 2e4)") + " -o " + out() +
                         " --set solver.hourglass=laplacian",
                     "\"j2_mandel\" with solver.hourglass \"laplacian\"");
}

TEST_F(Cli, BadFracture) {
  const std::string nh = R"("model": "neo_hookean", "density": 1000)";
  auto with = [&](const std::string& fracture, const std::string& model = "neo_hookean") {
    return scene(nh, R"("model": ")" + model + R"(", "yield_stress": 2e4, "density": 1000, "fracture": )" + fracture);
  };
  auto fr = [&](const std::string& fracture) {
    return scene(nh, R"("model": "neo_hookean", "density": 1000, "fracture": )" + fracture);
  };
  const std::string none = " --set solver.hourglass=none -o ";
  expect_input_error("run " + fr(R"({"energy_release_rate": 3, "length_scale": 0.01})") + " -o " + out(),
                     "/solver/hourglass: got \"genog\" with fracture in body \"block\"; expected \"none\"");
  expect_input_error("run " + with(R"({"energy_release_rate": 3, "length_scale": 0.01})", "j2") + none + out(),
                     "/bodies/0/material/fracture: got fracture with the \"j2\" model; expected an elastic model");
  expect_input_error("run " + fr(R"({"energy_release_rate": 0, "length_scale": 0.01})") + none + out(),
                     "/bodies/0/material/fracture/energy_release_rate: got 0; expected a positive number");
  expect_input_error("run " + fr(R"({"energy_release_rate": 3, "length_scale": -1})") + none + out(),
                     "/bodies/0/material/fracture/length_scale: got -1; expected a positive number");
  expect_input_error("run " + fr(R"({"energy_release_rate": 3, "length_scale": 0.002})") + none + out(),
                     "/bodies/0/material/fracture/length_scale: got 0.002; expected a length scale of at least a "
                     "quarter of the body's spacing (0.0025)");
  expect_input_error(
      "run " + fr(R"({"energy_release_rate": 3, "length_scale": 0.01, "phase_field_limit": 1})") + none + out(),
      "/bodies/0/material/fracture/phase_field_limit: got 1; expected a number in [0, 1)");
  expect_input_error(
      "run " +
          fr(R"({"energy_release_rate": 3, "length_scale": 0.01, "notches": [{"points": [[0.05, 0.02], [0.05, 0.02]]}]})") +
          none + out(),
      "/bodies/0/material/fracture/notches/0/points: got a notch of zero length");
  expect_input_error(
      "run " + fr(R"({"energy_release_rate": 3, "length_scale": 0.01, "notches": [{"points": [[1, 1], [2, 1]]}]})") +
          none + out(),
      "/bodies/0/material/fracture/notches/0/points: got a notch outside body 'block'");
  expect_input_error(
      "run " + fr(R"({"energy_release_rate": 3, "length_scale": 0.01, "notches": [{"points": [[0, 0.025]]}]})") + none +
          out(),
      "/bodies/0/material/fracture/notches/0/points: got an array of 1; expected at least 2 element(s)");
  expect_input_error(
      "run " +
          fr(R"({"energy_release_rate": 3, "length_scale": 0.01, "restrict_phase_field": [{"where": "x0 <", "minimum": 0.9}]})") +
          none + out(),
      "/bodies/0/material/fracture/restrict_phase_field/0/where");
  // 3-D notches: a quadrilateral that is degenerate, off its plane or not convex.
  const std::string cube = R"({"name": "cube", "dimension": 3, "solver": {"hourglass": "none", "end_time": 1e-6},
    "bodies": [{"name": "cube", "spacing": 0.01, "geometry": {"box": {"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}},
      "material": {"model": "saint_venant_kirchhoff", "density": 1000, "youngs_modulus": 1e6, "poisson_ratio": 0.3,
        "fracture": {"energy_release_rate": 3, "length_scale": 0.01, "notches": [{"points": QUAD}]}}}]})";
  auto quad = [&](const std::string& points) {
    std::string text = cube;
    text.replace(text.find("QUAD"), 4, points);
    const fs::path f = dir_ / "cube.json";
    std::ofstream(f) << text;
    return f.string();
  };
  expect_input_error("run " + quad("[[0, 0, 0.05], [0.05, 0, 0.05], [0.1, 0, 0.05], [0.15, 0, 0.05]]") + " -o " + out(),
                     "/bodies/0/material/fracture/notches/0/points: got a degenerate quadrilateral (zero area)");
  expect_input_error("run " + quad("[[0, 0, 0.05], [0.1, 0, 0.05], [0.1, 0.1, 0.06], [0, 0.1, 0.05]]") + " -o " + out(),
                     "off the plane of the others; expected 4 corners of a planar quadrilateral");
  expect_input_error(
      "run " + quad("[[0, 0, 0.05], [0.1, 0, 0.05], [0.02, 0.02, 0.05], [0, 0.1, 0.05]]") + " -o " + out(),
      "/bodies/0/material/fracture/notches/0/points: got a quadrilateral that is not convex");
  // eps0 below the spacing is accepted with a warning.
  const Result r =
      run("check " + fr(R"({"energy_release_rate": 3, "length_scale": 0.005})") + " --set solver.hourglass=none");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: /bodies/0/material/fracture/length_scale: 0.005 is smaller than the spacing"),
            std::string::npos)
      << r.output;
}

// From the mutation fuzz of issue 19: a number beyond the double range, JSON
// nested 100,000 deep (which crashed the parser's destructor), and output
// intervals so small that the run would never end writing rows.
TEST_F(Cli, HostileInputIsAnInputError) {
  expect_input_error("run " + scene("\"end_time\": 0.002", "\"end_time\": -1e999") + " -o " + out(),
                     "invalid JSON: number overflow parsing '-1e999' (numbers must be finite doubles)");
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  expect_input_error("run " + scene("\"probes\":", "\"deep\": " + deep + ", \"probes\":") + " -o " + out(),
                     "invalid scene: arrays and objects nested deeper than 256 levels");
  expect_input_error("run " + scene() + " -o " + out() + " --set output.interval=5e-324",
                     "/output/interval: got 5e-324; expected an interval of at least end_time / 1e9 (2e-12 s)");
  expect_input_error("run " + scene() + " -o " + out() + " --set output.probe_interval=1e-300",
                     "/output/probe_interval: got 1e-300; expected an interval of at least end_time / 1e9");
}

TEST_F(Cli, BadContact) {
  const std::string probes = R"("probes":)";
  auto with = [&](const std::string& contact) { return scene(probes, "\"contact\": " + contact + ", " + probes); };
  expect_input_error("run " + with("{}") + " -o " + out(),
                     "/contact: got contact with one body and no partner; expected two bodies in contact.bodies");
  expect_input_error("run " + with(R"({"self_contact": ["plate"]})") + " -o " + out(),
                     "/contact/self_contact/0: got \"plate\"; expected the name of a body listed in contact.bodies");
  expect_input_error("run " + with(R"({"rigid_bodies": ["punch"]})") + " -o " + out(),
                     "/contact/rigid_bodies/0: got \"punch\"; expected the name of a rigid body");
  expect_input_error("run " + with(R"({"self_contact": ["block"], "restitution": 0})") + " -o " + out(),
                     "/contact/restitution: got 0; expected a restitution in (0, 1]");
  expect_input_error("run " + with(R"({"self_contact": ["block"], "friction": -0.1})") + " -o " + out(),
                     "/contact/friction: got -0.1; expected a number >= 0");
  expect_input_error("run " + with(R"({"self_contact": ["block"], "stiffnes": 2})") + " -o " + out(),
                     "/contact/stiffnes: got an unknown key");
}

TEST_F(Cli, BadRelaxation) {
  auto with = [&](const std::string& relaxation) {
    return scene("\"end_time\": 0.002", "\"end_time\": 0.002, \"relaxation\": " + relaxation);
  };
  expect_input_error("run " + with("{}") + " -o " + out(),
                     "/solver/relaxation/viscosity: got neither; expected one of viscosity (eta, Pa s) and factor");
  expect_input_error("run " + with(R"({"viscosity": 10, "factor": 1})") + " -o " + out(),
                     "/solver/relaxation/viscosity: got both viscosity and factor; expected one of viscosity");
  expect_input_error("run " + with(R"({"factor": 1, "random_ratio": 0})") + " -o " + out(),
                     "/solver/relaxation/random_ratio: got 0; expected a number in (0, 1]");
  expect_input_error("run " + with(R"({"factor": 1, "start": 0.001, "end": 0.001})") + " -o " + out(),
                     "/solver/relaxation/end: got 0.001000; expected a time after start (0.001000)");
  expect_input_error("run " + with(R"({"factor": 1, "seed": 1.5})") + " -o " + out(),
                     "/solver/relaxation/seed: got 1.500000; expected a whole number >= 0");
}

TEST_F(Cli, NonPositiveDensityAndSpacing) {
  expect_input_error("run " + scene("\"density\": 1000", "\"density\": 0") + " -o " + out(),
                     "/bodies/0/material/density: got 0; expected a positive number");
  expect_input_error("run " + scene("\"spacing\": 0.01", "\"spacing\": -0.01") + " -o " + out(),
                     "/bodies/0/spacing: got -0.01; expected a positive number");
}

TEST_F(Cli, SmoothingLengthRatioOutOfRange) {
  expect_input_error("run " + scene("\"end_time\": 0.002", "\"end_time\": 0.002, \"h_over_dp\": 3") + " -o " + out(),
                     "/solver/h_over_dp: got 3; expected a number in [1, 2]");
}

TEST_F(Cli, EmptyBody) {
  expect_input_error("run " + scene("\"spacing\": 0.01", "\"spacing\": 1.0") + " -o " + out(), "/bodies/0/geometry");
}

TEST_F(Cli, ProbeOutsideEveryBody) {
  expect_input_error("run " + scene("[0.1, 0.025]", "[0.5, 0.025]") + " -o " + out(),
                     "/probes/0/point: got [0.5, 0.025]; expected a point inside one of the bodies");
}

TEST_F(Cli, BadExpression) {
  expect_input_error("run " + scene("\"y\": \"x0\"", "\"y\": \"x0 +* 2\"") + " -o " + out(),
                     "/bodies/0/initial_velocity/y");
  expect_input_error("run " + scene("\"y\": \"x0\"", "\"y\": \"1/(x0 - 0.005)\"") + " -o " + out(), "division by zero");
}

TEST_F(Cli, UnwritableOutputFolder) {
  const fs::path blocker = dir_ / "file";
  std::ofstream(blocker) << "x";
  const Result r = run("run " + scene() + " -o " + (blocker / "out").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("output folder"), std::string::npos) << r.output;
}

TEST_F(Cli, NumericalFailureStopsWithExitCode3AndKeepsLastSnapshot) {
  // Tight bounds: the tip leaves them after a few steps.
  const std::string s =
      scene("\"output\": {\"interval\": 0.001}",
            "\"output\": {\"interval\": 0.0005}, \"bounds\": {\"min\": [-1, -1], \"max\": [1, 0.04501]}");
  const Result r = run("run " + s + " -o " + out());
  EXPECT_EQ(r.code, 3) << r.output;
  EXPECT_NE(r.output.find("position"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("of body 'block'"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(fs::path(out()) / "snapshots" / "cli_block_00000.vtu"));
  const auto runj = nlohmann::json::parse(std::ifstream(fs::path(out()) / "run.json"));
  EXPECT_EQ(runj["status"], "failed");
}

TEST_F(Cli, CudaBackendRefusedWithoutDevice) {
  const Result v = run("--version");
  if (v.output.find("cuda devices: 0") == std::string::npos && v.output.find(", cuda") != std::string::npos)
    GTEST_SKIP() << "a CUDA device is present";
  const Result r = run("run " + scene() + " -o " + out() + " --backend cuda");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--backend cuda"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out()));
}

// `mfsd decompose` (issue 25, docs/distributed.md): the plate in 4 parts,
// owned counts summing to the scene's particles, and bad input exits 2.
TEST_F(Cli, DecomposePrintsPartsAndHalos) {
  const std::string plate = std::string(MFSD_SOURCE_DIR) + "/configs/oscillating_plate_2d.json";
  const Result r = run("decompose " + plate + " --ranks 4");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("1612 particles in 4 parts"), std::string::npos) << r.output;
  long owned = 0;
  int rows = 0;
  std::istringstream in(r.output);
  std::string line;
  while (std::getline(in, line)) {
    long rank, own, ghosts;
    if (std::sscanf(line.c_str(), "%ld %ld %ld", &rank, &own, &ghosts) == 3 && line.find('[') != std::string::npos) {
      owned += own;
      ++rows;
      EXPECT_GT(ghosts, 0);
    }
  }
  EXPECT_EQ(rows, 4);
  EXPECT_EQ(owned, 1612);
  EXPECT_EQ(run("decompose " + plate).code, 2);
  EXPECT_EQ(run("decompose " + plate + " --ranks 0").code, 2);
  EXPECT_EQ(run("decompose").code, 2);
}
