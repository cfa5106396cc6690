#include "host/scene/material_plausibility.hpp"

#include <cmath>
#include <sstream>

#include "host/scene/body_properties.hpp"

namespace mfsd {

namespace {

// Densities of solids in kg/m^3: the lightest foams (expanded polystyrene
// about 15-30) below, osmium (22,590) above. A density in g/cm^3 (0.5 to
// 22.6) falls below the band.
constexpr double kLightest = 25.0, kDensest = 23000.0;
// Longitudinal sound speed of the stiffest solids: diamond about 18 km/s.
constexpr double kFastest = 20000.0;

// The acoustic estimate of the run's steps: end_time c0 / (CFL h).
double steps_for(const Scene& s, const BodyProperties& p) { return s.solver.end_time * p.c0 / (s.solver.cfl * p.h); }

std::string speed(double c) {
  std::ostringstream o;
  o << std::fixed;
  o.precision(0);
  o << c;
  return o.str();
}

std::string count(double x) {
  std::ostringstream o;
  o.precision(x < 1e7 ? 7 : 3);
  o << x;
  return o.str();
}

}  // namespace

std::vector<std::string> material_plausibility_warnings(const Scene& scene) {
  std::vector<std::string> warnings;
  for (size_t k = 0; k < scene.bodies.size(); ++k) {
    const BodySpec& b = scene.bodies[k];
    const double rho = b.material.density;
    const BodyProperties p = body_properties(b, scene.solver, scene.dimension);
    const bool light = rho < kLightest;
    const bool dense = rho > kDensest;
    const bool fast = p.c0 > kFastest;
    if (!light && !dense && !fast) continue;
    std::ostringstream w;
    w.precision(6);
    w << "/bodies/" << k << "/material: ";
    if (light || dense) {
      w << "density " << rho << " kg/m^3 is outside what solids have in SI units (about 25 to 23,000 kg/m^3)";
      if (rho > 0.1 && rho < 25) w << "; " << rho << " looks like g/cm^3 (" << rho * 1000 << " kg/m^3)";
    } else {
      w << "c0 = " << speed(p.c0) << " m/s is faster than sound in any solid (diamond about 18,000 m/s)";
    }
    const double steps = steps_for(scene, p);
    w << ". With c0 = " << speed(p.c0) << " m/s the run takes about " << count(std::ceil(steps)) << " steps";
    if (light && rho > 0.1 && rho < 25) {
      BodySpec si = b;
      si.material.density = rho * 1000;
      w << ", " << std::round(steps / steps_for(scene, body_properties(si, scene.solver, scene.dimension)))
        << "x what it takes at " << rho * 1000 << " kg/m^3";
    }
    w << " (check the density in kg/m^3 and the moduli in Pa; \"units\": \"nondimensional\" for a scene in other "
         "units)";
    warnings.push_back(w.str());
  }
  return warnings;
}

}  // namespace mfsd
