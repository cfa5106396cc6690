// Column names and rows of the run's CSV outputs: probes.csv, energies.csv
// (totals, then per body) and boundary_forces.csv (per clamp, velocity
// condition and load). docs/scene-reference.md lists the columns.
#pragma once
#include <string>
#include <vector>

#include "host/scene/scene.hpp"
#include "host/solver/solver.hpp"

namespace mfsd {

std::vector<std::string> probe_columns(const Scene& scene);
std::vector<double> probe_row(const Scene& scene, double time, const std::vector<ProbeSample>& s);

std::vector<std::string> energy_columns(const Scene& scene);
std::vector<double> energy_row(double time, const EnergySample& e, int dimension);

// crack_<body>.csv: time, broken (0/1), tip.x tip.y (tip.z), length (kernels/fracture/crack_tip.hpp).
std::vector<std::string> crack_columns(const Scene& scene);
std::vector<double> crack_row(const Scene& scene, double time, const CrackTipSample& c);
std::vector<std::string> boundary_force_columns(const Scene& scene);
std::vector<double> boundary_force_row(const Scene& scene, double time, const std::vector<BoundaryForceSample>& s);

std::vector<std::string> measure_columns(const Scene& scene);
std::vector<double> measure_row(const Scene& scene, double time, size_t count, const MeasureSample& s);

}  // namespace mfsd
