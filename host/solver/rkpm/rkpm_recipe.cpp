#include "host/solver/rkpm/rkpm_recipe.hpp"

#include "host/particles/field_names.hpp"

namespace mfsd {

// A ghost's row is cut by the halo: each refresh holds what the gathers
// until the next one read of a partner and a ghost's own row got wrong
// (docs/distributed.md, "RKPM"). Every other field a ghost holds is its own
// function of these (x, a, du) or is read of no partner (the work sums,
// eps_p, sigma^(i)).
StepRecipe rkpm_recipe(const Scene& scene) {
  using namespace field;
  return StepRecipe({
      {"half_step", "u += dt/2 v (drift)"},
      // The force reads sigma_bar, tau^(i) and the damage of row I's nodes;
      // the move's supports a = a~ h0 J^(1/d) read F_cell.
      {"stress",
       "per node, row L with the operators it was built with: L_n, Hughes-Winget, return mapping, F_cell, "
       "NSNI sigma^(i) (rkpm.md 4; seed 004 eq. 25-26)",
       {},
       {effective_stress, nsni_stress, damage, cell_map}},
      {"neighbors", "the symmetric list when the skin is exceeded, radius max a + max r + skin (rkpm.md 2)"},
      // The force evaluates Psi_I at x_L from L's coefficients (the
      // Kronecker nodes travel as global indices, rkpm_solver.hpp).
      {"operators",
       "x_ops = X + u, a = a~ h0 J^(1/d); faces, RK coefficients at the 2d face points and the node, NSNI "
       "coefficients (rkpm.md 1, 3.2, 5.2 stage 5)",
       {},
       {node_operator, implicit_gradient, operator_status}},
      {"force", "f_int (SNNI + VC + NSNI), row-sum mass M_I, gravity, damping, v += dt a (rkpm.md 3.3-3.5, 5.1)"},
      // The contact's partners across the cut: v and M_I / rho0.
      {"contact",
       "penalty contact at x = X + u on the lumped masses (contact.hpp)",
       {velocity, lumped_volume},
       {},
       scene.contact.enabled},
      {"loads", "v += dt f/m at t + dt/2 (conditions.hpp)", {}, {}, has_load_condition(scene)},
      // The drifts, du and so the stress read v.
      {"boundary", "velocity conditions, walls and clamps at t + dt, with reactions", {}, {velocity}},
      {"advance", "u += dt/2 v (drift), the step's reduction"},
      {"time_step", "the one synchronisation; dt = CFL min h_L / c_L (rkpm.md 5.3); rebuild when the skin is used"},
  });
}

}  // namespace mfsd
