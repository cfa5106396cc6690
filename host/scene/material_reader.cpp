// The material of a body (bodies[].material): its model and constants, the
// Holzapfel-Ogden fibres, and the checks of a material against its method.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "host/scene/body_properties.hpp"
#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"

namespace mfsd {

namespace {

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

}  // namespace

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

}  // namespace mfsd
