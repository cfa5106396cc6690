// The resolved scene: plain data built from the JSON file by scene_reader
// (validated there) and consumed by the particle generator and the solvers.
// No JSON types here: this header is also compiled by nvcc.
#pragma once
#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "host/scene/shape.hpp"

namespace mfsd {
namespace expr {
class Program;
}  // namespace expr

// linear_elastic: the hypo-elastic solid of ULSPH (seed 002 eq. 6-8: linear
// equation of state, Jaumann rate of the shear stress); the others are
// hyperelastic (TLSPH). j2 is J2 plasticity in either method: multiplicative
// on neo-Hookean elasticity in TLSPH (seed 000), hypo-elastic with the radial
// return in ULSPH (seed 002 eq. 9-12).
enum class MaterialModel {
  neo_hookean,
  saint_venant_kirchhoff,
  j2,
  j2_mandel,
  holzapfel_ogden,
  linear_elastic,
  drucker_prager  // RKPM (rkpm.md 4.4): hypo-elastic Drucker-Prager with a tension cut-off
};
enum class HardeningLaw { linear, saturation, herschel_bulkley };
// The solution method of a body (bodies[].method; solver.method is the default).
enum class Method { tlsph, ulsph, rkpm };
// Hourglass control: tlsph none | laplacian | genog, ulsph none | gnog | gnog_amc.
enum class HourglassControl { none, laplacian, genog, gnog, gnog_amc };
// GENOG correction weight (solver.genog.limiter; kernels/tlsph/hourglass.hpp):
// the paper's phi = alpha d beta gamma (seed 000 eq. 32-33) or the authors'
// later capped form.
enum class GenogLimiterChoice { paper, capped };
// How the GENOG correction enters a pair's shear term (solver.genog.form).
enum class GenogFormChoice { vector, dyadic };
enum class SoundSpeed { bulk, p_wave };       // sqrt(K/rho0) | sqrt((K + 4G/3)/rho0)
enum class DampingForm { isotropic, split };  // one wave speed | c0 normal, c_s shear
enum class Precision { single_precision, double_precision };

// Phase-field brittle fracture of a body (seed 001 sections 2.2-2.4, 3.3.1;
// kernels/fracture/): the material's tensile energy is degraded by s^2.
struct PhaseFieldRestriction {
  std::string where;   // expression of x0 y0 z0 (and the constants): non-zero selects
  double minimum = 1;  // lower bound on s there (seed 001 "restrictphi", e.g. 0.9999)
};
struct FractureSpec {
  bool enabled = false;
  double energy_release_rate = 0;            // Gc [J/m^2]
  double length_scale = 0;                   // eps0 [m]
  double phase_field_limit = 0.1;            // s_l (seed 001 eq. 63)
  double speed = 0;                          // c of eq. 61 [m/s]; 0 = the P-wave speed sqrt((K + 4G/3)/rho0)
  std::vector<std::vector<Point3>> notches;  // 2 ends (2-D) or 4 corners (3-D), reference configuration
  std::vector<PhaseFieldRestriction> restrictions;
  Point3 crack_direction{0, 0, 0};  // of the crack-tip output; zero = along the first notch (2-D)
};

// Holzapfel-Ogden (seed 000 eq. 12-17; kernels/materials/holzapfel_ogden.hpp)
// with the active stress of seed 000 eq. 18-19, 43: T_a = k V_m(x0, y0, z0),
// grown linearly from 0 over ramp_time (0: from the start).
struct ActiveStressSpec {
  bool enabled = false;
  std::string potential;             // V_m, expression of x0 y0 z0 and the constants
  double tension_per_potential = 0;  // k (seed 000 eq. 43: -0.5)
  double ramp_time = 0;              // s
  // Compiled once by the scene reader (active_potential.hpp): the program,
  // and whether it is evaluated every step (it reads more than x0 y0 z0).
  std::shared_ptr<const expr::Program> program;
  bool per_step = false;
};
struct HolzapfelOgdenSpec {
  double a = 0, b = 0, af = 0, bf = 0, as = 0, bs = 0, afs = 0, bfs = 0;
  double lambda = 0;                             // Lame parameter of the ln J terms
  std::array<std::string, 3> fibre{"", "", ""};  // f0, expressions of x0 y0 z0; "" = not given
  std::array<std::string, 3> sheet{"", "", ""};  // s0
  ActiveStressSpec active;
};

// Drucker-Prager of RKPM bodies (rkpm.md 4.4): the cone from a Mohr-Coulomb
// cohesion and friction angle by one of the matches, a dilation angle
// (= friction: associative) and the mean-stress cut-off p <= T.
enum class ConeMatch { plane_strain, outer, inner };
struct DruckerPragerSpec {
  double cohesion = 0;        // c, Pa
  double friction_angle = 0;  // phi, degrees
  double dilation_angle = 0;  // psi, degrees (potential beta from psi by the same match)
  double tension_cutoff = 0;  // T, Pa; 0: none (the apex k/alpha bounds p)
  ConeMatch match = ConeMatch::plane_strain;
};
// Ductile damage of RKPM J2 bodies (rkpm.md 4.3): sigma = (1 - D) sigma_bar.
enum class DamageModel { none, linear, exponential, johnson_cook };
struct DamageSpec {
  DamageModel law = DamageModel::none;
  double onset_strain = 0;                                    // eps_D (linear, exponential)
  double failure_strain = 1;                                  // eps_f (linear)
  double decay_strain = 1;                                    // eps_r (exponential)
  double d1 = 0, d2 = 0, d3 = 0, d4 = 0, reference_rate = 1;  // johnson_cook
};

struct MaterialSpec {
  MaterialModel model = MaterialModel::neo_hookean;
  double density = 0;
  double failure_pressure = 0;  // ULSPH tension failure threshold (Pa; 0 = none; seed 002 section 5.9)
  double youngs_modulus = 0;
  double poisson_ratio = 0;
  // j2 (neo-Hookean elasticity on b_e, seed 000 section 3.2):
  // sigma_Y(a) = yield_stress + hardening_modulus a
  //              [+ (saturation_stress - yield_stress)(1 - exp(-saturation_exponent a))]
  HardeningLaw hardening = HardeningLaw::linear;
  double yield_stress = 0;
  double hardening_modulus = 0;
  double saturation_stress = 0;
  double saturation_exponent = 0;
  // Viscoplastic Herschel-Bulkley flow instead of hardening (seed 000 Table 8):
  // dgamma/dt = ((|s| - sqrt(2/3) yield_stress) / viscosity)^(1 / flow_exponent).
  double viscosity = 0;
  double flow_exponent = 1;
  // j2_mandel (seed 001 eq. 32-52): the same elasticity and linear hardening,
  // seed 001's return on C_p with the Mandel stress (j2_return_mapping.hpp).
  FractureSpec fracture;
  DruckerPragerSpec drucker_prager;    // model drucker_prager
  DamageSpec damage;                   // RKPM j2 bodies
  HolzapfelOgdenSpec holzapfel_ogden;  // model holzapfel_ogden (density, and E and nu derived from a and K)
  bool plastic() const {
    return model == MaterialModel::j2 || model == MaterialModel::j2_mandel || model == MaterialModel::drucker_prager;
  }
};

struct BodySpec {
  std::string name;
  Method method = Method::tlsph;  // bodies[].method, default solver.method
  Shape geometry;
  double spacing = 0;
  MaterialSpec material;
  std::array<std::string, 3> initial_velocity{"0", "0", "0"};   // expressions
  std::array<std::string, 3> initial_displacement{"", "", ""};  // expressions; "" = none
  std::array<std::string, 3> reference_map{"", "", ""};         // X = map(lattice point); "" = none
};

struct ClampSpec {
  std::string name;  // column prefix in reactions.csv; default clamp<k>
  std::string body;
  Shape region;
};

// A rigid frictionless wall: the plane through `point` with unit `normal`
// pointing to the allowed side; acts on the listed bodies (all when empty).
struct WallSpec {
  std::string name;  // column prefix of its reaction in boundary_forces.csv
  Point3 point{0, 0, 0};
  Point3 normal{0, 0, 1};
  std::vector<std::string> bodies;
};

// A kinematic rigid body (host/scene/rigid_body.hpp): a shape moved by
// x(t) = center + R(angle(t)) (X - center) + translation(t).
struct RigidBodySpec {
  std::string name;
  Shape shape;
  std::array<std::string, 3> translation{"0", "0", "0"};  // expressions of t
  std::string angle_degrees = "0";                        // expression of t
  Point3 axis{0, 0, 1};
  Point3 center{0, 0, 0};
  double marker_spacing = 0;  // of its surface markers in rigid_bodies.pvd
};

// Which particles of a body a condition or load acts on: the whole body, the
// particles inside a region, those where an expression of x0 y0 z0 (and the
// constants) is non-zero, or those within a distance of a rigid body at t = 0.
struct SelectionSpec {
  enum class Kind { body, region, expression, near };
  Kind kind = Kind::body;
  Shape region;
  std::string expression;
  std::string rigid_body;  // near
  double distance = 0;     // near
};

// A prescribed velocity (seed 001 "bcvel") or a load ("bcforce"): one
// expression per component, empty where the component is not given, applied
// while t_start <= t <= t_end.
struct ConditionSpec {
  enum class Type { velocity, point_force, traction, acceleration };
  Type type = Type::velocity;
  std::string name;  // column prefix in reactions.csv / loads.csv
  std::string body;
  SelectionSpec select;
  std::array<std::string, 3> value;  // "" = not given
  int face = -1;                     // traction: only particles exposing face 2a (-e_a) or 2a + 1 (+e_a); -1 any
  double t_start = 0;
  double t_end = 1e300;
};

// Contact (kernels/contact/contact_force.hpp): which bodies touch each other,
// which touch themselves, which rigid bodies are partners, and the pair law
// (seed 001 Listing 1: contcoeff, restcoef, kfric).
struct ContactSpec {
  bool enabled = false;
  std::vector<std::string> bodies;        // every body when the scene lists none
  std::vector<std::string> self_contact;  // bodies whose distant parts may touch
  std::vector<std::string> rigid_bodies;  // kinematic rigid bodies that push the bodies
  double stiffness = 1.0;                 // kappa = contcoeff
  double restitution = 1.0;               // e of an isolated pair
  double friction = 0.0;                  // Coulomb mu
};

struct ProbeSpec {
  std::string name;
  Point3 point{0, 0, 0};
  double radius = 0;                // 0: the nearest particle; > 0: mean over the particles within it
  std::vector<std::string> fields;  // position, displacement, velocity, von_mises, J
};

// An observer (issue 28; SPHinXsys's observers): points, or a line of
// evenly spaced points, where registered particle fields are interpolated
// with a kernel average over the particles within `radius`, Shepard-
// normalised or with the linear correction that reproduces linear fields
// (docs/scene-reference.md, "observers"); frozen: the particles and weights
// of the initial configuration, else those of the current one at each row.
struct ObserverSpec {
  enum class Interpolation { shepard, linear };
  std::string name;
  std::string body;  // "" = every body
  std::vector<Point3> points;
  std::vector<std::string> fields;  // registered field names, or "position"
  double radius = 0;                // 0: the body's kernel support 2h (the largest over the bodies)
  bool freeze = false;
  Interpolation interpolation = Interpolation::shepard;
};

// A measure plane (seed 001 Fig. 7): the particles within thickness / 2 of a
// planar quadrilateral (3-D, 4 corners) or a segment (2-D, 2 ends) in the
// reference configuration; their mean displacement and total force are
// written over time to measure_<name>.csv.
struct MeasurePlaneSpec {
  std::string name;
  std::string body;  // "" = every body
  std::vector<Point3> points;
  double thickness = 0;
};

// Dynamic relaxation (seed 003 ref. [68]; kernels/tlsph/relaxation.hpp): a
// viscous damping of the velocity differences of neighbours, integrated
// implicitly pair by pair, in a step with probability random_ratio.
struct RelaxationSpec {
  bool enabled = false;
  double viscosity = 0;               // eta, Pa s (one of viscosity and factor)
  double factor = 0;                  // eta = factor p rho0 c0 h / CFL per body (docs/theory.md)
  double random_ratio = 0.2;          // p: a step relaxes with probability p, with eta / p
  unsigned long long seed = 1;        // of the random choice (runs repeat exactly)
  double t_start = 0, t_end = 1e300;  // relaxes the steps that start in [t_start, t_end)
};

// ULSPH settings (solver.ulsph; seed 002 section 3.3, formulations.md section 3).
struct UlsphSpec {
  bool dual_time_stepping = true;    // advection steps of acoustic sub-steps | one criterion (every step rebuilds)
  double advection_cfl = 0.2;        // dt_adv = advection_cfl h / max(U_ref, |v|max)
  double reference_speed = 0;        // U_ref, m/s
  bool refresh_pairs = true;         // pair data at every step's positions between searches (theory.md)
  bool remove_plastic_rate = false;  // J2: radial return | the seed's rate without its plastic part first
  double xi = -1;                    // GNOG coefficient; < 0: per body 4 elastic, 0.2 plastic, 2 with gnog_amc
  double riemann_limiter = 0;        // eta of the low-dissipation limiter (seed 002 ref. [38]); 0: none
  bool energy_audit = false;         // energies.csv gets the shear force's missing work (shear_mismatch)
  // solver.ulsph.hourglass, or solver.hourglass when ulsph is the scene's method.
  HourglassControl hourglass = HourglassControl::gnog;
};

// Semi-Lagrangian RKPM settings (solver.rkpm; seed 004, ../shared/reference/rkpm.md).
enum class QuasiLinear { regularize, shepard, off };  // rkpm.md 1.6
enum class SmoothingCells { mapped, box };            // rkpm.md 3.2
struct RkpmSpec {
  double support_factor = 2.0;         // a~: a_I = a~ h0 J^(1/d) (rkpm.md 1.2)
  bool box_supports = false;           // support_shape: box (tensor-product kernel) | sphere (rkpm.md 1.1)
  bool nsni = true;                    // integration: snni | nsni (rkpm.md 3.5)
  double nsni_scale = 1.0;             // c_s, the NSNI stiffness scale (studies only)
  bool nsni_tangent = false;           // nsni_moduli: tangent (of the return mapping) | elastic (rkpm.md 4.5)
  bool nsni_consistent = false;        // nsni_moduli: consistent (gradients returned to the yield surface's tangent)
  bool variational_correction = true;  // VC of the test gradient (rkpm.md 3.4)
  QuasiLinear quasi_linear = QuasiLinear::regularize;
  double regularization = 1e-3;  // tau of the quasi-linear regularizer (rkpm.md 1.6)
  SmoothingCells cells = SmoothingCells::mapped;
  double recell_condition = 10;    // kappa_max: re-cell when cond(F_cell) exceeds it
  bool row_sum_mass = true;        // mass: row_sum | nodal (rkpm.md 3.3)
  double damping = 0;              // alpha_d of C = alpha_d M, 1/s (seed 004 eq. 29)
  double skin = 0.15;              // r_skin / dp of the neighbour list (rkpm.md 2)
  bool singular_kernel = true;     // on nodes of essential conditions (rkpm.md 1.7, 6)
  bool nearest_time_step = false;  // time_step: support (h0 J^(1/d)) | nearest (also <= the nearest node)
};

struct SolverSpec {
  Method method = Method::tlsph;
  UlsphSpec ulsph;
  RkpmSpec rkpm;
  HourglassControl hourglass = HourglassControl::genog;
  double h_over_dp = 1.15;
  double cfl = 0.6;
  bool cfl_given = false;  // solver.cfl given: it holds for both methods (else each method's default)
  double end_time = 0;
  double zeta = 1.07;
  double genog_alpha = 8.0;
  GenogLimiterChoice genog_limiter = GenogLimiterChoice::paper;
  GenogFormChoice genog_form = GenogFormChoice::vector;
  bool correction_in_force = true;
  double damping_factor = 1.0;
  DampingForm damping_form = DampingForm::isotropic;
  RelaxationSpec relaxation;
  SoundSpeed sound_speed = SoundSpeed::bulk;
  Point3 gravity{0, 0, 0};
  double correction_floor = 0.1;
  bool reorder = true;
  Precision precision = Precision::double_precision;
  // Time step from the Lagrangian wave speed c0 max|F^{-1}| (theory.md);
  // default: on when some body is plastic.
  bool deformed_time_step = false;
  bool deformed_time_step_given = false;
};

struct OutputSpec {
  double interval = 0;        // VTU snapshots and energies
  double probe_interval = 0;  // probes.csv rows
  bool vtu = true;
  double checkpoint_interval = 0;  // simulated time between checkpoints; 0: none
};

// Above these counts a scene is accepted with a warning (scene.warnings).
constexpr double kManySnapshots = 1e5;
constexpr double kManyRows = 1e8;

struct Scene {
  std::string name;
  std::string base_dir;  // folder of the scene file: relative file names (STL) start here
  std::string description;
  // "units": "SI" (default: materials implausible for a solid in SI units get
  // a warning) or "nondimensional" (no such warning; seed 000's muscle cube).
  bool si_units = true;
  int dimension = 2;
  SolverSpec solver;
  std::vector<BodySpec> bodies;
  std::vector<ClampSpec> clamps;
  std::vector<RigidBodySpec> rigid_bodies;
  std::vector<ConditionSpec> conditions;  // velocity_conditions, then loads
  std::vector<WallSpec> walls;
  ContactSpec contact;
  std::vector<ProbeSpec> probes;
  std::vector<ObserverSpec> observers;
  std::vector<MeasurePlaneSpec> measure_planes;
  OutputSpec output;
  Bounds bounds;  // particles leaving it stop the run
  std::vector<std::pair<std::string, double>> constants;
  std::vector<std::string> warnings;  // accepted but doubtful input, printed by check and run
};

// Whether some body carries a plastic state.
bool has_plastic_body(const Scene& scene);
// Whether some condition is a load (a force, pressure or traction, not a velocity).
bool has_load_condition(const Scene& scene);
// Whether some body's material has fracture.
bool has_fracture_body(const Scene& scene);
// Some body is Holzapfel-Ogden (the solver then keeps fibre and sheet fields).
bool has_holzapfel_ogden_body(const Scene& scene);
// Some Holzapfel-Ogden body has an active stress (energies.csv gets active_work columns).
bool has_active_stress(const Scene& scene);
// solver.ulsph.energy_audit with a ULSPH body (energies.csv gets shear_mismatch columns).
bool has_ulsph_energy_audit(const Scene& scene);

// The crack followed by the crack-tip output (crack_<body>.csv) of a
// fracturing body: from `origin` (the first notch's tip in 2-D, the centre of
// its quadrilateral in 3-D) along `direction` (material.fracture.crack_direction,
// else the first notch's direction in 2-D); `notch_length` is the part of
// that notch inside the body's bounding box (2-D; 0 in 3-D).
struct CrackSpec {
  size_t body;
  Point3 origin, direction;
  double notch_length;
};
std::vector<CrackSpec> crack_specs(const Scene& scene);

// The settings a body of method m runs with: the scene's own for its
// method (solver.method), else that method's defaults with the settings both
// methods share (end_time, h_over_dp, cfl when given, precision, sound_speed,
// gravity, reorder) and, for ULSPH, solver.ulsph (docs/scene-reference.md,
// "Mixed methods").
SolverSpec solver_for(const SolverSpec& solver, Method m);
// Whether the scene's bodies use both methods (host/solver/coupled/).
bool mixed_methods(const Scene& scene);
// The one method of an unmixed scene's bodies (solver.method when all agree with it).
Method scene_method(const Scene& scene);

const char* to_string(MaterialModel m);
const char* to_string(HourglassControl h);
const char* to_string(Method m);
const char* to_string(Precision p);

}  // namespace mfsd
