// A rank's local part of a distributed run (host/distributed/local_part.hpp,
// issue 25), for every rank of 1-5 on a two-body lattice: every particle is
// owned once; each owned particle finds every same-body partner within the
// halo radius among its rank's particles (brute force); ghosts are flagged
// and their owner sends them in the order the receiver expects (the plan
// needs no message); bodies stay ranges in ascending global order; the lists
// of conditions, clamps, probes and measure planes keep owned members only.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "host/distributed/local_part.hpp"

using namespace mfsd;
using namespace mfsd::distributed;

namespace {

// Two bodies side by side: a 24 x 8 block and an 8 x 8 block, spacing 1.
InitialParticles two_bodies() {
  InitialParticles p;
  p.dimension = 2;
  auto block = [&](int x0, int nx, int body) {
    const long begin = long(p.size());
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < nx; ++i) {
        p.position.push_back({x0 + i + 0.5, j + 0.5, 0.0});
        p.velocity.push_back({0, 0, 0});
        p.body.push_back(body);
        p.constrained.push_back(i == 0 ? 1 : 0);
        p.volume.push_back(1.0);
      }
    p.body_range.push_back({begin, long(p.size())});
  };
  block(0, 24, 0);
  block(25, 8, 1);
  p.probe_particles = {{3, 4, 5}, {200}};
  p.clamp_particles = {{0, 24, 48}};
  p.condition_particles = {{{10, 11, 12}, {0.5, 0.5, 0.5}}};
  p.measure_particles = {{100, 101, 102, 103}};
  return p;
}

}  // namespace

TEST(LocalPart, EveryRankHasItsPartnersAndThePlanMatches) {
  const InitialParticles all = two_bodies();
  const double radius = 2.3;
  for (int ranks = 1; ranks <= 5; ++ranks) {
    std::vector<LocalPart> parts;
    for (int r = 0; r < ranks; ++r) parts.push_back(local_part(all, r, ranks, radius));
    std::vector<int> owned_by(all.size(), -1);
    long owned = 0;
    for (int r = 0; r < ranks; ++r) {
      const LocalPart& p = parts[size_t(r)];
      owned += p.owned;
      std::set<long> here(p.global_id.begin(), p.global_id.end());
      ASSERT_EQ(here.size(), p.global_id.size()) << "a particle twice on rank " << r;
      for (size_t i = 0; i < p.global_id.size(); ++i) {
        const long g = p.global_id[i];
        EXPECT_EQ(p.particles.body[i], all.body[size_t(g)]);
        if (!p.ghost[i]) {
          EXPECT_EQ(owned_by[size_t(g)], -1) << "particle " << g << " owned twice";
          owned_by[size_t(g)] = r;
        }
      }
      // Bodies are ranges, in ascending global order.
      for (size_t b = 0; b < p.particles.body_range.size(); ++b) {
        const auto range = p.particles.body_range[b];
        for (long i = range.begin; i < range.end; ++i) {
          EXPECT_EQ(p.particles.body[size_t(i)], int(b));
          if (i > range.begin) EXPECT_LT(p.global_id[size_t(i - 1)], p.global_id[size_t(i)]);
        }
      }
      // Lists keep owned members only, as local ids.
      for (const auto& ids : p.particles.probe_particles)
        for (long id : ids) EXPECT_FALSE(p.ghost[size_t(id)]);
      for (const auto& sel : p.particles.condition_particles) {
        EXPECT_EQ(sel.ids.size(), sel.area.size());
        for (long id : sel.ids) EXPECT_FALSE(p.ghost[size_t(id)]);
      }
    }
    EXPECT_EQ(owned, long(all.size()));
    for (int r = 0; r < ranks; ++r) {
      const LocalPart& p = parts[size_t(r)];
      std::set<long> here(p.global_id.begin(), p.global_id.end());
      for (size_t i = 0; i < p.global_id.size(); ++i) {
        if (p.ghost[i]) continue;
        const auto& xi = all.position[size_t(p.global_id[i])];
        for (size_t j = 0; j < all.size(); ++j) {  // brute force: every partner is here
          const double dx = all.position[j][0] - xi[0], dy = all.position[j][1] - xi[1];
          if (all.body[j] == p.particles.body[i] && dx * dx + dy * dy < radius * radius)
            EXPECT_TRUE(here.count(long(j))) << "rank " << r << " lacks partner " << j;
        }
      }
      // The plan: what q sends to r, by global id, is what r receives from q, in order.
      std::map<int, std::vector<long>> receive;
      size_t k = 0;
      for (int q = 0; q < ranks; ++q)
        for (int c = 0; c < p.receive_counts[size_t(q)]; ++c, ++k) {
          const long local = p.receive_ids[k];
          EXPECT_TRUE(p.ghost[size_t(local)]);
          EXPECT_EQ(owned_by[size_t(p.global_id[size_t(local)])], q);
          receive[q].push_back(p.global_id[size_t(local)]);
        }
      EXPECT_EQ(k, p.receive_ids.size());
      long ghosts = 0;
      for (unsigned char g : p.ghost) ghosts += g;
      EXPECT_EQ(long(p.receive_ids.size()), ghosts) << "every ghost is refreshed";
      for (int q = 0; q < ranks; ++q) {
        const LocalPart& s = parts[size_t(q)];
        size_t first = 0;
        for (int t = 0; t < r; ++t) first += size_t(s.send_counts[size_t(t)]);
        std::vector<long> sent;
        for (int c = 0; c < s.send_counts[size_t(r)]; ++c)
          sent.push_back(s.global_id[size_t(s.send_ids[first + size_t(c)])]);
        EXPECT_EQ(sent, receive[q]) << ranks << " ranks: " << q << " -> " << r;
      }
    }
    // The owned members of each probe and measure plane sum to its size.
    for (size_t k = 0; k < all.probe_particles.size(); ++k) {
      long members = 0;
      for (const auto& p : parts) members += p.probe_members[k];
      EXPECT_EQ(members, long(all.probe_particles[k].size()));
    }
    long measured = 0;
    for (const auto& p : parts) measured += p.measure_members[0];
    EXPECT_EQ(measured, 4);
  }
}
