// RkpmSolver's distributed runs (docs/distributed.md, "RKPM"): the refresh
// of the operators with their Kronecker nodes as global indices, the list
// radius and migration decision, and the step statistics over all ranks.
// Included at the end of rkpm_solver.hpp.
#pragma once

namespace mfsd {

template <class B, int D, class Real>
void RkpmSolver<B, D, Real>::refresh_stage_ghosts(const std::vector<std::string>& names) {
  const bool operators = std::find(names.begin(), names.end(), field::node_operator) != names.end();
  if (operators) kronecker_ids(true);
  this->refresh_ghosts(names);
  if (operators) kronecker_ids(false);
}

template <class B, int D, class Real>
double RkpmSolver<B, D, Real>::list_radius() const {
  double r = 0;
  for (size_t b = 0; b < scene_.bodies.size(); ++b) {
    const double reach = b < last_stats_.size()
                             ? double(last_stats_[b].max_support) + double(last_stats_[b].max_cell_reach)
                             : build_reach_[b];
    r = std::max(r, reach + spec_.skin * scene_.bodies[b].spacing);
  }
  return r;
}

template <class B, int D, class Real>
double RkpmSolver<B, D, Real>::migration_margin() const {
  double dp = 0;
  for (const auto& b : scene_.bodies) dp = std::max(dp, b.spacing);
  return dp;
}

template <class B, int D, class Real>
double RkpmSolver<B, D, Real>::migration_radius() {
  halo_radius_ = std::max(distributed::halo_radius(scene_), list_radius() + migration_margin());
  return halo_radius_;
}

template <class B, int D, class Real>
bool RkpmSolver<B, D, Real>::migration_due() {
  double spacing = 0, skin = 0;
  for (const auto& b : scene_.bodies) spacing = std::max(spacing, b.spacing);
  skin = spec_.skin * spacing;
  double reach = 0.4 * (halo_radius_ - list_radius());
  if (scene_.contact.enabled) reach = std::min(reach, 0.4 * (halo_radius_ - kContactRateReach * spacing) - 0.5 * skin);
  return migration_travelled_ > reach;
}

template <class B, int D, class Real>
void RkpmSolver<B, D, Real>::refresh_all() {
  if (!this->ghosts_) return;
  kronecker_ids(true);
  this->refresh_all_ghosts();
  kronecker_ids(false);
}

template <class B, int D, class Real>
void RkpmSolver<B, D, Real>::kronecker_ids(bool to_global) {
  Op* op = particles_.template get<Op>(field::node_operator);
  if (to_global)
    parallel_for<B>(particles_.size(), rkpm::KroneckerToGlobal<D, Real>{op, raw(global_of_local_)});
  else
    parallel_for<B>(particles_.size(), rkpm::KroneckerToLocal<D, Real>{op, raw(sorted_global_), raw(local_of_sorted_),
                                                                       Index(sorted_global_.size())});
}

template <class B, int D, class Real>
void RkpmSolver<B, D, Real>::bind_kronecker_ids() {
  if (!this->ghosts_) return;
  const auto ids = to_host<B>(particles_.template buffer<Index>(field::id));
  std::vector<Index> global(ids.size()), order(ids.size());
  for (size_t i = 0; i < ids.size(); ++i) global[i] = Index(this->ghosts_->global_id(long(ids[i])));
  std::iota(order.begin(), order.end(), Index(0));
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return global[size_t(a)] < global[size_t(b)]; });
  std::vector<Index> sorted(ids.size());
  for (size_t k = 0; k < order.size(); ++k) sorted[k] = global[size_t(order[k])];
  from_host<B>(global, global_of_local_);
  from_host<B>(sorted, sorted_global_);
  from_host<B>(order, local_of_sorted_);
}

template <class B, int D, class Real>
void RkpmSolver<B, D, Real>::stats_over_ranks(std::vector<rkpm::StepStats<D, Real>>& stats) {
  if (!this->ghosts_) return;
  std::vector<double> v;
  for (const auto& s : stats) {
    v.insert(v.end(), {double(s.max_speed2), double(s.max_drift2), double(s.max_support), double(s.max_cell_reach),
                       -double(s.min_dt)});
    for (int a = 0; a < D; ++a) v.push_back(-double(s.box.lo.v[a])), v.push_back(double(s.box.hi.v[a]));
  }
  this->ghosts_->max_over_ranks(v);
  size_t k = 0;
  for (auto& s : stats) {
    s.max_speed2 = Real(v[k++]), s.max_drift2 = Real(v[k++]), s.max_support = Real(v[k++]);
    s.max_cell_reach = Real(v[k++]), s.min_dt = Real(-v[k++]);
    for (int a = 0; a < D; ++a) s.box.lo.v[a] = Real(-v[k++]), s.box.hi.v[a] = Real(v[k++]);
  }
}
}  // namespace mfsd
