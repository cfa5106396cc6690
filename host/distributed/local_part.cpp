#include "host/distributed/local_part.hpp"

#include <algorithm>
#include <array>
#include <unordered_map>

#include "host/distributed/halo.hpp"

namespace mfsd::distributed {

namespace {

// The members of `ids` (global) that this rank owns, as local ids.
std::vector<long> owned_members(const std::vector<long>& ids, const std::unordered_map<long, long>& local_of,
                                const std::vector<unsigned char>& ghost) {
  std::vector<long> out;
  for (long id : ids) {
    const auto it = local_of.find(id);
    if (it != local_of.end() && !ghost[size_t(it->second)]) out.push_back(it->second);
  }
  return out;
}

}  // namespace

void map_lists(const InitialParticles& all, const std::unordered_map<long, long>& local_of,
               const std::vector<unsigned char>& ghost, InitialParticles& p, std::vector<long>& probe_members,
               std::vector<long>& measure_members) {
  p.probe_particles.clear();
  p.clamp_particles.clear();
  p.measure_particles.clear();
  p.condition_particles.clear();
  probe_members.clear();
  measure_members.clear();
  for (const auto& ids : all.probe_particles) {
    p.probe_particles.push_back(owned_members(ids, local_of, ghost));
    probe_members.push_back(long(p.probe_particles.back().size()));
  }
  for (const auto& ids : all.clamp_particles) p.clamp_particles.push_back(owned_members(ids, local_of, ghost));
  for (const auto& ids : all.measure_particles) {
    p.measure_particles.push_back(owned_members(ids, local_of, ghost));
    measure_members.push_back(long(p.measure_particles.back().size()));
  }
  for (const auto& sel : all.condition_particles) {
    InitialParticles::Selected s;
    for (size_t k = 0; k < sel.ids.size(); ++k) {
      const auto it = local_of.find(sel.ids[k]);
      if (it == local_of.end() || ghost[size_t(it->second)]) continue;
      s.ids.push_back(it->second);
      if (!sel.area.empty()) s.area.push_back(sel.area[k]);
    }
    p.condition_particles.push_back(std::move(s));
  }
}

LocalPart local_part(const InitialParticles& all, int rank, int ranks, double halo_radius) {
  LocalPart part;
  std::vector<int> owner;
  part.decomposition = recursive_coordinate_bisection(all.position, all.dimension, ranks, owner);
  const std::vector<std::vector<size_t>> halo = halo_lists(part.decomposition, all.position, owner, halo_radius);
  std::vector<unsigned char> is_ghost_here(all.size(), 0);
  for (size_t g : halo[size_t(rank)]) is_ghost_here[g] = 1;

  // Local order: per body, the owned particles and the ghosts in ascending
  // global index, the order the stable cell sort keeps within a cell.
  std::unordered_map<long, long> local_of;
  InitialParticles& p = part.particles;
  p.dimension = all.dimension;
  auto take = [&](size_t g) {
    local_of[long(g)] = long(part.global_id.size());
    part.global_id.push_back(long(g));
    part.ghost.push_back(is_ghost_here[g]);
    p.position.push_back(all.position[g]);
    p.velocity.push_back(all.velocity[g]);
    p.body.push_back(all.body[g]);
    p.constrained.push_back(all.constrained[g]);
    p.volume.push_back(all.volume[g]);
    p.surface.push_back(all.surface.empty() ? 0 : all.surface[g]);
    if (!all.displacement.empty()) p.displacement.push_back(all.displacement[g]);
    if (!all.phase_field_lower.empty()) p.phase_field_lower.push_back(all.phase_field_lower[g]);
    if (!all.fibre.empty()) {
      p.fibre.push_back(all.fibre[g]);
      p.sheet.push_back(all.sheet[g]);
      p.active_tension.push_back(all.active_tension[g]);
    }
  };
  for (const auto& r : all.body_range) {
    const long begin = long(part.global_id.size());
    for (long g = r.begin; g < r.end; ++g) {
      if (owner[size_t(g)] == rank) ++part.owned;
      if (owner[size_t(g)] == rank || is_ghost_here[size_t(g)]) take(size_t(g));
    }
    p.body_range.push_back({begin, long(part.global_id.size())});
    std::array<double, 6> box{0, 0, 0, 0, 0, 0};
    for (long g = r.begin; g < r.end; ++g)
      for (size_t a = 0; a < 3; ++a) {
        const double x = all.position[size_t(g)][a];
        box[a] = g == r.begin ? x : std::min(box[a], x);
        box[3 + a] = g == r.begin ? x : std::max(box[3 + a], x);
      }
    part.body_boxes.insert(part.body_boxes.end(), box.begin(), box.end());
  }
  if (all.surface.empty()) p.surface.clear();

  map_lists(all, local_of, part.ghost, p, part.probe_members, part.measure_members);
  p.constrained_count.assign(all.body_range.size(), 0);
  for (size_t i = 0; i < part.global_id.size(); ++i)
    if (!part.ghost[i] && p.constrained[i]) ++p.constrained_count[size_t(p.body[i])];
  p.rigid_markers = all.rigid_markers;

  // The plan. Rank q's ghosts from this rank are halo[q]'s members owned
  // here, in halo[q]'s (ascending) order; this rank's ghosts from q are
  // halo[rank]'s members owned by q, in the same order.
  part.send_counts.assign(size_t(ranks), 0);
  part.receive_counts.assign(size_t(ranks), 0);
  for (int q = 0; q < ranks; ++q) {
    if (q == rank) continue;
    for (size_t g : halo[size_t(q)])
      if (owner[g] == rank) {
        part.send_ids.push_back(local_of.at(long(g)));
        ++part.send_counts[size_t(q)];
      }
    for (size_t g : halo[size_t(rank)])
      if (owner[g] == q) {
        part.receive_ids.push_back(local_of.at(long(g)));
        ++part.receive_counts[size_t(q)];
      }
  }
  return part;
}

}  // namespace mfsd::distributed
