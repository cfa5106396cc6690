#include "host/driver/output_rows.hpp"

namespace mfsd {

std::vector<std::string> probe_columns(const Scene& scene) {
  std::vector<std::string> cols{"time"};
  const char* axes[3] = {"x", "y", "z"};
  for (auto& p : scene.probes)
    for (auto& f : p.fields) {
      if (f == "von_mises" || f == "J" || f == "von_mises_strain" || f == "plastic_strain" || f == "phase_field") {
        cols.push_back(p.name + "." + f);
      } else {
        for (int a = 0; a < scene.dimension; ++a) cols.push_back(p.name + "." + f + "." + axes[a]);
      }
    }
  return cols;
}

std::vector<double> probe_row(const Scene& scene, double time, const std::vector<ProbeSample>& s) {
  std::vector<double> row{time};
  for (size_t k = 0; k < scene.probes.size(); ++k)
    for (auto& f : scene.probes[k].fields) {
      if (f == "von_mises") {
        row.push_back(s[k].von_mises);
      } else if (f == "J") {
        row.push_back(s[k].jacobian);
      } else if (f == "von_mises_strain") {
        row.push_back(s[k].von_mises_strain);
      } else if (f == "plastic_strain") {
        row.push_back(s[k].plastic_strain);
      } else if (f == "phase_field") {
        row.push_back(s[k].phase_field);
      } else {
        const Point3& v = f == "position" ? s[k].position : (f == "displacement" ? s[k].displacement : s[k].velocity);
        for (int a = 0; a < scene.dimension; ++a) row.push_back(v[a]);
      }
    }
  return row;
}

namespace {
const char* kBodyEnergyColumns[] = {"kinetic",       "strain",        "plastic",      "fracture",
                                    "external_work", "boundary_work", "contact_work", "gravity_work",
                                    "damping",       "relaxation",    "balance"};
}

// Totals first (the columns earlier versions wrote keep their places), then
// per body <name>.<quantity>.
std::vector<std::string> energy_columns(const Scene& scene) {
  std::vector<std::string> cols{"time",           "kinetic",       "strain",        "total",      "hourglass_max",
                                "hourglass_mean", "external_work", "boundary_work", "plastic",    "fracture",
                                "contact_work",   "gravity_work",  "damping",       "relaxation", "balance"};
  const char* axes[3] = {"x", "y", "z"};
  for (int a = 0; a < scene.dimension; ++a) cols.push_back(std::string("momentum.") + axes[a]);
  for (auto& b : scene.bodies) {
    for (const char* q : kBodyEnergyColumns) cols.push_back(b.name + "." + q);
    for (int a = 0; a < scene.dimension; ++a) cols.push_back(b.name + ".momentum." + axes[a]);
  }
  // Scenes with fracture: the crack surface energy, in total and per body, last.
  if (has_fracture_body(scene)) {
    cols.push_back("crack_surface");
    for (auto& b : scene.bodies) cols.push_back(b.name + ".crack_surface");
  }
  // Scenes with an active stress (Holzapfel-Ogden muscle): its work on the bodies, in the balance, last.
  if (has_active_stress(scene)) {
    cols.push_back("active_work");
    for (auto& b : scene.bodies) cols.push_back(b.name + ".active_work");
  }
  // solver.ulsph.energy_audit: the shear force's missing work (not in the balance), last.
  if (has_ulsph_energy_audit(scene)) {
    cols.push_back("shear_mismatch");
    for (auto& b : scene.bodies) cols.push_back(b.name + ".shear_mismatch");
  }
  return cols;
}

std::vector<double> energy_row(double time, const EnergySample& e, int dimension) {
  BodyEnergy sum;
  for (auto& b : e.bodies) {
    sum.external_work += b.external_work;
    sum.boundary_work += b.boundary_work;
    sum.plastic += b.plastic;
    sum.fracture += b.fracture;
    sum.contact_work += b.contact_work;
    sum.relaxation += b.relaxation;
    sum.gravity_work += b.gravity_work;
    sum.damping += b.damping;
    sum.active_work += b.active_work;
  }
  sum.kinetic = e.kinetic;
  sum.strain = e.strain;
  std::vector<double> row{time,
                          e.kinetic,
                          e.strain,
                          e.kinetic + e.strain,
                          e.hourglass_max,
                          e.hourglass_mean,
                          sum.external_work,
                          sum.boundary_work,
                          sum.plastic,
                          sum.fracture,
                          sum.contact_work,
                          sum.gravity_work,
                          sum.damping,
                          sum.relaxation,
                          sum.balance()};
  for (int a = 0; a < dimension; ++a) row.push_back(e.momentum[a]);
  for (auto& b : e.bodies) {
    row.insert(row.end(), {b.kinetic, b.strain, b.plastic, b.fracture, b.external_work, b.boundary_work, b.contact_work,
                           b.gravity_work, b.damping, b.relaxation, b.balance()});
    for (int a = 0; a < dimension; ++a) row.push_back(b.momentum[a]);
  }
  if (e.with_fracture) {
    double total = 0;
    for (auto& b : e.bodies) total += b.crack_surface;
    row.push_back(total);
    for (auto& b : e.bodies) row.push_back(b.crack_surface);
  }
  if (e.with_active) {
    row.push_back(sum.active_work);
    for (auto& b : e.bodies) row.push_back(b.active_work);
  }
  if (e.with_audit) {
    double total = 0;
    for (auto& b : e.bodies) total += b.shear_mismatch;
    row.push_back(total);
    for (auto& b : e.bodies) row.push_back(b.shear_mismatch);
  }
  return row;
}

std::vector<std::string> crack_columns(const Scene& scene) {
  std::vector<std::string> cols{"time", "broken"};
  const char* axes[3] = {"x", "y", "z"};
  for (int a = 0; a < scene.dimension; ++a) cols.push_back(std::string("tip.") + axes[a]);
  cols.push_back("length");
  return cols;
}

std::vector<double> crack_row(const Scene& scene, double time, const CrackTipSample& c) {
  std::vector<double> row{time, c.broken ? 1.0 : 0.0};
  for (int a = 0; a < scene.dimension; ++a) row.push_back(c.tip[size_t(a)]);
  row.push_back(c.length);
  return row;
}

std::vector<std::string> boundary_force_columns(const Scene& scene) {
  std::vector<std::string> cols{"time"};
  const char* axes[3] = {"x", "y", "z"};
  auto add = [&](const std::string& name) {
    for (int a = 0; a < scene.dimension; ++a) cols.push_back(name + "." + axes[a]);
  };
  for (auto& c : scene.clamps) add(c.name);
  for (auto& c : scene.conditions) add(c.name);
  for (auto& w : scene.walls) add(w.name);
  for (auto& r : scene.contact.rigid_bodies) add(r);
  return cols;
}

std::vector<double> boundary_force_row(const Scene& scene, double time, const std::vector<BoundaryForceSample>& s) {
  std::vector<double> row{time};
  for (auto& f : s)
    for (int a = 0; a < scene.dimension; ++a) row.push_back(f.force[a]);
  return row;
}

std::vector<std::string> measure_columns(const Scene& scene) {
  std::vector<std::string> cols{"time", "particles"};
  const char* axes[3] = {"x", "y", "z"};
  for (const char* q : {"u", "force"})
    for (int a = 0; a < scene.dimension; ++a) cols.push_back(std::string(q) + "." + axes[a]);
  return cols;
}

std::vector<double> measure_row(const Scene& scene, double time, size_t count, const MeasureSample& s) {
  std::vector<double> row{time, double(count)};
  for (int a = 0; a < scene.dimension; ++a) row.push_back(s.displacement[a]);
  for (int a = 0; a < scene.dimension; ++a) row.push_back(s.force[a]);
  return row;
}

}  // namespace mfsd
