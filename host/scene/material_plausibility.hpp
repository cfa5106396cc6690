// Warnings for materials that are legal but implausible for a solid in SI
// units (issue 47): a density given in g/cm^3 (7.8 for 7800 kg/m^3) or a
// sound speed beyond any solid's. Both are silent otherwise and only cost
// time: c0 sets the time step, so the run takes many times the steps.
#pragma once
#include <string>
#include <vector>

#include "host/scene/scene.hpp"

namespace mfsd {

// One warning per doubtful body, naming its material's JSON path, c0 and the
// steps the run would take (end_time c0 / (CFL h), the acoustic estimate).
std::vector<std::string> material_plausibility_warnings(const Scene& scene);

}  // namespace mfsd
