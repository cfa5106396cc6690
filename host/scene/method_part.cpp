#include "host/scene/method_part.hpp"

#include <algorithm>

namespace mfsd {

namespace {

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

MethodPart method_part(const Scene& scene, const InitialParticles& all, Method method) {
  MethodPart part;
  part.method = method;
  Scene& s = part.scene;
  s = scene;
  s.bodies.clear();
  std::vector<long> local(all.size(), -1);  // scene id -> part id
  InitialParticles& p = part.particles;
  p.dimension = all.dimension;
  std::vector<std::string> names;
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    if (scene.bodies[b].method != method) continue;
    const int lb = int(s.bodies.size());
    s.bodies.push_back(scene.bodies[b]);
    names.push_back(scene.bodies[b].name);
    part.scene_body.push_back(b);
    const InitialParticles::Range r = all.body_range[b];
    p.body_range.push_back({long(p.size()), long(p.size()) + (r.end - r.begin)});
    p.constrained_count.push_back(all.constrained_count.empty() ? 0 : all.constrained_count[b]);
    for (long i = r.begin; i < r.end; ++i) {
      const size_t k = size_t(i);
      local[k] = long(p.size());
      part.id.push_back(i);
      p.position.push_back(all.position[k]);
      p.velocity.push_back(all.velocity[k]);
      p.body.push_back(lb);
      p.constrained.push_back(all.constrained[k]);
      p.volume.push_back(all.volume[k]);
      if (!all.surface.empty()) p.surface.push_back(all.surface[k]);
      if (!all.displacement.empty()) p.displacement.push_back(all.displacement[k]);
      if (!all.phase_field_lower.empty()) p.phase_field_lower.push_back(all.phase_field_lower[k]);
      if (!all.fibre.empty()) p.fibre.push_back(all.fibre[k]);
      if (!all.sheet.empty()) p.sheet.push_back(all.sheet[k]);
      if (!all.active_tension.empty()) p.active_tension.push_back(all.active_tension[k]);
    }
  }
  auto members = [&](const std::vector<long>& ids) {
    std::vector<long> out;
    for (long id : ids)
      if (local[size_t(id)] >= 0) out.push_back(local[size_t(id)]);
    return out;
  };
  // The settings of this method; the plastic default of the deformed time step from its own bodies.
  s.solver = solver_for(scene.solver, method);
  if (!s.solver.deformed_time_step_given) s.solver.deformed_time_step = has_plastic_body(s);

  s.clamps.clear();
  for (size_t c = 0; c < scene.clamps.size(); ++c)
    if (contains(names, scene.clamps[c].body)) {
      s.clamps.push_back(scene.clamps[c]);
      p.clamp_particles.push_back(members(all.clamp_particles[c]));
    }
  s.conditions.clear();
  for (size_t c = 0; c < scene.conditions.size(); ++c)
    if (contains(names, scene.conditions[c].body)) {
      s.conditions.push_back(scene.conditions[c]);
      const InitialParticles::Selected& sel = all.condition_particles[c];
      InitialParticles::Selected mine;
      for (size_t k = 0; k < sel.ids.size(); ++k) {
        if (local[size_t(sel.ids[k])] < 0) continue;
        mine.ids.push_back(local[size_t(sel.ids[k])]);
        if (!sel.area.empty()) mine.area.push_back(sel.area[k]);
      }
      p.condition_particles.push_back(mine);
    }
  s.walls.clear();
  for (const WallSpec& w : scene.walls) {
    if (w.bodies.empty()) {  // every body
      s.walls.push_back(w);
      continue;
    }
    WallSpec mine = w;
    mine.bodies.clear();
    for (const std::string& b : w.bodies)
      if (contains(names, b)) mine.bodies.push_back(b);
    if (!mine.bodies.empty()) s.walls.push_back(mine);
  }
  ContactSpec& c = s.contact;
  c.bodies.clear();
  c.self_contact.clear();
  for (const std::string& b : scene.contact.bodies)
    if (contains(names, b)) c.bodies.push_back(b);
  for (const std::string& b : scene.contact.self_contact)
    if (contains(names, b)) c.self_contact.push_back(b);
  c.enabled = scene.contact.enabled && !c.bodies.empty();
  if (!c.enabled) c.rigid_bodies.clear();
  // Measure planes of one body keep their body; those of every body hold this part's share.
  for (MeasurePlaneSpec& m : s.measure_planes)
    if (!m.body.empty() && !contains(names, m.body)) m.body.clear();
  p.rigid_markers = all.rigid_markers;
  for (const auto& ids : all.probe_particles) {
    p.probe_particles.push_back(members(ids));
    part.probe_count.push_back(long(p.probe_particles.back().size()));
  }
  for (const auto& ids : all.measure_particles) {
    p.measure_particles.push_back(members(ids));
    part.measure_count.push_back(long(p.measure_particles.back().size()));
  }
  return part;
}

}  // namespace mfsd
