// The solver section of a scene: method, time stepping, hourglass control,
// and the keys of each method (solver.rkpm).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"

namespace mfsd {

namespace {

// Keys of the TLSPH pipeline that have no meaning for ULSPH (refused there).
const char* const kTlsphOnlyKeys[] = {
    "kernel_correction_in_force", "correction_floor", "deformed_time_step", "zeta", "genog", "damping", "relaxation"};

// solver.method "rkpm": the keys RKPM shares with the others and solver.rkpm
// (docs/scene-reference.md; defaults from ../shared/reference/rkpm.md).
SolverSpec read_rkpm_solver(JsonNode& s, SolverSpec spec, int dim) {
  for (const char* key : kTlsphOnlyKeys)
    if (s.has(key))
      throw SceneError(s.key_path(key), "a setting of method tlsph", "no such key with solver.method \"rkpm\"");
  for (const char* key : {"ulsph", "hourglass", "sound_speed", "h_over_dp"})
    if (s.has(key))
      throw SceneError(s.key_path(key), std::string("solver.") + key + " with solver.method \"rkpm\"",
                       "no such key: RKPM needs no hourglass control and sizes its supports with "
                       "solver.rkpm.support_factor");
  spec.hourglass = HourglassControl::none;
  spec.damping_factor = 0;
  spec.sound_speed = SoundSpeed::p_wave;  // c = sqrt((lambda + 2 mu)/rho), rkpm.md 5.3
  spec.end_time = s.number("end_time", Range::positive());
  spec.cfl_given = s.has("cfl");
  // rkpm.md 5.3: CFL 0.5 with NSNI at a~ >= 1.75 (critical steps 1.0-1.3 h/c).
  spec.cfl = s.number("cfl", 0.5, Range{0.0, 1.0, true, false, "a number in (0, 1]"});
  spec.precision = s.choice("precision", {"double", "float"}, "double") == "float" ? Precision::single_precision
                                                                                   : Precision::double_precision;
  spec.reorder = s.boolean("reorder", true);
  const auto g = s.vector("gravity", size_t(dim), std::vector<double>(size_t(dim), 0.0), Range::any());
  for (int a = 0; a < dim; ++a) spec.gravity[a] = g[a];
  RkpmSpec& r = spec.rkpm;
  JsonNode k = s.object_or_empty("rkpm");
  // rkpm.md 1.2: a linear basis needs >= d + 1 covering kernels; 1.5-2.0.
  r.support_factor =
      k.number("support_factor", 2.0, Range{1.0, 3.0, true, false, "a number in (1, 3] (1.5 to 2.0 advised)"});
  r.nsni = k.choice("integration", {"nsni", "snni"}, "nsni") == "nsni";
  r.nsni_scale = k.number("nsni_scale", 1.0, Range{0.0, 4.0, false, false, "a number in [0, 4] (1: the paper's)"});
  // rkpm.md 4.5: elastic by default. The tangent lowers the footing's load
  // (12.6 c -> 8.1 c against 5.14 c) but lets the Taylor bar's plastic zone
  // lose its stabilization and blow up at 18 us (docs/theory.md).
  const std::string moduli = k.choice("nsni_moduli", {"elastic", "tangent", "consistent"}, "elastic");
  r.nsni_tangent = moduli == "tangent";
  r.nsni_consistent = moduli == "consistent";
  r.variational_correction = k.boolean("variational_correction", true);
  const std::string q = k.choice("quasi_linear", {"regularize", "shepard", "off"}, "regularize");
  r.quasi_linear = q == "regularize" ? QuasiLinear::regularize
                   : q == "shepard"  ? QuasiLinear::shepard
                                     : QuasiLinear::off;
  r.regularization =
      k.number("regularization", 1e-3, Range{0.0, 0.1, true, false, "a number in (0, 0.1] (1e-3 to 1e-2 advised)"});
  r.cells = k.choice("cells", {"mapped", "box"}, "mapped") == "mapped" ? SmoothingCells::mapped : SmoothingCells::box;
  r.box_supports = k.choice("support_shape", {"sphere", "box"}, "sphere") == "box";
  r.recell_condition = k.number("recell_condition", 10.0, Range{1.0, 1e6, true, false, "a number in (1, 1e6]"});
  r.row_sum_mass = k.choice("mass", {"row_sum", "nodal"}, "row_sum") == "row_sum";
  r.damping = k.number("damping", 0.0, Range::non_negative());
  r.skin = k.number("skin", 0.15, Range{0.0, 1.0, true, false, "a number in (0, 1] (times the spacing)"});
  r.singular_kernel =
      k.choice("essential_boundary", {"singular_kernel", "nodal"}, "singular_kernel") == "singular_kernel";
  r.nearest_time_step = k.choice("time_step", {"support", "nearest"}, "support") == "nearest";
  k.finish();
  s.finish();
  return spec;
}

}  // namespace

SolverSpec read_solver(JsonNode s, int dim) {
  SolverSpec spec;
  // solver.method; solver.formulation is its earlier name.
  if (s.has("method") && s.has("formulation"))
    throw SceneError(s.key_path("formulation"), "both method and formulation", "solver.method only");
  const std::string method = s.has("formulation") ? s.choice("formulation", {"tlsph", "ulsph", "rkpm"}, "tlsph")
                                                  : s.choice("method", {"tlsph", "ulsph", "rkpm"}, "tlsph");
  spec.method = method == "ulsph" ? Method::ulsph : method == "rkpm" ? Method::rkpm : Method::tlsph;
  if (spec.method == Method::rkpm) return read_rkpm_solver(s, spec, dim);
  if (s.has("rkpm"))
    throw SceneError(s.key_path("rkpm"), "RKPM settings with solver.method \"" + method + "\"",
                     "solver.method \"rkpm\", or no solver.rkpm");
  // solver.ulsph: the settings of the ULSPH bodies, whichever the scene's method.
  auto ulsph_hourglass = [](const std::string& hg) {
    return hg == "none" ? HourglassControl::none : (hg == "gnog" ? HourglassControl::gnog : HourglassControl::gnog_amc);
  };
  bool hourglass_in_ulsph = false;
  // (No read of `s` while `u` lives: a key added to s's resolved object may move u's.)
  if (spec.method == Method::ulsph || s.has("ulsph")) {
    const bool hourglass_in_solver = s.has("hourglass");
    JsonNode u = s.object_or_empty("ulsph");
    hourglass_in_ulsph = u.has("hourglass");
    if (spec.method == Method::ulsph && hourglass_in_solver && hourglass_in_ulsph)
      throw SceneError(u.key_path("hourglass"), "both solver.hourglass and solver.ulsph.hourglass",
                       "one of them (with solver.method \"ulsph\" they are the same setting)");
    if (spec.method != Method::ulsph || hourglass_in_ulsph)
      spec.ulsph.hourglass = ulsph_hourglass(u.choice("hourglass", {"none", "gnog", "gnog_amc"}, "gnog"));
    spec.ulsph.dual_time_stepping = u.choice("time_stepping", {"dual", "single"}, "dual") == "dual";
    spec.ulsph.advection_cfl = u.number("advection_cfl", 0.2, Range{0.0, 1.0, true, false, "a number in (0, 1]"});
    spec.ulsph.reference_speed = u.number("reference_speed", 0.0, Range::non_negative());
    spec.ulsph.refresh_pairs = u.boolean("refresh_pairs", true);
    spec.ulsph.remove_plastic_rate = u.choice("j2_return", {"radial", "seed"}, "radial") == "seed";
    if (u.has("xi")) spec.ulsph.xi = u.number("xi", Range::positive());
    spec.ulsph.riemann_limiter = u.number("riemann_limiter", 0.0, Range::non_negative());
    spec.ulsph.energy_audit = u.boolean("energy_audit", false);
    u.finish();
  }
  if (spec.method == Method::ulsph && !hourglass_in_ulsph)
    spec.ulsph.hourglass = ulsph_hourglass(s.choice("hourglass", {"none", "gnog", "gnog_amc"}, "gnog"));
  if (spec.method == Method::ulsph) {
    for (const char* key : kTlsphOnlyKeys)
      if (s.has(key))
        throw SceneError(s.key_path(key), "a setting of method tlsph",
                         "no such key with solver.method \"ulsph\" (docs/scene-reference.md lists each method's keys; "
                         "for TLSPH settings in a scene of both methods, make tlsph the scene's method and give the "
                         "ULSPH bodies bodies[].method \"ulsph\")");
    spec.hourglass = spec.ulsph.hourglass;
    spec.damping_factor = 0;  // ULSPH dissipates through its Riemann solver (seed 002 eq. 15-17)
  } else {
    const std::string hg = s.choice("hourglass", {"none", "laplacian", "genog"}, "genog");
    spec.hourglass = hg == "none" ? HourglassControl::none
                                  : (hg == "laplacian" ? HourglassControl::laplacian : HourglassControl::genog);
  }
  spec.end_time = s.number("end_time", Range::positive());
  spec.h_over_dp = s.number("h_over_dp", 1.15, Range{1.0, 2.0, false, false, "a number in [1, 2]"});
  // The acoustic CFL number in both methods: h/(c0 + |v|max) (seed 000 eq. 38, seed 002 eq. 29).
  spec.cfl_given = s.has("cfl");
  spec.cfl =
      s.number("cfl", spec.method == Method::ulsph ? 0.4 : 0.6, Range{0.0, 1.0, true, false, "a number in (0, 1]"});
  spec.precision = s.choice("precision", {"double", "float"}, "double") == "float" ? Precision::single_precision
                                                                                   : Precision::double_precision;
  spec.sound_speed =
      s.choice("sound_speed", {"bulk", "p_wave"}, "bulk") == "bulk" ? SoundSpeed::bulk : SoundSpeed::p_wave;
  // B0 in the force sums: the papers' eq. 20/32 for none and genog. For
  // laplacian the Laplacian shear sum has no B0, so B0 in the remaining-stress
  // sum leaves surface particles out of equilibrium at rest (docs/theory.md);
  // the default there is the authors' code (B0 only in dF/dt).
  spec.correction_in_force = s.boolean("kernel_correction_in_force", spec.hourglass != HourglassControl::laplacian);
  spec.correction_floor = s.number("correction_floor", 0.1, Range{0.0, 1.0, true, false, "a number in (0, 1]"});
  spec.reorder = s.boolean("reorder", true);
  if (s.has("deformed_time_step")) {
    spec.deformed_time_step = s.boolean("deformed_time_step", false);
    spec.deformed_time_step_given = true;
  }
  spec.zeta = s.number("zeta", 1.07, Range::positive());
  {
    JsonNode g = s.object_or_empty("genog");
    spec.genog_alpha = g.number("alpha", 8.0, Range::positive());
    spec.genog_limiter = g.choice("limiter", {"paper", "capped"}, "paper") == "paper" ? GenogLimiterChoice::paper
                                                                                      : GenogLimiterChoice::capped;
    spec.genog_form = g.choice("form", {"vector", "dyadic"}, "vector") == "vector" ? GenogFormChoice::vector
                                                                                   : GenogFormChoice::dyadic;
    g.finish();
  }
  {
    JsonNode d = s.object_or_empty("damping");
    spec.damping_factor = d.number("factor", 1.0, Range::non_negative());
    spec.damping_form = d.choice("form", {"isotropic", "split"}, "isotropic") == "isotropic" ? DampingForm::isotropic
                                                                                             : DampingForm::split;
    d.finish();
  }
  if (s.has("relaxation")) {
    JsonNode r = s.object_or_empty("relaxation");
    spec.relaxation.enabled = r.boolean("enabled", true);
    if (r.has("viscosity") == r.has("factor"))
      throw SceneError(r.key_path("viscosity"), r.has("factor") ? "both viscosity and factor" : "neither",
                       "one of viscosity (eta, Pa s) and factor (eta = factor p rho0 c0 h / CFL)");
    if (r.has("viscosity")) spec.relaxation.viscosity = r.number("viscosity", Range::positive());
    if (r.has("factor")) spec.relaxation.factor = r.number("factor", Range::positive());
    spec.relaxation.random_ratio = r.number("random_ratio", 0.2, Range{0.0, 1.0, true, false, "a number in (0, 1]"});
    const double seed = r.number("seed", 1.0, Range::non_negative());
    if (seed != std::floor(seed) || seed > 9.0e15)
      throw SceneError(r.key_path("seed"), std::to_string(seed), "a whole number >= 0");
    spec.relaxation.seed = (unsigned long long)seed;
    spec.relaxation.t_start = r.number("start", 0.0, Range::non_negative());
    spec.relaxation.t_end = r.number("end", 1e300, Range::positive());
    if (spec.relaxation.t_end <= spec.relaxation.t_start)
      throw SceneError(r.key_path("end"), std::to_string(spec.relaxation.t_end),
                       "a time after start (" + std::to_string(spec.relaxation.t_start) + ")");
    r.finish();
  }
  const auto g = s.vector("gravity", size_t(dim), std::vector<double>(size_t(dim), 0.0), Range::any());
  for (int k = 0; k < dim; ++k) spec.gravity[k] = g[k];
  s.finish();
  return spec;
}

}  // namespace mfsd
