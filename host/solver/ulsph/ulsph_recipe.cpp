#include "host/solver/ulsph/ulsph_recipe.hpp"

#include "host/particles/field_names.hpp"

namespace mfsd {

// A ghost's row is cut by the halo, so each pass whose pair sums a later
// pass reads of a partner is followed by its owners' values (docs/distributed.md);
// every other field a ghost holds is its own function of these (x = X + u,
// the pair data, B) or is read of no partner (a, the work sums). The
// single-process comparisons (tests/mpi) check that the lists are complete.
StepRecipe ulsph_recipe(const Scene& scene) {
  using namespace field;
  return StepRecipe({
      {"half_step",
       "u to the half step (eq. 14); after the search, rho to the half step (eq. 30), with refresh_pairs "
       "in one pass with the kept pairs' data and B at the half-step positions"},
      {"neighbors",
       "at the start of an advection step (migrate first in a distributed run): x = X + u, cell sort, CSR "
       "with the pair data at V = m/rho, B (seed 002 eq. 20-21)"},
      // The force and GNOG read p, tau, L and kappa of the partners (and the failure flag with them).
      {"stress",
       "p (linear EOS, tension failure), L, Jaumann rate of tau with the J2 return and kappa (eq. 6-12)",
       {},
       {pressure, shear_stress, velocity_gradient, plastic_scale, failed}},
      {"force", "a = pressure + Riemann + shear + GNOG + g, v += dt a (eq. 15-18, 27-29, 31)"},
      // The contact's partners across the cut.
      {"contact", "penalty contact between bodies at x = X + u (contact.hpp)", {velocity}, {}, scene.contact.enabled},
      {"loads", "v += dt f/m at t + dt/2 (conditions.hpp)", {}, {}, has_load_condition(scene)},
      // The density step and L read v of the partners.
      {"boundary", "velocity conditions, walls and clamps at t + dt, with reactions", {}, {velocity}},
      // The search's V_j = m_j / rho_j and the next p read rho.
      {"advance",
       "rho and u through the second half at the new v (eq. 32), the step's maxima and health",
       {},
       {density}},
      {"time_step",
       "the one synchronisation; dt_adv = C_adv h / max(U_ref, |v|max), dt_ac = CFL h / (c0 + |v|max) "
       "(eq. 28-29): acoustic steps until dt_adv is covered"},
  });
}

}  // namespace mfsd
