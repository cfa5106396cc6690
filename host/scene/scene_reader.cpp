#include "host/scene/scene_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

#include "host/expr/expression_error.hpp"
#include "host/expr/program.hpp"
#include "host/scene/body_properties.hpp"
#include "host/scene/scene_error.hpp"

namespace mfsd {

namespace {

// Names a scene constant may not take: expression variables and the
// per-body constants that body expressions receive.
const std::set<std::string> kReservedNames = {"x0", "y0", "z0", "x",  "y",  "z",  "ux", "uy", "uz",   "vx",
                                              "vy", "vz", "t",  "dt", "dx", "pi", "c0", "cs", "rho0", "h"};

// The entries of `constants` whose names occur in `text` as words.
std::map<std::string, double> named_constants(const std::string& text, const std::map<std::string, double>& constants) {
  std::map<std::string, double> named;
  auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (size_t k = 0; k < text.size();) {
    if (!word(text[k])) {
      ++k;
      continue;
    }
    size_t end = k;
    while (end < text.size() && word(text[end])) ++end;
    const auto it = constants.find(text.substr(k, end - k));
    if (it != constants.end()) named.insert(*it);
    k = end;
  }
  return named;
}

void line_column(const std::string& text, size_t byte, size_t& line, size_t& column) {
  line = 1;
  column = 1;
  for (size_t k = 0; k < byte && k < text.size(); ++k) {
    if (text[k] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
}

// A direction given per body (numbers) or per particle (expressions of x0 y0 z0).
std::array<std::string, 3> read_direction(JsonNode& m, const std::string& key, int dim) {
  std::array<std::string, 3> out{"", "", ""};
  auto node = m.optional_object(key);
  if (!node) return out;
  const char* axes[3] = {"x", "y", "z"};
  for (int a = 0; a < dim; ++a) out[size_t(a)] = node->expression(axes[a], "0");
  node->finish();
  return out;
}

// Holzapfel-Ogden (seed 000 eq. 12-19): a, b > 0; the anisotropic a_i, b_i >= 0
// (seed 000 Table 3 sets b_f = 0, and a_f = a_s = a_fs = 0 for the isotropic
// body); lambda from bulk_modulus (K = lambda + 2a/3) or poisson_ratio
// (lambda = 2 a nu / (1 - 2 nu), a the shear modulus, as seed 000 section 5.2).
void read_holzapfel_ogden(JsonNode& m, MaterialSpec& spec, int dim) {
  HolzapfelOgdenSpec& h = spec.holzapfel_ogden;
  h.a = m.number("a", Range::positive());
  h.b = m.number("b", Range::positive());
  h.af = m.number("a_f", 0.0, Range::non_negative());
  h.bf = m.number("b_f", 0.0, Range::non_negative());
  h.as = m.number("a_s", 0.0, Range::non_negative());
  h.bs = m.number("b_s", 0.0, Range::non_negative());
  h.afs = m.number("a_fs", 0.0, Range::non_negative());
  h.bfs = m.number("b_fs", 0.0, Range::non_negative());
  if (m.has("bulk_modulus") == m.has("poisson_ratio"))
    throw SceneError(
        m.path(),
        m.has("bulk_modulus") ? "both bulk_modulus and poisson_ratio" : "neither bulk_modulus nor poisson_ratio",
        "one of them: bulk_modulus K (lambda = K - 2a/3) or poisson_ratio nu (lambda = 2 a nu / (1 - 2 nu))");
  if (m.has("bulk_modulus")) {
    const double K = m.number("bulk_modulus", Range::positive());
    h.lambda = K - 2.0 * h.a / 3.0;
    if (!(h.lambda > 0))
      throw SceneError(m.key_path("bulk_modulus"), std::to_string(K),
                       "a bulk modulus > 2a/3 = " + std::to_string(2.0 * h.a / 3.0) + " (lambda = K - 2a/3 > 0)");
  } else {
    const double nu = m.number("poisson_ratio", Range{0.0, 0.5, true, true, "a number in (0, 0.5)"});
    h.lambda = 2.0 * h.a * nu / (1.0 - 2.0 * nu);
  }
  // E and nu of the small-strain shear modulus a and bulk modulus lambda + 2a/3
  // (expression constants E nu K G, reports).
  const double G = h.a, K = h.lambda + 2.0 * G / 3.0;
  spec.poisson_ratio = (3 * K - 2 * G) / (2 * (3 * K + G));
  spec.youngs_modulus = 2 * G * (1 + spec.poisson_ratio);
  h.fibre = read_direction(m, "fibre", dim);
  h.sheet = read_direction(m, "sheet", dim);
  if (auto act = m.optional_object("active_stress")) {
    h.active.enabled = true;
    h.active.potential = act->expression("potential", "");
    if (h.active.potential.empty())
      throw SceneError(act->key_path("potential"), "nothing",
                       "the transmembrane potential V_m, an expression of x0 y0 z0");
    h.active.tension_per_potential = act->number("tension_per_potential", Range::any());
    h.active.ramp_time = act->number("ramp_time", 0.0, Range::non_negative());
    act->finish();
  }
  const bool needs_fibre = h.af > 0 || h.afs > 0 || h.active.enabled, needs_sheet = h.as > 0 || h.afs > 0;
  if (needs_fibre && h.fibre[0].empty())
    throw SceneError(m.key_path("fibre"), "nothing",
                     "the fibre direction f0 {\"x\": .., \"y\": ..}: numbers, or expressions of x0 y0 z0 "
                     "(a_f, a_fs or active_stress act along it)");
  if (needs_sheet && h.sheet[0].empty())
    throw SceneError(
        m.key_path("sheet"), "nothing",
        "the sheet direction s0 {\"x\": .., \"y\": ..}, orthogonal to the fibre (a_s or a_fs act along it)");
}

MaterialSpec read_material(JsonNode m, double spacing, int dim, std::vector<std::string>& warnings) {
  MaterialSpec spec;
  const std::string model = m.choice("model", {"neo_hookean", "saint_venant_kirchhoff", "j2", "j2_mandel",
                                               "holzapfel_ogden", "linear_elastic", "drucker_prager"});
  spec.model = model == "neo_hookean"       ? MaterialModel::neo_hookean
               : model == "linear_elastic"  ? MaterialModel::linear_elastic
               : model == "j2"              ? MaterialModel::j2
               : model == "j2_mandel"       ? MaterialModel::j2_mandel
               : model == "drucker_prager"  ? MaterialModel::drucker_prager
               : model == "holzapfel_ogden" ? MaterialModel::holzapfel_ogden
                                            : MaterialModel::saint_venant_kirchhoff;
  spec.density = m.number("density", Range::positive());
  if (spec.model == MaterialModel::holzapfel_ogden) {
    read_holzapfel_ogden(m, spec, dim);
    m.finish();  // no fracture or plasticity with this model
    return spec;
  }
  spec.youngs_modulus = m.number("youngs_modulus", Range::positive());
  spec.poisson_ratio = m.number("poisson_ratio", Range{-1.0, 0.5, true, true, "a number in (-1, 0.5)"});
  if (auto f = m.optional_object("fracture")) spec.fracture = read_fracture(*f, spec, spacing, dim, warnings);
  // Tension failure of ULSPH bodies (seed 002 section 5.9): -p above it fails a particle.
  spec.failure_pressure = m.number("failure_pressure", 0.0, Range::non_negative());
  if (spec.model == MaterialModel::drucker_prager) {
    DruckerPragerSpec& d = spec.drucker_prager;
    d.cohesion = m.number("cohesion", Range::positive());
    d.friction_angle = m.number("friction_angle", 0.0, Range{0.0, 60.0, false, true, "an angle in [0, 60) degrees"});
    d.dilation_angle = m.number("dilation_angle", d.friction_angle,
                                Range{0.0, d.friction_angle, false, false, "an angle in [0, friction_angle] degrees"});
    d.tension_cutoff = m.number("tension_cutoff", 0.0, Range::non_negative());
    const std::string match =
        m.choice("cone_match", {"plane_strain", "outer", "inner"}, dim == 2 ? "plane_strain" : "outer");
    d.match = match == "plane_strain" ? ConeMatch::plane_strain
              : match == "outer"      ? ConeMatch::outer
                                      : ConeMatch::inner;
    m.finish();
    return spec;
  }
  if (spec.model == MaterialModel::j2) {
    if (auto d = m.optional_object("damage")) {
      DamageSpec& g = spec.damage;
      const std::string law = d->choice("law", {"linear", "exponential", "johnson_cook"});
      g.law = law == "linear"        ? DamageModel::linear
              : law == "exponential" ? DamageModel::exponential
                                     : DamageModel::johnson_cook;
      if (g.law != DamageModel::johnson_cook) g.onset_strain = d->number("onset_strain", 0.0, Range::non_negative());
      if (g.law == DamageModel::linear) {
        g.failure_strain = d->number("failure_strain", Range::positive());
        if (g.failure_strain <= g.onset_strain)
          throw SceneError(d->key_path("failure_strain"), std::to_string(g.failure_strain),
                           "a strain above onset_strain (" + std::to_string(g.onset_strain) + ")");
      }
      if (g.law == DamageModel::exponential) g.decay_strain = d->number("decay_strain", Range::positive());
      if (g.law == DamageModel::johnson_cook) {
        g.d1 = d->number("d1", Range::any());
        g.d2 = d->number("d2", 0.0, Range::any());
        g.d3 = d->number("d3", 0.0, Range::any());
        g.d4 = d->number("d4", 0.0, Range::any());
        g.reference_rate = d->number("reference_rate", 1.0, Range::positive());
      }
      d->finish();
    }
  }
  if (spec.plastic()) {
    spec.yield_stress = m.number("yield_stress", Range::positive());
    spec.hardening_modulus = m.number("hardening_modulus", 0.0, Range::non_negative());
    if (spec.model == MaterialModel::j2_mandel) {
      m.finish();  // linear hardening only (seed 001): other keys are errors
      return spec;
    }
    if (m.has("saturation_stress") || m.has("saturation_exponent")) {
      spec.hardening = HardeningLaw::saturation;
      spec.saturation_stress = m.number("saturation_stress", Range::positive());
      spec.saturation_exponent = m.number("saturation_exponent", Range::positive());
      if (spec.saturation_stress < spec.yield_stress)
        throw SceneError(
            m.key_path("saturation_stress"), std::to_string(spec.saturation_stress),
            "a value >= yield_stress (" + std::to_string(spec.yield_stress) + "): the saturation law would soften");
    }
    if (m.has("viscosity") || m.has("flow_exponent")) {
      if (spec.hardening != HardeningLaw::linear || spec.hardening_modulus != 0)
        throw SceneError(m.key_path("viscosity"), "hardening as well",
                         "either hardening (hardening_modulus, saturation_*) or Herschel-Bulkley viscoplastic flow "
                         "(viscosity, flow_exponent), not both");
      spec.hardening = HardeningLaw::herschel_bulkley;
      spec.viscosity = m.number("viscosity", Range::positive());
      spec.flow_exponent = m.number("flow_exponent", 1.0, Range::positive());
    }
  }
  m.finish();
  return spec;
}

// Each number in range can still give an infinite or zero derived quantity
// (E = 1e308 with rho0 = 1e-300: c0 = inf), which expressions and the time
// step would meet later.
void check_body_properties(const BodySpec& body, const SolverSpec& solver, int dim, const std::string& path) {
  const BodyProperties p = body_properties(body, solver, dim);
  const std::pair<const char*, double> material[] = {{"K", p.K}, {"G", p.G}, {"c0", p.c0}, {"cs", p.c_shear}};
  for (const auto& [name, value] : material)
    if (!std::isfinite(value) || !(value > 0)) {
      std::ostringstream got;
      got << "density " << body.material.density << ", youngs_modulus " << body.material.youngs_modulus
          << " and poisson_ratio " << body.material.poisson_ratio << " (" << name << " = " << value << ")";
      throw SceneError(path + "/material", got.str(), "a material whose moduli and sound speeds are finite and > 0");
    }
  const std::pair<const char*, double> lattice[] = {{"h", p.h}, {"dp^d", p.volume}, {"rho0 dp^d", p.mass}};
  for (const auto& [name, value] : lattice)
    if (!std::isfinite(value) || !(value > 0)) {
      std::ostringstream got;
      got << body.spacing << " (" << name << " = " << value << ")";
      throw SceneError(path + "/spacing", got.str(), "a spacing whose particle volume and mass are finite and > 0");
    }
}

// Each method's materials: ULSPH has the hypo-elastic solid and J2 with
// linear hardening (seed 002), TLSPH the hyperelastic models and its J2
// family; neither takes the other's.
void check_method_material(const BodySpec& body, const SolverSpec& solver, const std::string& path) {
  const MaterialSpec& m = body.material;
  if (m.damage.law != DamageModel::none && solver.method != Method::rkpm)
    throw SceneError(path + "/damage", std::string("damage with solver.method \"") + to_string(solver.method) + "\"",
                     "solver.method \"rkpm\" (SPH bodies fail by phase-field fracture or tension failure)");
  if (solver.method == Method::rkpm) {
    // RKPM's stress update is hypo-elastic (Hughes-Winget, seed 004 eq. 25-26).
    const bool ok = m.model == MaterialModel::linear_elastic || m.model == MaterialModel::drucker_prager ||
                    (m.model == MaterialModel::j2 && m.hardening == HardeningLaw::linear);
    if (!ok)
      throw SceneError(path + "/model", std::string("\"") + to_string(m.model) + "\" with solver.method \"rkpm\"",
                       "\"linear_elastic\", \"j2\" with linear hardening or \"drucker_prager\" (the hypo-elastic "
                       "laws of seed 004 section 7; hyperelastic models need solver.method \"tlsph\")");
    if (m.fracture.enabled)
      throw SceneError(path + "/fracture", "phase-field fracture with solver.method \"rkpm\"",
                       "solver.method \"tlsph\"");
    if (m.failure_pressure > 0)
      throw SceneError(path + "/failure_pressure", "tension failure with solver.method \"rkpm\"",
                       "solver.method \"ulsph\"");
  } else if (solver.method == Method::ulsph) {
    const bool ok = m.model == MaterialModel::linear_elastic ||
                    (m.model == MaterialModel::j2 && m.hardening == HardeningLaw::linear);
    if (!ok)
      throw SceneError(path + "/model", std::string("\"") + to_string(m.model) + "\" with solver.method \"ulsph\"",
                       "\"linear_elastic\" or \"j2\" with linear hardening (seed 002)");
    if (m.fracture.enabled)
      throw SceneError(path + "/fracture", "phase-field fracture with solver.method \"ulsph\"",
                       "solver.method \"tlsph\" (ULSPH bodies fail by tension: material.failure_pressure)");
  } else {
    if (m.model == MaterialModel::drucker_prager)
      throw SceneError(path + "/model", "\"drucker_prager\" with solver.method \"tlsph\"", "solver.method \"rkpm\"");
    if (m.model == MaterialModel::linear_elastic)
      throw SceneError(path + "/model", "\"linear_elastic\" with solver.method \"tlsph\"",
                       "a hyperelastic model (neo_hookean, saint_venant_kirchhoff, ...), or solver.method \"ulsph\" "
                       "or \"rkpm\"");
    if (m.failure_pressure > 0)
      throw SceneError(path + "/failure_pressure", "tension failure with solver.method \"tlsph\"",
                       "solver.method \"ulsph\" (TLSPH bodies break by phase-field fracture)");
  }
}

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

}  // namespace

namespace {
// Arrays and objects nested deeper than this are refused before parsing: a
// parsed document is destroyed recursively, and a scene never needs it.
constexpr int kMaxJsonDepth = 256;
// Objects with more keys than this too: the parser's ordered objects insert
// a key in O(keys) (100,000 constants took minutes).
constexpr long kMaxObjectKeys = 10000;

// Throws a SceneError at the first bracket nested deeper than kMaxJsonDepth,
// or at the key beyond kMaxObjectKeys of an object (brackets and commas
// inside strings do not count).
// Scans JSON text one character at a time: inside() is true for the
// characters of a string literal, its quotes included.
struct JsonStrings {
  bool in_string = false, escaped = false;
  bool inside(char c) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
      return true;
    }
    if (c == '"') in_string = true;
    return in_string;
  }
};

void check_json_depth(const std::string& text, const std::string& source_name) {
  int depth = 0;
  JsonStrings strings;
  std::vector<long> keys;  // per open bracket: commas so far in an object, -1 in an array
  auto fail = [&](size_t k, const std::string& what) {
    size_t line, column;
    line_column(text, k, line, column);
    throw SceneError(source_name + ":" + std::to_string(line) + ":" + std::to_string(column) +
                     ": invalid scene: " + what);
  };
  for (size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (strings.inside(c)) continue;
    if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        fail(k, "arrays and objects nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
      keys.push_back(c == '{' ? 0 : -1);
    }
    if (c == ',' && !keys.empty() && keys.back() >= 0 && ++keys.back() >= kMaxObjectKeys)
      fail(k, "an object with more than " + std::to_string(kMaxObjectKeys) + " keys");
    if (c == ']' || c == '}') {
      --depth;
      if (!keys.empty()) keys.pop_back();
    }
  }
}
}  // namespace

// The first occurrence of `token` outside JSON strings that is a whole token
// (not part of a longer number or name); npos when there is none.
size_t find_outside_strings(const std::string& text, const std::string& token) {
  if (token.empty()) return std::string::npos;
  auto part = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+'; };
  JsonStrings strings;
  for (size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (strings.inside(c)) continue;
    if (text.compare(k, token.size(), token) == 0 && (k == 0 || !part(text[k - 1])) &&
        (k + token.size() >= text.size() || !part(text[k + token.size()])))
      return k;
  }
  return std::string::npos;
}

Json parse_scene_json(const std::string& text, const std::string& source_name) {
  check_json_depth(text, source_name);
  try {
    return Json::parse(text, nullptr, true, /*ignore_comments=*/true);
  } catch (const Json::out_of_range& e) {  // e.g. a number beyond the double range, -1e999
    std::string what = e.what();
    const auto p = what.find("] ");
    if (p != std::string::npos) what = what.substr(p + 2);
    // The exception has no position: the number it quotes is found in the text.
    std::string where;
    const auto q0 = what.find('\''), q1 = what.rfind('\'');
    if (q0 != std::string::npos && q1 > q0) {
      const size_t at = find_outside_strings(text, what.substr(q0 + 1, q1 - q0 - 1));
      if (at != std::string::npos) {
        size_t line, column;
        line_column(text, at, line, column);
        where = ":" + std::to_string(line) + ":" + std::to_string(column);
      }
    }
    throw SceneError(source_name + where + ": invalid JSON: " + what + " (numbers must be finite doubles)");
  } catch (const Json::parse_error& e) {
    size_t line, column;
    line_column(text, e.byte > 0 ? e.byte - 1 : 0, line, column);
    // nlohmann's text repeats the position: keep what follows "column N: ".
    std::string what = e.what();
    const auto p = what.find("column ");
    if (p != std::string::npos && what.find(": ", p) != std::string::npos) what = what.substr(what.find(": ", p) + 2);
    throw SceneError(source_name + ":" + std::to_string(line) + ":" + std::to_string(column) +
                     ": invalid JSON: " + what);
  }
}

void check_file_name(const std::string& path, const std::string& name, const std::string& used_in) {
  constexpr size_t kMaxLength = 200;
  bool ok = name.size() <= kMaxLength && name != "." && name != "..";
  for (char c : name) ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.');
  if (!ok)
    throw SceneError(path, json_text(Json(name)) + " (" + std::to_string(name.size()) + " characters)",
                     "a name of at most " + std::to_string(kMaxLength) +
                         " letters, digits, '_', '-' and '.', not \".\" or \"..\" (it names " + used_in + ")");
}

std::string path_of(const std::string& assignment) { return assignment.substr(0, assignment.find('=')); }

void apply_override(Json& doc, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SceneError("--set " + assignment, "", "the form path=value, e.g. solver.hourglass=laplacian");
  const std::string path = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  try {  // every string of a scene must be valid UTF-8 (run.json holds them)
    (void)Json(assignment).dump();
  } catch (const Json::type_error&) {
    throw SceneError("--set " + Json(path).dump(-1, ' ', true, Json::error_handler_t::replace),
                     "bytes that are not UTF-8", "UTF-8 text");
  }
  Json value;
  check_json_depth(text, "--set " + path_of(assignment));
  try {
    value = Json::parse(text);
  } catch (const Json::exception&) {
    value = text;  // a plain string such as laplacian (or a number beyond double range, refused where read)
  }
  std::vector<std::string> parts;
  std::stringstream ss(path);
  for (std::string p; std::getline(ss, p, '.');) {
    if (p.empty()) throw SceneError("--set " + path, "an empty path component", "names separated by '.'");
    parts.push_back(p);
  }
  Json* node = &doc;
  std::string walked;
  for (size_t k = 0; k < parts.size(); ++k) {
    const std::string& p = parts[k];
    const bool last = k + 1 == parts.size();
    walked += "/" + p;
    if (node->is_array()) {
      Json* next = nullptr;
      const bool numeric = p.find_first_not_of("0123456789") == std::string::npos;
      if (numeric && std::stoul(p) < node->size()) next = &(*node)[std::stoul(p)];
      for (auto& e : *node)
        if (!next && e.is_object() && e.contains("name") && e["name"] == p) next = &e;
      if (!next)
        throw SceneError("--set " + path, "no element '" + p + "' at " + walked,
                         "an index below " + std::to_string(node->size()) + " or the name of an element");
      if (last) *next = value;
      node = next;
    } else if (node->is_object()) {
      if (last) {
        if (value.is_null())
          node->erase(p);  // --set key=null removes the key: its default applies
        else
          (*node)[p] = value;
      } else {
        if (!node->contains(p)) (*node)[p] = Json::object();
        node = &(*node)[p];
      }
    } else {
      throw SceneError("--set " + path, json_type_name(*node) + " at " + walked,
                       "an object or an array to descend into");
    }
  }
}

Scene read_scene(const Json& doc, Json& resolved, const std::string& base_dir) {
  Scene scene;
  scene.base_dir = base_dir;
  resolved = Json::object();
  // Constants first (in file order): numbers or expressions of earlier constants.
  std::map<std::string, double> constants;
  auto eval = [&constants](const std::string& text, const std::string& path) {
    try {
      // Only the constants the text names: compile() checks every constant
      // it is given, and a scene of n constants evaluates n texts.
      expr::Program p = expr::compile(text, expr::VariableTable{}, named_constants(text, constants));
      return p.evaluate_host(nullptr);
    } catch (const expr::ExpressionError& e) {
      try {  // again with all of them, for a message that lists them
        (void)expr::compile(text, expr::VariableTable{}, constants).evaluate_host(nullptr);
      } catch (const expr::ExpressionError& all) {
        throw SceneError(path + ": " + all.what());
      }
      throw SceneError(path + ": " + e.what());
    }
  };
  JsonNode root(doc, "", resolved, eval);
  scene.name = root.string("name");
  check_file_name("/name", scene.name, "the output folder out/<name> and the snapshot files");
  scene.description = root.string("description", "");
  if (!root.has("dimension")) throw SceneError("/dimension", "nothing", "2 or 3 (this key is required)");
  scene.dimension = int(root.integer("dimension", 2, 2, 3));
  const int dim = scene.dimension;

  if (auto c = root.optional_object("constants")) {
    const Json& src = doc["constants"];
    for (auto it = src.begin(); it != src.end(); ++it) {
      const std::string name = it.key();
      const std::string path = "/constants/" + name;
      if (kReservedNames.count(name))
        throw SceneError(path, "the reserved name '" + name + "'",
                         "another name (reserved: variables x0 y0 z0 x y z ux uy uz vx vy vz t dt dx, pi, and the body "
                         "constants c0 cs rho0 h)");
      if (const std::string problem = expr::name_problem(name); !problem.empty())
        throw SceneError(path, json_text(Json(name)) + ", " + problem,
                         "a name of letters, digits and '_' that starts with a letter or '_' and is neither a "
                         "function nor a reserved word (if and or skip Skip pi)");
      const double v = c->number(name, Range::any());
      constants[name] = v;
      scene.constants.emplace_back(name, v);
    }
    c->finish();
  }

  scene.solver = read_solver(root.object("solver"), dim);

  auto bodies = root.array("bodies", true, 1);
  std::set<std::string> names;
  for (size_t b = 0; b < bodies.size(); ++b) {
    JsonNode node = root.element("bodies", b, *bodies[b]);
    BodySpec body;
    body.name = node.string("name");
    const std::string body_method = node.choice("method", {"tlsph", "ulsph", "rkpm"}, to_string(scene.solver.method));
    body.method = body_method == "ulsph" ? Method::ulsph : body_method == "rkpm" ? Method::rkpm : Method::tlsph;
    if ((body.method == Method::rkpm) != (scene.solver.method == Method::rkpm))
      throw SceneError(node.key_path("method"),
                       "\"" + body_method + "\" in a scene of method \"" + to_string(scene.solver.method) + "\"",
                       "one method for every body when RKPM is involved (RKPM bodies do not yet share a scene "
                       "with SPH bodies)");
    // The settings this body runs with (solver_for: a body of the other method takes that method's defaults).
    const SolverSpec solver = solver_for(scene.solver, body.method);
    if (!names.insert(body.name).second)
      throw SceneError(node.key_path("name"), "\"" + body.name + "\"", "a name no other body has");
    body.spacing = node.number("spacing", Range::positive());
    body.geometry = read_shape(node.object("geometry"), dim, scene.base_dir);
    body.material = read_material(node.object("material"), body.spacing, dim, scene.warnings);
    if (body.material.fracture.enabled) check_file_name(node.key_path("name"), body.name, "crack_<name>.csv");
    check_method_material(body, solver, node.key_path("material"));
    if (body.material.fracture.enabled && solver.hourglass != HourglassControl::none)
      throw SceneError(
          "/solver/hourglass",
          std::string("\"") + to_string(solver.hourglass) + "\" with fracture in body \"" + body.name + "\"",
          "\"none\": the degraded stress of phase-field fracture is implemented in the standard "
          "TLSPH form (seed 001), not in the hourglass-controlled splits");
    if (body.material.model == MaterialModel::holzapfel_ogden && solver.hourglass == HourglassControl::laplacian)
      throw SceneError("/solver/hourglass",
                       std::string("\"laplacian\" with the holzapfel_ogden body \"") + body.name + "\"",
                       "\"genog\" or \"none\": the Laplacian form of seed 003 is defined for isotropic elastic "
                       "bodies; GENOG's shear term takes the Holzapfel-Ogden c = a exp[b(I1 - 3)] (seed 000)");
    if (body.material.plastic() && solver.hourglass == HourglassControl::laplacian)
      throw SceneError(node.key_path("material") + "/model",
                       std::string("\"") + to_string(body.material.model) + "\" with solver.hourglass \"laplacian\"",
                       "an elastic model, or hourglass \"genog\" or \"none\": the Laplacian form of seed 003 "
                       "is defined for elastic bodies only");
    check_body_properties(body, solver, dim, node.path());
    JsonNode v = node.object_or_empty("initial_velocity");
    const char* axes[3] = {"x", "y", "z"};
    for (int a = 0; a < dim; ++a) body.initial_velocity[size_t(a)] = v.expression(axes[a], "0");
    v.finish();
    if (auto r = node.optional_object("reference_map")) {
      const char* identity[3] = {"x0", "y0", "z0"};
      for (int a = 0; a < dim; ++a) body.reference_map[size_t(a)] = r->expression(axes[a], identity[a]);
      r->finish();
    }
    if (auto u = node.optional_object("initial_displacement")) {
      for (int a = 0; a < dim; ++a) body.initial_displacement[size_t(a)] = u->expression(axes[a], "0");
      u->finish();
    }
    node.finish();
    scene.bodies.push_back(body);
  }

  if (scene.solver.method == Method::tlsph && doc.contains("solver") && doc["solver"].is_object() &&
      doc["solver"].contains("ulsph") && std::none_of(scene.bodies.begin(), scene.bodies.end(), [](const BodySpec& b) {
        return b.method == Method::ulsph;
      }))
    throw SceneError("/solver/ulsph", "ULSPH settings in a scene without ULSPH bodies",
                     "solver.method \"ulsph\" or bodies[].method \"ulsph\", or no solver.ulsph");

  auto clamps = root.array("clamps", false);
  std::set<std::string> boundary_names;  // clamps, conditions, loads, walls: columns of boundary_forces.csv
  for (size_t c = 0; c < clamps.size(); ++c) {
    JsonNode node = root.element("clamps", c, *clamps[c]);
    ClampSpec clamp;
    clamp.name = read_unique_name(node, "clamp" + std::to_string(c), boundary_names, "clamp");
    clamp.body = read_body_name(node, "body", names);
    clamp.region = read_shape(node.object("region"), dim, scene.base_dir);
    node.finish();
    scene.clamps.push_back(clamp);
  }

  if (!scene.solver.deformed_time_step_given) scene.solver.deformed_time_step = has_plastic_body(scene);

  read_rigid_bodies(root, scene);
  read_conditions(root, scene, names, boundary_names);
  read_contact(root, scene);
  for (const std::string& r : scene.contact.rigid_bodies)
    if (!boundary_names.insert(r).second)
      throw SceneError("/contact/rigid_bodies", "\"" + r + "\"",
                       "a rigid body whose name no clamp, condition, load or wall has (its reaction is a column of "
                       "boundary_forces.csv)");
  read_measure_planes(root, scene, names);
  read_observers(root, scene, names);

  auto probes = root.array("probes", false);
  std::set<std::string> probe_names;
  for (size_t p = 0; p < probes.size(); ++p) {
    JsonNode node = root.element("probes", p, *probes[p]);
    ProbeSpec probe;
    probe.name = node.string("name");
    if (!probe_names.insert(probe.name).second)
      throw SceneError(node.key_path("name"), "\"" + probe.name + "\"", "a name no other probe has");
    const auto x = node.vector("point", size_t(dim), Range::any());
    for (int a = 0; a < dim; ++a) probe.point[a] = x[a];
    probe.radius = node.number("radius", 0.0, Range::non_negative());
    auto fields = node.array("fields", false);
    const std::set<std::string> allowed = {"position", "displacement",     "velocity",       "von_mises",
                                           "J",        "von_mises_strain", "plastic_strain", "phase_field"};
    for (size_t k = 0; k < fields.size(); ++k) {
      const Json& f = *fields[k];
      const std::string fp = node.key_path("fields") + "/" + std::to_string(k);
      if (!f.is_string() || !allowed.count(f.get<std::string>()))
        throw SceneError(fp, json_text(f),
                         "one of \"position\", \"displacement\", \"velocity\", \"von_mises\", \"J\", "
                         "\"von_mises_strain\", \"plastic_strain\", \"phase_field\"");
      probe.fields.push_back(f.get<std::string>());
      node.resolved()["fields"][k] = f;
    }
    if (probe.fields.empty()) {
      probe.fields = {"position"};
      node.resolved()["fields"] = Json::array({"position"});
    }
    node.finish();
    scene.probes.push_back(probe);
  }

  {
    JsonNode out = root.object_or_empty("output");
    // At most 1e9 rows: smaller intervals are typing errors (5e-324), and the
    // run would never end writing them.
    const double shortest = scene.solver.end_time * 1e-9;
    const Range interval{shortest, 1e308, false, false, "an interval of at least end_time / 1e9 (" + [&] {
                           std::ostringstream o;
                           o << shortest;
                           return o.str();
                         }() + " s)"};
    scene.output.interval = out.number("interval", scene.solver.end_time / 100.0, interval);
    scene.output.probe_interval = out.number("probe_interval", scene.output.interval / 20.0, interval);
    scene.output.vtu = out.boolean("vtu", true);
    // Checkpoints every checkpoint_interval of simulated time (0: none).
    scene.output.checkpoint_interval = out.number("checkpoint_interval", 0.0, Range::non_negative());
    if (scene.output.checkpoint_interval > 0 && scene.output.checkpoint_interval < shortest)
      throw SceneError("/output/checkpoint_interval", std::to_string(scene.output.checkpoint_interval),
                       "0 (no checkpoints) or an interval of at least end_time / 1e9");
    out.finish();
    // Legal but heavy: say how much a run will write before it starts.
    const double snapshots = scene.solver.end_time / scene.output.interval;
    const double rows = scene.solver.end_time / scene.output.probe_interval;
    std::ostringstream w;
    if (scene.output.vtu && snapshots > kManySnapshots)
      w << "/output/interval: the run writes about " << std::setprecision(3) << snapshots
        << " snapshots (VTU files); more than " << kManySnapshots << " is rarely meant";
    else if (rows > kManyRows)
      w << "/output/probe_interval: the run writes about " << std::setprecision(3) << rows
        << " rows per CSV file; more than " << kManyRows << " is rarely meant";
    if (!w.str().empty()) scene.warnings.push_back(w.str());
  }

  // Bounds: default = the bodies' bounding box grown by its size on every side.
  Bounds bb = scene.bodies[0].geometry.bounds(dim);
  for (auto& b : scene.bodies) {
    const Bounds c = b.geometry.bounds(dim);
    for (int a = 0; a < dim; ++a) bb.min[a] = std::min(bb.min[a], c.min[a]), bb.max[a] = std::max(bb.max[a], c.max[a]);
  }
  double size = 0;
  for (int a = 0; a < dim; ++a) size = std::max(size, bb.max[a] - bb.min[a]);
  std::vector<double> lo(static_cast<size_t>(dim)), hi(static_cast<size_t>(dim));
  for (int a = 0; a < dim; ++a) lo[size_t(a)] = bb.min[a] - size, hi[size_t(a)] = bb.max[a] + size;
  {
    JsonNode bn = root.object_or_empty("bounds");
    lo = bn.vector("min", size_t(dim), lo, Range::any());
    hi = bn.vector("max", size_t(dim), hi, Range::any());
    bn.finish();
  }
  for (int a = 0; a < dim; ++a) {
    scene.bounds.min[a] = lo[size_t(a)];
    scene.bounds.max[a] = hi[size_t(a)];
    if (!(hi[size_t(a)] > lo[size_t(a)]))
      throw SceneError("/bounds/max/" + std::to_string(a), std::to_string(hi[size_t(a)]),
                       "a value greater than /bounds/min");
  }
  root.finish();
  return scene;
}

SceneDocument load_scene_text(const std::string& text, const std::string& source_name,
                              const std::vector<std::string>& overrides, const std::string& base_dir) {
  SceneDocument d;
  d.source_name = source_name;
  d.source = parse_scene_json(text, source_name);
  if (!d.source.is_object()) throw SceneError(source_name, json_type_name(d.source), "a JSON object at the top level");
  for (auto& o : overrides) apply_override(d.source, o);
  d.scene = read_scene(d.source, d.resolved, base_dir);
  return d;
}

SceneDocument load_scene_file(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path, "", "a readable scene file (it cannot be opened)");
  std::stringstream ss;
  ss << in.rdbuf();
  return load_scene_text(ss.str(), path, overrides, std::filesystem::path(path).parent_path().string());
}

}  // namespace mfsd
