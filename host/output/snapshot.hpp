// The particle fields at one output time, as plain host data: what every
// method's solver hands the writers (VTU, CSV) and what they write by name.
#pragma once
#include <string>
#include <vector>

namespace mfsd {

// Host copies of the particle fields, in double, 3 components per vector
// (z = 0 in 2-D), in the solver's current particle order: the kinematics,
// then the per-particle scalars a solver or model registers by name (von_mises,
// J, hourglass, von_mises_strain, plastic_strain with a J2 body, phase_field
// with a fracturing body, ...); every writer writes each under its name, so a
// new output field is one registration in the solver.
struct Snapshot {
  size_t n = 0;
  std::vector<long> id;
  std::vector<int> body;
  std::vector<unsigned char> constrained;
  std::vector<double> position, displacement, velocity;  // 3 n
  struct Field {
    std::string name;
    std::vector<double> values;  // n
  };
  std::vector<Field> fields;
  // The named field, or null.
  const std::vector<double>* field(const std::string& name) const {
    for (const auto& f : fields)
      if (f.name == name) return &f.values;
    return nullptr;
  }
};

}  // namespace mfsd
