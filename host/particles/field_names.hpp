// Names of particle fields, so stages agree on them without string typos.
#pragma once

namespace mfsd::field {
inline constexpr const char* id = "id";
inline constexpr const char* body = "body";
inline constexpr const char* ghost = "ghost";  // distributed runs: 1 for a copy of another rank's particle
// Distributed runs with migration: the particle's cell key at the set-up's
// sort, which with its global index gives its place in the single-process order.
inline constexpr const char* order_key = "order_key";
inline constexpr const char* reference_position = "reference_position";
inline constexpr const char* reference_position_double = "reference_position_double";  // set-up only
inline constexpr const char* displacement = "displacement";
inline constexpr const char* velocity = "velocity";
inline constexpr const char* acceleration = "acceleration";
inline constexpr const char* volume = "volume";
inline constexpr const char* constrained = "constrained";
inline constexpr const char* deformation_gradient = "deformation_gradient";
inline constexpr const char* deformation_rate = "deformation_rate";
inline constexpr const char* correction_matrix = "correction_matrix";
inline constexpr const char* force_stress = "force_stress";
inline constexpr const char* shear_coefficient = "shear_coefficient";
inline constexpr const char* shear_stress = "shear_stress";
inline constexpr const char* inverse_deformation_gradient = "inverse_deformation_gradient";
inline constexpr const char* genog_neighbor_record = "genog_neighbor_record";  // 3-D genog, CPU
inline constexpr const char* hourglass_indicator = "hourglass_indicator";
inline constexpr const char* von_mises = "von_mises";
inline constexpr const char* jacobian = "jacobian";
inline constexpr const char* von_mises_strain = "von_mises_strain";
inline constexpr const char* plastic_state = "plastic_state";    // plastic bodies: C_p^{-1}, alpha, work
inline constexpr const char* plastic_strain = "plastic_strain";  // output copy of alpha
inline constexpr const char* damping_work = "damping_work";      // Kelvin-Voigt work per reference volume
// Holzapfel-Ogden bodies (kernels/materials/holzapfel_ogden.hpp):
inline constexpr const char* fibre = "fibre";                    // f0, unit, reference configuration
inline constexpr const char* sheet = "sheet";                    // s0
inline constexpr const char* active_tension = "active_tension";  // k V_m (seed 000 eq. 43), before the ramp
inline constexpr const char* stiffening = "stiffening";          // current / reference longitudinal modulus
inline constexpr const char* active_work = "active_work";        // active stress's work on the body per V0
// Phase-field fracture (fracturing bodies; kernels/fracture/phase_field.hpp).
inline constexpr const char* phase_field = "phase_field";              // s
inline constexpr const char* phase_field_rate = "phase_field_rate";    // ds/dt
inline constexpr const char* fracture_history = "fracture_history";    // H = max psi_plus
inline constexpr const char* tensile_energy = "tensile_energy";        // psi_plus at the half step
inline constexpr const char* fracture_released = "fracture_released";  // released energy per V0
inline constexpr const char* phase_field_lower = "phase_field_lower";  // restrict_phase_field bound
inline constexpr const char* phase_field_next = "phase_field_next";    // s_{n+1} within a step
// ULSPH (host/solver/ulsph/; kernels/ulsph/): the state and the stage fields.
inline constexpr const char* mass = "mass";                        // m = rho0 V0
inline constexpr const char* density = "density";                  // rho
inline constexpr const char* current_volume = "current_volume";    // V = m / rho at the step's start (pair refresh)
inline constexpr const char* dissipated_work = "dissipated_work";  // J taken by the Riemann dissipation and GNOG
inline constexpr const char* numerical_acceleration = "numerical_acceleration";  // Riemann + GNOG part of a
inline constexpr const char* shear_mismatch = "shear_mismatch";  // ULSPH energy audit: sum V tau : (L - L~) dt
inline constexpr const char* plastic_work = "plastic_work";      // J of plastic work (ULSPH J2)
inline constexpr const char* pair_density = "pair_density";      // rho when the pair data (V_j = m_j/rho_j) were formed
inline constexpr const char* pressure = "pressure";              // p = K (rho/rho0 - 1)
inline constexpr const char* velocity_gradient = "velocity_gradient";            // L_ab = dv_a/dx_b
inline constexpr const char* hourglass_acceleration = "hourglass_acceleration";  // GNOG a_h, accumulated
inline constexpr const char* current_position = "current_position";              // x = X + u for the search
inline constexpr const char* plastic_scale = "plastic_scale";                    // kappa of J2 bodies
inline constexpr const char* failed = "failed";                                  // 1 once a particle failed
inline constexpr const char* failed_output = "failed_output";                    // the same as a Real (outputs)
// RKPM (host/solver/rkpm/): the operators' configuration and the node state.
inline constexpr const char* support = "support";                      // a = a~ h0 J^(1/d)
inline constexpr const char* operator_position = "operator_position";  // x of the operators
inline constexpr const char* build_position = "build_position";        // x at the list's build
inline constexpr const char* increment = "increment";                  // du since the operators' configuration
inline constexpr const char* cell_map = "cell_map";                    // F_cell
inline constexpr const char* cell_lo = "cell_lo";                      // initial cell extents
inline constexpr const char* cell_hi = "cell_hi";
inline constexpr const char* cell_surface = "cell_surface";            // boundary face bits
inline constexpr const char* singular = "singular";                    // singular-kernel node
inline constexpr const char* node_operator = "node_operator";          // faces and RK coefficients
inline constexpr const char* implicit_gradient = "implicit_gradient";  // NSNI data
inline constexpr const char* operator_status = "operator_status";      // regularized / failed points
inline constexpr const char* nearest = "nearest";                      // distance to the nearest node (time step)
inline constexpr const char* reach = "reach";                          // a + cell reach
inline constexpr const char* effective_stress = "effective_stress";    // sigma_bar, 3 x 3
inline constexpr const char* stress_gradient = "stress_gradient";      // NSNI sigma^(i)
inline constexpr const char* nsni_stress = "nsni_stress";              // NSNI tau^(i)
inline constexpr const char* damage = "damage";                        // D
inline constexpr const char* internal_work = "internal_work";          // J
inline constexpr const char* lumped_mass = "lumped_mass";              // M_I
inline constexpr const char* lumped_volume = "lumped_volume";          // M_I / rho0
inline constexpr const char* density0 = "density0";                    // rho0 per node
}  // namespace mfsd::field
