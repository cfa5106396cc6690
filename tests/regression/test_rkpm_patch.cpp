// RKPM linear patch test through the whole solver (rkpm.md 7.2, the `snni`
// gate): a 2-D square of 11 x 11 nodes on a vertex-centred lattice (half
// cells on the edges, quarter cells at the corners), linear elastic, every
// node moving with v = A X; after one step every node whose support reaches
// no boundary face must be in equilibrium (the others carry the boundary
// term sum_f Psi_I sigma a_f that a traction t = sigma n balances): its
// velocity change, as a force, against |sigma| h.
//   lattice, conforming cells, SNNI and SNNI + NSNI         <= 1e-13
//   interior nodes perturbed +-0.2 dp, box cells around them
//   (non-conforming), without the VC correction             > 1e-2 (fails)
//   the same with the VC correction (rkpm.md 3.4)           <= 1e-13
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "host/scene/particle_generator.hpp"
#include "host/scene/scene_reader.hpp"
#include "host/solver/solver.hpp"

using namespace mfsd;

namespace {

constexpr int kCells = 10;
constexpr double kDp = 0.1;
// The affine velocity gradient (with shear, so that |sigma| > 0 in every measure).
constexpr double kA[2][2] = {{1e-3, 2e-3}, {0.5e-3, -1.5e-3}};

Scene square_scene(const std::string& rkpm) {
  const std::string text = R"({
    "name": "rkpm_patch", "dimension": 2,
    "solver": {"method": "rkpm", "end_time": 1, "rkpm": )" +
                           rkpm + R"(},
    "bodies": [{"name": "square", "spacing": 0.1,
                "geometry": {"box": {"min": [0, 0], "max": [1, 1]}},
                "material": {"model": "linear_elastic", "density": 1, "youngs_modulus": 1, "poisson_ratio": 0.3}}]
  })";
  return load_scene_text(text, "rkpm_patch", {}).scene;
}

// 11 x 11 vertex-centred nodes, interior ones moved by up to jitter dp.
InitialParticles square_nodes(double jitter, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter * kDp, jitter * kDp);
  InitialParticles p;
  p.dimension = 2;
  for (int j = 0; j <= kCells; ++j)
    for (int i = 0; i <= kCells; ++i) {
      const bool inside = i > 0 && i < kCells && j > 0 && j < kCells;
      Point3 x{i * kDp, j * kDp, 0};
      if (inside) x[0] += u(rng), x[1] += u(rng);
      unsigned char surface = 0;
      if (i == 0) surface |= 1u;
      if (i == kCells) surface |= 2u;
      if (j == 0) surface |= 4u;
      if (j == kCells) surface |= 8u;
      const double lx = (i == 0 || i == kCells) ? 0.5 * kDp : kDp, ly = (j == 0 || j == kCells) ? 0.5 * kDp : kDp;
      p.position.push_back(x);
      p.velocity.push_back(Point3{kA[0][0] * x[0] + kA[0][1] * x[1], kA[1][0] * x[0] + kA[1][1] * x[1], 0});
      p.body.push_back(0);
      p.constrained.push_back(0);
      p.volume.push_back(lx * ly);
      p.surface.push_back(surface);
    }
  p.body_range.push_back({0, long(p.position.size())});
  p.constrained_count.push_back(0);
  return p;
}

// max over interior nodes of |dv| rho V0 / (dt |sigma| dp) after one step,
// |sigma| the largest von Mises stress (uniform in an exact run).
double patch_residual(const std::string& rkpm, double jitter, double reach = 2 * kDp) {
  const Scene scene = square_scene(rkpm);
  const InitialParticles init = square_nodes(jitter, 7);
  auto solver = make_solver(scene, init, SolverOptions{});
  solver->initialize();
  const Snapshot s0 = solver->snapshot();
  const double dt = solver->next_dt();
  solver->step();
  const Snapshot s1 = solver->snapshot();
  double sigma = 0;
  for (const auto& f : s1.fields)
    if (f.name == "von_mises")
      for (double v : f.values) sigma = std::max(sigma, v);
  EXPECT_GT(sigma, 0);
  double worst = 0;
  for (size_t k = 0; k < s1.n; ++k) {
    const size_t id = size_t(s1.id[k]);
    const Point3& X = init.position[id];
    // Nodes whose support (a = 2 dp; a box reaches 2 sqrt 2 dp) reaches no
    // boundary face: the others carry the boundary term sum_f Psi_I sigma
    // a_f, which tractions balance.
    const double a = reach * (1 + 1e-9), far = kCells * kDp - a;
    const bool inside = X[0] >= a && X[0] <= far && X[1] >= a && X[1] <= far;
    if (!inside) continue;
    size_t k0 = 0;
    while (size_t(s0.id[k0]) != id) ++k0;
    const double dv =
        std::hypot(s1.velocity[3 * k] - s0.velocity[3 * k0], s1.velocity[3 * k + 1] - s0.velocity[3 * k0 + 1]);
    worst = std::max(worst, dv * init.volume[id] / (dt * sigma * kDp));
  }
  return worst;
}

}  // namespace

TEST(RkpmPatchTest, ConformingLatticeCellsAreExact) {
  const double snni = patch_residual(R"({"integration": "snni"})", 0.0);
  const double nsni = patch_residual(R"({"integration": "nsni"})", 0.0);
  EXPECT_LE(snni, 1e-13);
  EXPECT_LE(nsni, 1e-13);
  std::printf("patch residual, lattice: SNNI %.3g, SNNI + NSNI %.3g\n", snni, nsni);
}

TEST(RkpmPatchTest, NonConformingCellsNeedTheVariationalCorrection) {
  const double off = patch_residual(R"({"integration": "snni", "variational_correction": false})", 0.2);
  const double on = patch_residual(R"({"integration": "snni", "variational_correction": true})", 0.2);
  const double on_nsni = patch_residual(R"({"integration": "nsni", "variational_correction": true})", 0.2);
  EXPECT_GT(off, 1e-2);  // plain SNNI fails the patch test on non-conforming cells
  EXPECT_LE(on, 1e-13);
  EXPECT_LE(on_nsni, 1e-13);
  std::printf("patch residual, perturbed: VC off %.3g, VC on %.3g, VC on + NSNI %.3g\n", off, on, on_nsni);
}

// The same with box supports (`support_shape: box`, rkpm.md 1.1-1.2).
TEST(RkpmPatchTest, BoxSupportsPassToo) {
  const double reach = 2 * std::sqrt(2.0) * kDp;
  const double lattice = patch_residual(R"({"integration": "nsni", "support_shape": "box"})", 0.0, reach);
  const double off =
      patch_residual(R"({"integration": "snni", "variational_correction": false, "support_shape": "box"})", 0.2, reach);
  const double on = patch_residual(R"({"integration": "nsni", "support_shape": "box"})", 0.2, reach);
  EXPECT_LE(lattice, 1e-13);
  EXPECT_GT(off, 1e-2);
  EXPECT_LE(on, 1e-13);
  std::printf("patch residual, box supports: lattice + NSNI %.3g, perturbed VC off %.3g, VC on + NSNI %.3g\n", lattice,
              off, on);
}
