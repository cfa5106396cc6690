// The halo exchange of the distributed engine on loopback (issue 25;
// docs/distributed.md), run by ctest with mpiexec on 1, 2 and 4 ranks
// (`scripts/test.sh --mpi`). Every rank cuts the same cloud (the generator
// and the bisection are deterministic), keeps its own points, and sends each
// other rank the points of its own that lie within the search radius of that
// rank's box (ids and positions, through the engine's exchange_blocks). The received ghosts must
// be exactly the halo list of the whole cloud (host/distributed/halo.hpp),
// which every rank can compute as the oracle here.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include "host/distributed/block_exchange.hpp"
#include "host/distributed/halo.hpp"
#include "host/distributed/rcb.hpp"

using namespace mfsd::distributed;

namespace {

int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
int size() {
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

std::vector<Point> cloud(std::size_t n, int dim) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Point> p(n, Point{0, 0, 0});
  for (auto& x : p)
    for (int a = 0; a < dim; ++a) x[a] = u(rng) * (a == 0 ? 2.0 : 1.0);
  return p;
}

}  // namespace

TEST(MpiDecomposition, EveryRankCutsAlike) {
  const auto pts = cloud(5000, 3);
  std::vector<int> owner;
  const Decomposition d = recursive_coordinate_bisection(pts, 3, size(), owner);
  // The cut positions are bitwise equal on every rank: min == max over ranks.
  std::vector<double> cuts;
  for (const CutNode& c : d.tree)
    if (c.axis >= 0) cuts.push_back(c.position);
  std::vector<double> lo(cuts.size()), hi(cuts.size());
  MPI_Allreduce(cuts.data(), lo.data(), int(cuts.size()), MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(cuts.data(), hi.data(), int(cuts.size()), MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  EXPECT_EQ(lo, hi);
  long mine = d.counts[size_t(rank())], total = 0;
  MPI_Allreduce(&mine, &total, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  EXPECT_EQ(total, 5000);
}

TEST(MpiHaloExchange, GhostsReceivedAreTheHaloList) {
  for (int dim : {2, 3}) {
    const auto pts = cloud(dim == 2 ? 4000 : 3000, dim);
    const double radius = dim == 2 ? 0.05 : 0.1;
    std::vector<int> owner;
    const Decomposition d = recursive_coordinate_bisection(pts, dim, size(), owner);
    const int me = rank(), P = size();
    const std::size_t parts = static_cast<std::size_t>(P);
    // What this rank sends each other rank: its own points near that rank's box.
    std::vector<std::vector<double>> out(parts);  // per destination: id, x, y, z, ...
    for (std::size_t i = 0; i < pts.size(); ++i) {
      if (owner[i] != me) continue;  // a rank knows only its own points from here on
      for (int q = 0; q < P; ++q)
        if (q != me && d.boxes[size_t(q)].distance(pts[i], dim) < radius)
          out[size_t(q)].insert(out[size_t(q)].end(), {double(i), pts[i][0], pts[i][1], pts[i][2]});
    }
    // Through the engine's own exchange (host/distributed/block_exchange.hpp),
    // the one a distributed run's migrations and contact candidates take.
    std::vector<std::vector<char>> blocks(parts);
    for (std::size_t q = 0; q < parts; ++q) {
      blocks[q].resize(out[q].size() * sizeof(double));
      if (!out[q].empty()) std::memcpy(blocks[q].data(), out[q].data(), blocks[q].size());
    }
    double bytes_sent = 0;
    const std::vector<char> bytes = exchange_blocks(blocks, &bytes_sent);
    ASSERT_EQ(bytes.size() % (4 * sizeof(double)), 0u);
    std::vector<double> recv(bytes.size() / sizeof(double));
    if (!bytes.empty()) std::memcpy(recv.data(), bytes.data(), bytes.size());
    const int total = int(recv.size());
    double expected_sent = 0;
    for (std::size_t q = 0; q < parts; ++q) expected_sent += q == std::size_t(me) ? 0.0 : double(blocks[q].size());
    EXPECT_EQ(bytes_sent, expected_sent);
    std::vector<std::size_t> got;
    for (int k = 0; k + 3 < total; k += 4) {
      const std::size_t id = std::size_t(recv[size_t(k)]);
      got.push_back(id);
      for (int a = 0; a < 3; ++a) EXPECT_EQ(recv[size_t(k + 1 + a)], pts[id][a]);  // bitwise: doubles travel as is
    }
    std::sort(got.begin(), got.end());
    const auto oracle = halo_lists(d, pts, owner, radius);
    EXPECT_EQ(got, oracle[size_t(me)]) << "rank " << me << " of " << P << ", " << dim << "-D";
    long ghosts = long(got.size()), all = 0;
    MPI_Allreduce(&ghosts, &all, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
    if (me == 0)
      std::printf("%d-D, %d ranks: %ld ghosts exchanged in all (%.3f per point)\n", dim, P, all,
                  double(all) / double(pts.size()));
  }
}

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  // Only rank 0 prints gtest's report; every rank's failures reach the exit code.
  if (rank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  int failed = RUN_ALL_TESTS() != 0, any = 0;
  MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return any;
}
