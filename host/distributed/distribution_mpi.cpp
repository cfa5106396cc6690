// The MPI build's distributed run (issue 25, docs/distributed.md): each rank
// runs the method's own solver on its owned particles and ghosts, the ghosts
// refreshed by MPI_Alltoallv of the fields each pass reads (the solver says
// which), and the solver below makes every answer global: the time step is the
// minimum over the ranks, sums and means are reduced, snapshots hold the owned
// particles under their ids in the whole scene.
#define OMPI_SKIP_MPICXX 1  // the C interface only
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <unordered_map>

#include "host/distributed/block_exchange.hpp"
#include "host/distributed/distribution.hpp"
#include "host/distributed/local_part.hpp"
#include "host/distributed/migration.hpp"
#include "host/halo/halo_radius.hpp"
#include "host/scene/scene_error.hpp"
#include "host/solver/numerical_failure.hpp"

namespace mfsd {

namespace {

bool g_initialized = false;

// The tag of exchange_blocks' messages, apart from the halo refresh's.
constexpr int kBlockTag = 27;

int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
int world_size() {
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

void sum(double* values, int n) { MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD); }
double reduce(double value, MPI_Op op) {
  MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, op, MPI_COMM_WORLD);
  return value;
}

// The lists of particles (conditions, clamps, probes, measure planes) of `p`.
InitialParticles only_lists(const InitialParticles& p) {
  InitialParticles l;
  l.dimension = p.dimension;
  l.probe_particles = p.probe_particles;
  l.clamp_particles = p.clamp_particles;
  l.measure_particles = p.measure_particles;
  l.condition_particles = p.condition_particles;
  return l;
}

// Host staging: the solver packs and unpacks on its backend; the bytes of a
// refresh go in one message to each rank that shares a halo with this one (a
// GPU-aware library could take device buffers).
class MpiGhostExchange final : public GhostExchange {
 public:
  // `scene_lists`: the whole scene's lists of particles (by global index).
  MpiGhostExchange(const distributed::LocalPart& p, InitialParticles scene_lists)
      : mask_(p.ghost),
        send_(p.send_ids),
        receive_(p.receive_ids),
        send_counts_(p.send_counts),
        receive_counts_(p.receive_counts),
        boxes_(p.body_boxes),
        global_(p.global_id),
        lists_(only_lists(p.particles)),
        probe_members_(p.probe_members),
        measure_members_(p.measure_members),
        scene_lists_(std::move(scene_lists)),
        decomposition_(p.decomposition) {}
  long global_id(long local_id) const override { return global_[size_t(local_id)]; }
  const std::vector<double>& body_boxes() const override { return boxes_; }
  const std::vector<unsigned char>& ghost_mask() const override { return mask_; }
  const std::vector<long>& send_ids() const override { return send_; }
  const std::vector<long>& receive_ids() const override { return receive_; }
  const std::vector<int>& send_counts() const override { return send_counts_; }
  const std::vector<int>& receive_counts() const override { return receive_counts_; }
  void exchange(const std::vector<char>& send, size_t element_bytes, std::vector<char>& receive) override {
    const size_t ranks = send_counts_.size();
    std::vector<int> sc(ranks), sd(ranks), rc(ranks), rd(ranks);
    int s = 0, r = 0;
    for (size_t q = 0; q < ranks; ++q) {
      sc[q] = int(size_t(send_counts_[q]) * element_bytes);
      rc[q] = int(size_t(receive_counts_[q]) * element_bytes);
      sd[q] = s;
      rd[q] = r;
      s += sc[q];
      r += rc[q];
    }
    receive.resize(size_t(r));
    // Point to point with the ranks that share a halo with this one (about
    // 26 in a 3-D cut, whatever the rank count), not a collective over all.
    std::vector<MPI_Request> requests;
    for (size_t q = 0; q < ranks; ++q)
      if (rc[q] > 0) {
        requests.emplace_back();
        MPI_Irecv(receive.data() + rd[q], rc[q], MPI_BYTE, int(q), kTag, MPI_COMM_WORLD, &requests.back());
      }
    for (size_t q = 0; q < ranks; ++q)
      if (sc[q] > 0) {
        requests.emplace_back();
        MPI_Isend(send.data() + sd[q], sc[q], MPI_BYTE, int(q), kTag, MPI_COMM_WORLD, &requests.back());
      }
    MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
    bytes_sent_ += double(s);
    ++exchanges_;
  }
  void max_over_ranks(std::vector<double>& values) override {
    MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  }
  void sum_over_ranks(std::vector<double>& values) override { sum(values.data(), int(values.size())); }
  std::vector<std::vector<double>> gather_all(const std::vector<double>& values) override {
    const int ranks = int(send_counts_.size());
    std::vector<int> counts(static_cast<size_t>(ranks)), displacements(static_cast<size_t>(ranks));
    const int mine = int(values.size());
    MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    int total = 0;
    for (int r = 0; r < ranks; ++r) displacements[size_t(r)] = total, total += counts[size_t(r)];
    std::vector<double> all(size_t(total) + 1);
    MPI_Allgatherv(values.data(), mine, MPI_DOUBLE, all.data(), counts.data(), displacements.data(), MPI_DOUBLE,
                   MPI_COMM_WORLD);
    std::vector<std::vector<double>> out;
    for (int r = 0; r < ranks; ++r)
      out.emplace_back(all.begin() + displacements[size_t(r)],
                       all.begin() + displacements[size_t(r)] + counts[size_t(r)]);
    return out;
  }
  std::vector<char> exchange_blocks(const std::vector<std::vector<char>>& to_rank) override {
    return distributed::exchange_blocks(to_rank, &bytes_sent_);
  }
  int rank() const override { return world_rank(); }
  double bytes_sent() const { return bytes_sent_; }
  static constexpr int kTag = 25;  // the halo refresh (exchange_blocks: kBlockTag)
  long exchanges() const { return exchanges_; }
  void reset_counts() { bytes_sent_ = 0, exchanges_ = 0; }

  // Two paths (docs/distributed.md, "Migration"). Without a rebalance every
  // rank decides alone where its owned particles go: the owner by the cut
  // tree, the ranks whose region lies within `radius` (the halo test of
  // halo.hpp); only the counts per rank are reduced (the imbalance) and the
  // records travel point to point. A rebalance gathers every position to
  // bisect them again (O(N) per rank, rare).
  Arrivals migrate(const std::vector<long>& owned, const std::vector<std::array<double, 3>>& position,
                   const std::vector<char>& records, size_t record_bytes, double radius) override {
    const int ranks = int(send_counts_.size()), me = rank();
    const distributed::Decomposition& d = decomposition_;
    std::vector<int> owner(owned.size());
    std::vector<double> counts(static_cast<size_t>(ranks), 0.0);
    for (size_t k = 0; k < owned.size(); ++k) {
      owner[k] = d.owner({position[k][0], position[k][1], position[k][2]});
      counts[size_t(owner[k])] += 1;
    }
    sum_over_ranks(counts);
    distributed::Decomposition now = d;
    for (int q = 0; q < ranks; ++q) now.counts[size_t(q)] = long(counts[size_t(q)]);
    if (now.imbalance() > distributed::kRebalanceThreshold)
      return migrate_gathered(owned, position, records, record_bytes, radius);

    // Each record with a header (global index, new owner, position), to its
    // new owner and to the ranks whose halo holds it, in ascending global index.
    struct Header {
      long global;
      long owner;
      double x[3];
    };
    std::vector<size_t> order(owned.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(),
              [&](size_t i, size_t j) { return global_id(owned[i]) < global_id(owned[j]); });
    std::vector<std::vector<char>> out(static_cast<size_t>(ranks));
    for (size_t k : order) {
      const distributed::Point x{position[k][0], position[k][1], position[k][2]};
      const Header h{global_id(owned[k]), long(owner[k]), {x[0], x[1], x[2]}};
      for (int q = 0; q < ranks; ++q) {
        if (q != owner[k] && !(d.boxes[size_t(q)].distance(x, d.dim) < radius)) continue;
        std::vector<char>& o = out[size_t(q)];
        const char* hp = reinterpret_cast<const char*>(&h);
        o.insert(o.end(), hp, hp + sizeof(Header));
        o.insert(o.end(), records.data() + k * record_bytes, records.data() + (k + 1) * record_bytes);
      }
    }
    for (int q = 0; q < ranks; ++q)
      if (q != me) migrated_bytes_ += double(out[size_t(q)].size());
    const double sent_before = bytes_sent_;
    std::vector<char> in = exchange_blocks(out);
    bytes_sent_ = sent_before;  // counted as migration, not as refreshes
    in.insert(in.end(), out[size_t(me)].begin(), out[size_t(me)].end());
    Arrivals a;
    const size_t item = sizeof(Header) + record_bytes, n = in.size() / item;
    a.records.resize(n * record_bytes);
    held_owner_.clear();
    send_gids_.assign(static_cast<size_t>(ranks), {});
    for (size_t k = 0; k < n; ++k) {
      Header h;
      std::memcpy(static_cast<void*>(&h), in.data() + k * item, sizeof(Header));
      std::memcpy(a.records.data() + k * record_bytes, in.data() + k * item + sizeof(Header), record_bytes);
      a.global_id.push_back(h.global);
      a.ghost.push_back(h.owner != me ? 1 : 0);
      held_owner_[h.global] = int(h.owner);
      if (h.owner != me) continue;
      const distributed::Point x{h.x[0], h.x[1], h.x[2]};
      for (int q = 0; q < ranks; ++q)
        if (q != me && d.boxes[size_t(q)].distance(x, d.dim) < radius) send_gids_[size_t(q)].push_back(h.global);
    }
    for (auto& s : send_gids_) std::sort(s.begin(), s.end());
    decomposition_.counts = now.counts;
    ++migrations_;
    return a;
  }

  // A migration with a rebalance: every rank gathers every owned position
  // and computes the new cuts, owners and halos (host/distributed/migration.hpp).
  Arrivals migrate_gathered(const std::vector<long>& owned, const std::vector<std::array<double, 3>>& position,
                            const std::vector<char>& records, size_t record_bytes, double radius) {
    const int ranks = int(send_counts_.size()), me = rank();
    // Every rank's owned particles: global index and position.
    std::vector<double> mine;
    mine.reserve(owned.size() * 4);
    for (size_t k = 0; k < owned.size(); ++k)
      mine.insert(mine.end(), {double(global_id(owned[k])), position[k][0], position[k][1], position[k][2]});
    const std::vector<std::vector<double>> all = gather_all(mine);
    size_t total = 0;
    for (const auto& a : all) total += a.size() / 4;
    std::vector<distributed::Point> points(total);
    std::vector<int> old_owner(total, -1);
    for (int r = 0; r < ranks; ++r)
      for (size_t k = 0; k + 3 < all[size_t(r)].size(); k += 4) {
        const size_t g = size_t(all[size_t(r)][k]);
        if (g >= total || old_owner[g] >= 0) throw std::logic_error("migration: the ranks' owned particles overlap");
        old_owner[g] = r;
        points[g] = {all[size_t(r)][k + 1], all[size_t(r)][k + 2], all[size_t(r)][k + 3]};
      }
    distributed::Repartition next = distributed::repartition(decomposition_, points, radius, 0.0);
    const std::vector<std::vector<long>> held = distributed::holdings(next);
    // Records out: to each rank, those of its holdings owned here, ascending.
    std::unordered_map<long, size_t> slot;
    for (size_t k = 0; k < owned.size(); ++k) slot[global_id(owned[k])] = k;
    std::vector<std::vector<char>> out(static_cast<size_t>(ranks));
    for (int q = 0; q < ranks; ++q)
      for (long g : held[size_t(q)])
        if (old_owner[size_t(g)] == me) {
          const char* r = records.data() + slot.at(g) * record_bytes;
          out[size_t(q)].insert(out[size_t(q)].end(), r, r + record_bytes);
        }
    // In: this rank's holdings, grouped by their old owner (the other ranks
    // in rank order, as exchange_blocks returns them, then this one).
    for (int q = 0; q < ranks; ++q)
      if (q != me) migrated_bytes_ += double(out[size_t(q)].size());
    const double sent_before = bytes_sent_;
    Arrivals a;
    a.records = exchange_blocks(out);
    bytes_sent_ = sent_before;  // counted as migration, not as refreshes
    a.records.insert(a.records.end(), out[size_t(me)].begin(), out[size_t(me)].end());
    for (int pass = 0; pass < 2; ++pass)
      for (int q = 0; q < ranks; ++q) {
        if ((pass == 0) == (q == me)) continue;
        for (long g : held[size_t(me)])
          if (old_owner[size_t(g)] == q) {
            a.global_id.push_back(g);
            a.ghost.push_back(next.owner[size_t(g)] != me ? 1 : 0);
          }
      }
    if (a.records.size() != a.global_id.size() * record_bytes)
      throw std::logic_error("migration: the records received do not match the holdings");
    ++migrations_;
    if (next.rebalanced) ++rebalances_;
    decomposition_ = next.decomposition;
    follow(held[size_t(me)], next.owner, next.halo);
    return a;
  }

  // The owners of this rank's held particles and what it sends each rank,
  // from the whole scene's owners and halos.
  void follow(const std::vector<long>& held, const std::vector<int>& owner,
              const std::vector<std::vector<std::size_t>>& halo) {
    const int me = rank();
    held_owner_.clear();
    for (long g : held) held_owner_[g] = owner[size_t(g)];
    send_gids_.assign(halo.size(), {});
    for (size_t q = 0; q < halo.size(); ++q)
      for (size_t g : halo[q])
        if (owner[g] == me) send_gids_[q].push_back(long(g));
  }

  void adopt(const std::vector<long>& global_id) override {
    const int ranks = int(send_counts_.size()), me = rank();
    global_ = global_id;
    std::unordered_map<long, long> local_of;
    mask_.assign(global_.size(), 0);
    std::vector<long> ghosts;
    for (size_t i = 0; i < global_.size(); ++i) {
      local_of[global_[i]] = long(i);
      mask_[i] = held_owner_.at(global_[i]) != me ? 1 : 0;
      if (mask_[i]) ghosts.push_back(global_[i]);
    }
    std::sort(ghosts.begin(), ghosts.end());
    // The plan as local_part.cpp makes it: to each rank its ghosts owned
    // here, from each rank the ghosts it owns, both in ascending global index.
    send_.clear();
    receive_.clear();
    send_counts_.assign(size_t(ranks), 0);
    receive_counts_.assign(size_t(ranks), 0);
    for (int q = 0; q < ranks; ++q) {
      if (q == me) continue;
      for (long g : send_gids_[size_t(q)]) {
        send_.push_back(local_of.at(g));
        ++send_counts_[size_t(q)];
      }
      for (long g : ghosts)
        if (held_owner_.at(g) == q) {
          receive_.push_back(local_of.at(g));
          ++receive_counts_[size_t(q)];
        }
    }
    distributed::map_lists(scene_lists_, local_of, mask_, lists_, probe_members_, measure_members_);
    ++generation_;
  }

  // The membership of a checkpoint written after a migration (collective):
  // the owners and halos from every rank's owned and ghost particles, then
  // the plan as after that migration.
  void restore_membership(const std::vector<long>& global, const std::vector<unsigned char>& ghost,
                          const distributed::Decomposition& d) {
    std::vector<double> owned, ghosts;
    for (size_t i = 0; i < global.size(); ++i) (ghost[i] ? ghosts : owned).push_back(double(global[i]));
    const std::vector<std::vector<double>> all_owned = gather_all(owned), all_ghosts = gather_all(ghosts);
    size_t total = 0;
    for (const auto& o : all_owned) total += o.size();
    owner_.assign(total, -1);
    halo_.assign(all_owned.size(), {});
    for (size_t r = 0; r < all_owned.size(); ++r) {
      for (double g : all_owned[r]) owner_.at(size_t(g)) = int(r);
      for (double g : all_ghosts[r]) halo_[r].push_back(size_t(g));
      std::sort(halo_[r].begin(), halo_[r].end());
    }
    if (std::count(owner_.begin(), owner_.end(), -1) > 0)
      throw StateMismatch("the ranks' checkpoints do not own every particle once (of different runs?)");
    decomposition_ = d;
    follow(std::vector<long>(global.begin(), global.end()), owner_, halo_);
    adopt(global);
  }
  const std::vector<long>& global_ids() const { return global_; }

  const InitialParticles& lists() const override { return lists_; }
  const std::vector<long>& probe_members() const { return probe_members_; }
  const std::vector<long>& measure_members() const { return measure_members_; }
  const distributed::Decomposition& decomposition() const { return decomposition_; }
  // Changes with every adopt(): the solver below refreshes its copies.
  long generation() const { return generation_; }
  long migrations() const { return migrations_; }
  long rebalances() const { return rebalances_; }
  double migrated_bytes() const { return migrated_bytes_; }

 private:
  std::vector<unsigned char> mask_;
  std::vector<long> send_, receive_;
  std::vector<int> send_counts_, receive_counts_;
  std::vector<double> boxes_;
  std::vector<long> global_;
  InitialParticles lists_;  // by local id, owned members
  std::vector<long> probe_members_, measure_members_;
  InitialParticles scene_lists_;  // by global index
  distributed::Decomposition decomposition_;
  std::vector<int> owner_;                      // per global index (a restored membership)
  std::vector<std::vector<std::size_t>> halo_;  // per rank, a restored membership
  std::unordered_map<long, int> held_owner_;    // after a migration: the owner of each held particle
  std::vector<std::vector<long>> send_gids_;    // after a migration: per rank, the ghosts it gets from here
  double bytes_sent_ = 0, migrated_bytes_ = 0;
  long exchanges_ = 0, generation_ = 0, migrations_ = 0, rebalances_ = 0;
};

class DistributedSolver final : public Solver {
 public:
  DistributedSolver(std::unique_ptr<Solver> inner, const distributed::LocalPart& part,
                    std::shared_ptr<MpiGhostExchange> exchange)
      : inner_(std::move(inner)), exchange_(std::move(exchange)) {
    follow_membership();
    probe_total_ = probe_members_;
    measure_total_ = measure_members_;
    sum(probe_total_.data(), int(probe_total_.size()));
    sum(measure_total_.data(), int(measure_total_.size()));
    body_owned_.assign(part.particles.body_range.size(), 0.0);
    for (size_t i = 0; i < part.ghost.size(); ++i)
      if (!part.ghost[i]) body_owned_[size_t(part.particles.body[i])] += 1;
    sum(body_owned_.data(), int(body_owned_.size()));
  }

  void initialize() override {
    guarded([&] { inner_->initialize(); });
    common_dt();
    exchange_->reset_counts();
  }
  void step() override {
    guarded([&] { inner_->step(); });
    follow_membership();
    common_dt();
  }
  void limit_next_dt(double dt_max) override { inner_->limit_next_dt(dt_max); }
  double time() const override { return inner_->time(); }
  double next_dt() const override { return inner_->next_dt(); }
  long steps() const override { return inner_->steps(); }

  // The owned particles, by their ids in the whole scene.
  Snapshot snapshot() override {
    const Snapshot all = inner_->snapshot();
    Snapshot s;
    std::vector<size_t> keep;
    const std::vector<unsigned char>& ghost = exchange_->ghost_mask();
    for (size_t k = 0; k < all.n; ++k)
      if (!ghost[size_t(all.id[k])]) keep.push_back(k);
    s.n = keep.size();
    for (const auto& f : all.fields) s.fields.push_back({f.name, {}});
    for (size_t k : keep) {
      s.id.push_back(exchange_->global_id(long(all.id[k])));
      s.body.push_back(all.body[k]);
      s.constrained.push_back(all.constrained[k]);
      for (int a = 0; a < 3; ++a) {
        s.position.push_back(all.position[3 * k + size_t(a)]);
        s.displacement.push_back(all.displacement[3 * k + size_t(a)]);
        s.velocity.push_back(all.velocity[3 * k + size_t(a)]);
      }
      for (size_t f = 0; f < all.fields.size(); ++f) s.fields[f].values.push_back(all.fields[f].values[k]);
    }
    return s;
  }

  EnergySample energies() override {
    EnergySample e = inner_->energies();
    std::vector<double> v{e.kinetic,     e.strain,      e.momentum[0],
                          e.momentum[1], e.momentum[2], e.hourglass_mean * double(owned_)};
    for (const BodyEnergy& b : e.bodies)
      v.insert(v.end(), {b.kinetic, b.strain, b.plastic, b.fracture, b.external_work, b.boundary_work, b.contact_work,
                         b.gravity_work, b.damping, b.relaxation, b.crack_surface, b.active_work, b.shear_mismatch,
                         b.momentum[0], b.momentum[1], b.momentum[2]});
    sum(v.data(), int(v.size()));
    size_t k = 0;
    e.kinetic = v[k++], e.strain = v[k++];
    for (int a = 0; a < 3; ++a) e.momentum[a] = v[k++];
    const double owned = std::accumulate(body_owned_.begin(), body_owned_.end(), 0.0);
    e.hourglass_mean = owned > 0 ? v[k++] / owned : (k++, 0.0);
    for (BodyEnergy& b : e.bodies) {
      for (double* x : {&b.kinetic, &b.strain, &b.plastic, &b.fracture, &b.external_work, &b.boundary_work,
                        &b.contact_work, &b.gravity_work, &b.damping, &b.relaxation, &b.crack_surface, &b.active_work,
                        &b.shear_mismatch, &b.momentum[0], &b.momentum[1], &b.momentum[2]})
        *x = v[k++];
    }
    e.hourglass_max = reduce(e.hourglass_max, MPI_MAX);
    return e;
  }

  // Each crack's tip over the ranks: the first by kernels/fracture/crack_tip.hpp's
  // order (the further reach, then the lower reference position), as one process finds it.
  std::vector<CrackTipSample> crack_tips() override {
    std::vector<CrackTipSample> tips = inner_->crack_tips();
    constexpr int kItem = 12;  // broken, reach, reference (3), tip (3), length, padding
    std::vector<double> mine;
    for (const CrackTipSample& t : tips) {
      mine.insert(mine.end(), {t.broken ? 1.0 : 0.0, t.reach, t.reference[0], t.reference[1], t.reference[2], t.tip[0],
                               t.tip[1], t.tip[2], t.length, 0.0, 0.0, 0.0});
    }
    const int n = int(mine.size()), ranks = world_size();
    std::vector<double> all(size_t(n) * size_t(ranks));
    MPI_Allgather(mine.data(), n, MPI_DOUBLE, all.data(), n, MPI_DOUBLE, MPI_COMM_WORLD);
    for (size_t k = 0; k < tips.size(); ++k) {
      const double* best = nullptr;
      for (int r = 0; r < ranks; ++r) {
        const double* t = all.data() + size_t(r) * size_t(n) + k * kItem;
        if (t[0] == 0.0) continue;
        bool before = best == nullptr || t[1] > best[1];
        if (best && t[1] == best[1])
          for (int a = 2; a < 5; ++a)
            if (t[a] != best[a]) {
              before = t[a] < best[a];
              break;
            }
        if (before) best = t;
      }
      CrackTipSample& out = tips[k];
      out.broken = best != nullptr;
      if (!best) continue;
      out.reach = best[1];
      for (int a = 0; a < 3; ++a) out.reference[size_t(a)] = best[2 + a], out.tip[size_t(a)] = best[5 + a];
      out.length = best[8];
    }
    return tips;
  }

  // A probe's mean over its particles: each rank's mean over those it owns, weighted by their number.
  std::vector<ProbeSample> probes() override {
    std::vector<ProbeSample> p = inner_->probes();
    std::vector<double> v;
    for (size_t k = 0; k < p.size(); ++k) {
      const double w = probe_members_[k];
      for (int a = 0; a < 3; ++a)
        v.insert(v.end(), {w * p[k].position[a], w * p[k].displacement[a], w * p[k].velocity[a]});
      v.insert(v.end(), {w * p[k].von_mises, w * p[k].jacobian, w * p[k].von_mises_strain, w * p[k].plastic_strain,
                         w * p[k].phase_field});
    }
    sum(v.data(), int(v.size()));
    size_t i = 0;
    for (size_t k = 0; k < p.size(); ++k) {
      const double w = probe_total_[k] > 0 ? 1.0 / probe_total_[k] : 0.0;
      for (int a = 0; a < 3; ++a) {
        p[k].position[a] = w * v[i++];
        p[k].displacement[a] = w * v[i++];
        p[k].velocity[a] = w * v[i++];
      }
      for (double* x :
           {&p[k].von_mises, &p[k].jacobian, &p[k].von_mises_strain, &p[k].plastic_strain, &p[k].phase_field})
        *x = w * v[i++];
    }
    return p;
  }

  std::vector<BoundaryForceSample> boundary_forces() override {
    std::vector<BoundaryForceSample> f = inner_->boundary_forces();
    std::vector<double> v;
    for (const auto& s : f) v.insert(v.end(), s.force.begin(), s.force.end());
    sum(v.data(), int(v.size()));
    for (size_t k = 0; k < f.size(); ++k)
      for (int a = 0; a < 3; ++a) f[k].force[size_t(a)] = v[3 * k + size_t(a)];
    return f;
  }

  std::vector<MeasureSample> measures() override {
    std::vector<MeasureSample> m = inner_->measures();
    std::vector<double> v;
    for (size_t k = 0; k < m.size(); ++k)
      for (int a = 0; a < 3; ++a) v.insert(v.end(), {measure_members_[k] * m[k].displacement[a], m[k].force[a]});
    sum(v.data(), int(v.size()));
    for (size_t k = 0; k < m.size(); ++k) {
      const double w = measure_total_[k] > 0 ? 1.0 / measure_total_[k] : 0.0;
      for (int a = 0; a < 3; ++a) {
        m[k].displacement[a] = w * v[6 * k + 2 * size_t(a)];
        m[k].force[a] = v[6 * k + 2 * size_t(a) + 1];
      }
    }
    return m;
  }

  const StageTimers& timers() const override { return inner_->timers(); }
  void reset_timers() override {
    inner_->reset_timers();
    exchange_->reset_counts();
  }

  // Particle counts of the whole scene; the pairs are every rank's rows,
  // the ghosts' (cut) rows included.
  SetupReport setup_report() const override {
    SetupReport r = inner_->setup_report();
    r.body_particles.clear();
    for (double c : body_owned_) r.body_particles.push_back(long(c));
    r.particles = std::accumulate(r.body_particles.begin(), r.body_particles.end(), 0L);
    std::vector<double> v{double(r.pairs), double(r.regularized_corrections)};
    sum(v.data(), 2);
    r.pairs = long(v[0]);
    r.regularized_corrections = long(v[1]);
    r.mean_neighbors = r.particles ? double(r.pairs) / double(r.particles) : 0.0;
    r.min_neighbors = long(reduce(double(r.min_neighbors), MPI_MIN));
    r.max_neighbors = long(reduce(double(r.max_neighbors), MPI_MAX));
    return r;
  }

  // This rank's particles, owned and ghosts (a continued run on as many
  // ranks has the same parts: the cut is a function of the scene).
  // With the membership (particles by global index, ghost flags) and the
  // cuts, which change when particles migrate (ULSPH): a continued run
  // takes them back before its solver reads the fields.
  void save_state(StateArchive& archive) override {
    inner_->save_state(archive);
    archive.put("distributed/global_id", exchange_->global_ids());
    archive.put("distributed/ghost", exchange_->ghost_mask());
    archive.put("distributed/decomposition", distributed::to_numbers(exchange_->decomposition()));
  }
  void restore_state(const StateArchive& archive) override {
    if (archive.has("distributed/global_id")) {
      const auto global = archive.get<long>("distributed/global_id");
      const auto ghost = archive.get<unsigned char>("distributed/ghost", long(global.size()));
      if (reduce(global != exchange_->global_ids() ? 1.0 : 0.0, MPI_MAX) > 0) {
        exchange_->restore_membership(
            global, ghost, distributed::decomposition_from(archive.get<double>("distributed/decomposition")));
        inner_->expect_particles(long(global.size()));
      }
    }
    inner_->restore_state(archive);
    follow_membership();
    exchange_->reset_counts();
  }
  void attach_ghosts(std::shared_ptr<GhostExchange>) override {
    throw std::logic_error("a distributed solver is not distributed again");
  }

  double bytes_sent() const { return exchange_->bytes_sent(); }

 private:
  // Every rank takes the smallest of the ranks' next steps (each is the
  // method's own CFL bound over its owned particles, so the result is the
  // single-process step).
  void common_dt() { inner_->limit_next_dt(reduce(inner_->next_dt(), MPI_MIN)); }

  // A numerical failure on this rank ends every rank with its message, the
  // particle named by its id in the whole scene.
  template <class F>
  void guarded(F&& f) {
    try {
      f();
    } catch (const NumericalFailure& e) {
      const long id = e.particle_id();
      const NumericalFailure global =
          id >= 0 && size_t(id) < exchange_->ghost_mask().size() ? e.renumbered(exchange_->global_id(id)) : e;
      MpiSession::abort("run stopped: " + std::string(global.what()), 3);
    }
  }

  // The owned count and the probes' and planes' members here, again after a
  // migration has moved particles between the ranks.
  void follow_membership() {
    if (generation_ == exchange_->generation()) return;
    generation_ = exchange_->generation();
    const auto& ghost = exchange_->ghost_mask();
    owned_ = long(std::count(ghost.begin(), ghost.end(), (unsigned char)0));
    probe_members_.assign(exchange_->probe_members().begin(), exchange_->probe_members().end());
    measure_members_.assign(exchange_->measure_members().begin(), exchange_->measure_members().end());
  }

  std::unique_ptr<Solver> inner_;
  long generation_ = -1;
  long owned_ = 0;
  std::vector<double> probe_members_, probe_total_, measure_members_, measure_total_, body_owned_;
  std::shared_ptr<MpiGhostExchange> exchange_;
};

class MpiDistribution final : public Distribution {
 public:
  int rank() const override { return world_rank(); }
  int ranks() const override { return world_size(); }

  void check(const Scene& scene) const override {
    auto refuse = [](const std::string& path, const std::string& what) {
      throw SceneError(path, what,
                       "a scene without it on several processes (not distributed yet, docs/distributed.md)");
    };
    if (scene.solver.relaxation.enabled) refuse("/solver/relaxation", "dynamic relaxation");
  }

  InitialParticles local_particles(const Scene& scene, const InitialParticles& all) override {
    part_ = distributed::local_part(all, rank(), ranks(), distributed::halo_radius(scene));
    scene_lists_ = only_lists(all);
    return part_.particles;
  }

  std::unique_ptr<Solver> distribute(std::unique_ptr<Solver> local) override {
    exchange_ = std::make_shared<MpiGhostExchange>(part_, std::move(scene_lists_));
    local->attach_ghosts(exchange_);
    return std::make_unique<DistributedSolver>(std::move(local), part_, exchange_);
  }

  bool any(bool flag) const override {
    int f = flag ? 1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &f, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
    return f != 0;
  }
  void barrier() const override { MPI_Barrier(MPI_COMM_WORLD); }

  void print_report(long steps) const override {
    const int n = ranks();
    const std::vector<unsigned char> none;
    const std::vector<unsigned char>& mask = exchange_ ? exchange_->ghost_mask() : none;
    const double ghosts = double(std::count(mask.begin(), mask.end(), (unsigned char)1));
    const double mine[5] = {double(mask.size()) - ghosts, ghosts, exchange_ ? exchange_->bytes_sent() : 0.0,
                            exchange_ ? double(exchange_->exchanges()) : 0.0,
                            exchange_ ? exchange_->migrated_bytes() : 0.0};
    std::vector<double> all(size_t(5 * n));
    MPI_Gather(mine, 5, MPI_DOUBLE, all.data(), 5, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    if (!root()) return;
    const distributed::Decomposition& d = exchange_ ? exchange_->decomposition() : part_.decomposition;
    std::printf("mfsd: rank   owned   ghosts   sent/step [kB]   exchanges/step (%d ranks, imbalance %.3f)\n", n,
                d.imbalance());
    double migrated = 0;
    for (int r = 0; r < n; ++r) {
      const double* a = all.data() + 5 * r;
      migrated += a[4];
      std::printf("mfsd: %4d %8.0f %8.0f %14.2f %12.2f\n", r, a[0], a[1], steps > 0 ? a[2] / double(steps) / 1e3 : 0.0,
                  steps > 0 ? a[3] / double(steps) : 0.0);
    }
    if (exchange_ && exchange_->migrations() > 0)
      std::printf("mfsd: migrations: %ld (rebalances %ld), %.1f kB moved between ranks in all\n",
                  exchange_->migrations(), exchange_->rebalances(), migrated / 1e3);
  }

 private:
  distributed::LocalPart part_;
  InitialParticles scene_lists_;
  std::shared_ptr<MpiGhostExchange> exchange_;
};

}  // namespace

std::unique_ptr<Distribution> make_distribution() {
  if (!g_initialized) return nullptr;
  return std::make_unique<MpiDistribution>();
}

MpiSession::MpiSession(int& argc, char**& argv) {
  bool launched = false;
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMI_RANK", "PMIX_RANK"})
    launched = launched || std::getenv(name);
  if (!launched) return;
  MPI_Init(&argc, &argv);
  g_initialized = true;
}

MpiSession::~MpiSession() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (g_initialized && !finalized) MPI_Finalize();
}

bool MpiSession::active() { return g_initialized; }
namespace distributed {

std::vector<char> exchange_blocks(const std::vector<std::vector<char>>& to_rank, double* bytes_sent) {
  const int ranks = world_size(), me = world_rank();
  std::vector<int> out(static_cast<size_t>(ranks), 0), in(static_cast<size_t>(ranks), 0);
  for (int q = 0; q < ranks; ++q) out[size_t(q)] = q == me ? 0 : int(to_rank[size_t(q)].size());
  MPI_Alltoall(out.data(), 1, MPI_INT, in.data(), 1, MPI_INT, MPI_COMM_WORLD);
  size_t total = 0;
  for (int c : in) total += size_t(c);
  std::vector<char> received(total);
  std::vector<MPI_Request> requests;
  size_t at = 0;
  for (int q = 0; q < ranks; ++q) {
    if (in[size_t(q)] > 0) {
      requests.emplace_back();
      MPI_Irecv(received.data() + at, in[size_t(q)], MPI_BYTE, q, kBlockTag, MPI_COMM_WORLD, &requests.back());
    }
    at += size_t(in[size_t(q)]);
  }
  for (int q = 0; q < ranks; ++q)
    if (out[size_t(q)] > 0) {
      requests.emplace_back();
      MPI_Isend(to_rank[size_t(q)].data(), out[size_t(q)], MPI_BYTE, q, kBlockTag, MPI_COMM_WORLD, &requests.back());
      if (bytes_sent) *bytes_sent += double(out[size_t(q)]);
    }
  MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  return received;
}

}  // namespace distributed

int MpiSession::rank() { return g_initialized ? world_rank() : 0; }

void MpiSession::abort(const std::string& message, int code) {
  if (!g_initialized) {
    if (!message.empty()) std::fprintf(stderr, "mfsd: %s\n", message.c_str());
    std::exit(code);
  }
  if (!message.empty()) std::fprintf(stderr, "mfsd: rank %d of %d: %s\n", world_rank(), world_size(), message.c_str());
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

}  // namespace mfsd
