#include "host/solver/tlsph/tlsph_recipe.hpp"

#include "host/particles/field_names.hpp"

namespace mfsd {

// The pairs join reference neighbours, so a ghost's row is cut by the halo:
// its copies follow their owners after every pass whose pair sums their rows
// get wrong and a later pass reads (docs/distributed.md).
StepRecipe tlsph_recipe(const Scene& scene) {
  using namespace field;
  return StepRecipe({
      {"stress",
       "per body: F and u to t + dt/2 (eq. 35), then the material x hourglass variant matrices "
       "(eq. 3, 7, 25-28; seed 003 eq. 27-28)"},
      {"force", "per body: the gathered pair sums (eq. 20, 27, 32), then v to t + dt (eq. 36)"},
      // The owned rows' Laplacians and crack surfaces read s; a ghost's own
      // stress stage reads s and ds/dt (s_n+1/2 = s + dt/2 ds/dt).
      {"phase_field",
       "phase-field rate and half step (formulations.md, phase-field fracture)",
       {},
       {phase_field, phase_field_rate},
       has_fracture_body(scene)},
      {"contact",
       "pair forces at the half-step positions, v += dt f/m like a load (contact.hpp)",
       {},
       {},
       scene.contact.enabled},
      {"loads", "v += dt f/m at t + dt/2 (conditions.hpp)", {}, {}, has_load_condition(scene)},
      {"boundary", "velocity conditions at t + dt, then clamps, with reactions"},
      {"relaxation",
       "dynamic relaxation of v, holding the boundary's particles (tlsph_relaxation.hpp)",
       {},
       {},
       scene.solver.relaxation.enabled},
      // The owned rows' rate sums read the new v of the ghosts; the next
      // step's stress stage reads u, F and dF/dt.
      {"deformation_rate",
       "dF/dt at the new velocity (eq. 22), F and u to t + dt (eq. 37), max |v|, max |a| and health",
       {velocity, acceleration},
       {displacement, deformation_gradient, deformation_rate}},
      {"time_step", "the one synchronisation; next dt on the host (eq. 38)"},
  });
}

}  // namespace mfsd
