// Dynamic relaxation (kernels/tlsph/relaxation.hpp, host/solver/tlsph/tlsph_relaxation.hpp):
// the coloured Gauss-Seidel sweeps keep each body's momentum to round-off and
// remove exactly the kinetic energy they report; for a small viscosity a step
// equals the explicit SPH Laplacian step summed by brute force over all
// particle pairs (second order in eta dt); a large viscosity drives a body to
// its mean velocity; cells of one colour touch disjoint particles; the random
// choice relaxes the requested fraction of steps and repeats with its seed.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "host/solver/tlsph/tlsph_relaxation.hpp"
#include "kernels/sph/wendland_c2.hpp"
#include "particle_fixture.hpp"

using namespace mfsd;

namespace {

// One relaxation of a step as the solver runs it: the sweeps, the step's
// synchronisation, then the dissipation sums.
template <class R, class View>
void relax_step(R& r, const View& view, double t, double dt) {
  DeviceResults<Cpu> results;
  r.apply(view, t, dt, results);
  results.fetch();
  r.collect(results);
}

constexpr double kDp = 0.01, kRho = 1000;

template <int D>
struct RelaxationCase {
  test::Fixture<D, double> fx;
  std::vector<BodyRange> ranges;
  TlsphViews<D, double> view{};
  double h;

  // Two bodies side by side (x < and > the middle), random velocities.
  static std::vector<Vec<D, double>> points(const int* n) { return test::lattice<D>(n, kDp, 0.1, 7); }
  static std::vector<int> bodies(const std::vector<Vec<D, double>>& x, const int* n) {
    std::vector<int> b(x.size());
    for (size_t i = 0; i < x.size(); ++i) b[i] = i % size_t(n[0]) < size_t(n[0] / 2) ? 0 : 1;
    return b;
  }
  // The fixture wants each body a contiguous range: sort the lattice by body first.
  static std::vector<Vec<D, double>> sorted(const int* n) {
    const auto x = points(n);
    const auto b = bodies(x, n);
    std::vector<Vec<D, double>> out;
    for (int body = 0; body < 2; ++body)
      for (size_t i = 0; i < x.size(); ++i)
        if (b[i] == body) out.push_back(x[i]);
    return out;
  }
  static std::vector<int> sorted_bodies(const int* n) {
    const auto x = points(n);
    auto b = bodies(x, n);
    std::sort(b.begin(), b.end());
    return b;
  }

  explicit RelaxationCase(const int* n)
      : fx(sorted(n), kDp, 1.15 * kDp, true, sorted_bodies(n)), h(1.15 * kDp) {
    const auto body = fx.template host<int>(field::body);
    Index split = 0;
    while (split < Index(body.size()) && body[size_t(split)] == 0) ++split;
    ranges = {BodyRange{0, split}, BodyRange{split, Index(body.size())}};
    fx.particles.template add<Vec<D, double>>(field::velocity);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<Vec<D, double>> v(body.size());
    for (auto& w : v)
      for (int a = 0; a < D; ++a) w.v[a] = u(rng);
    from_host<Cpu>(v, fx.particles.template buffer<Vec<D, double>>(field::velocity));
    fx.particles.template add<Vec<D, double>>(field::acceleration);  // zero: no forces
    view.acceleration = fx.particles.template get<Vec<D, double>>(field::acceleration);
    view.pairs = fx.pairs.view();
    view.velocity = fx.particles.template get<Vec<D, double>>(field::velocity);
    view.volume = fx.particles.template get<double>(field::volume);
    view.reference_position = fx.particles.template get<Vec<D, double>>(field::reference_position);
  }

  std::vector<Vec<D, double>> velocity() { return fx.template host<Vec<D, double>>(field::velocity); }
  std::vector<Vec<D, double>> position() { return fx.template host<Vec<D, double>>(field::reference_position); }

  TlsphRelaxation<Cpu, D, double> relaxation(double eta, double p, unsigned long long seed = 1,
                                             const std::vector<unsigned char>& held = {}) {
    TlsphRelaxation<Cpu, D, double> r;
    r.setup(RelaxationSpec{true, eta, 0.0, p, seed, 0.0, 1e300}, ranges, {kRho, kRho}, {eta, eta}, position(), 2 * h,
            held);
    return r;
  }

  // Per body: momentum and kinetic energy.
  std::array<std::array<double, 4>, 2> sums() {
    const auto v = velocity();
    const double m = kRho * std::pow(kDp, D);
    std::array<std::array<double, 4>, 2> s{};
    for (int b = 0; b < 2; ++b)
      for (Index i = ranges[size_t(b)].begin; i < ranges[size_t(b)].end; ++i) {
        for (int a = 0; a < D; ++a) s[size_t(b)][size_t(a)] += m * v[size_t(i)].v[a];
        s[size_t(b)][3] += 0.5 * m * dot(v[size_t(i)], v[size_t(i)]);
      }
    return s;
  }
};

template <int D>
void conserves_momentum_and_reports_the_loss(const int* n) {
  RelaxationCase<D> c(n);
  auto r = c.relaxation(50.0, 1.0);
  const auto before = c.sums();
  relax_step(r, c.view, 0.0, 1e-3);
  const auto after = c.sums();
  for (size_t b = 0; b < 2; ++b) {
    for (int a = 0; a < D; ++a) EXPECT_NEAR(after[b][size_t(a)], before[b][size_t(a)], 1e-14 * before[b][3] / 1.0);
    const double loss = before[b][3] - after[b][3];
    EXPECT_GT(loss, 0.05 * before[b][3]);  // the field is rough: a strong viscosity takes much of it
    EXPECT_NEAR(r.dissipation(b), loss, 1e-12 * before[b][3]);
  }
}

TEST(Relaxation, ConservesMomentumAndReportsTheLoss2D) {
  const int n[2] = {24, 12};
  conserves_momentum_and_reports_the_loss<2>(n);
}
TEST(Relaxation, ConservesMomentumAndReportsTheLoss3D) {
  const int n[3] = {10, 6, 6};
  conserves_momentum_and_reports_the_loss<3>(n);
}

// Small eta dt: the implicit pair sweeps = the explicit step
// v_i += dt/m_i sum_j 2 eta V_i V_j (dW/dr / r)(v_i - v_j) to O((eta dt)^2).
template <int D>
void small_viscosity_matches_the_explicit_laplacian(const int* n) {
  RelaxationCase<D> c(n);
  const double dt = 1e-4, eta = 1e-3 * kRho * c.h * c.h / dt;  // eta dt / (rho h^2) = 1e-3
  const auto x = c.position();
  const auto v0 = c.velocity();
  const auto body = c.fx.template host<int>(field::body);
  const auto W = WendlandC2<D, double>::make(c.h);
  const double V = std::pow(kDp, D), m = kRho * V;
  std::vector<Vec<D, double>> explicit_change(x.size());
  for (size_t i = 0; i < x.size(); ++i)
    for (size_t j = 0; j < x.size(); ++j) {
      const double r = norm(x[i] - x[j]);
      if (j == i || body[i] != body[j] || r >= W.cutoff()) continue;
      explicit_change[i] = explicit_change[i] + (v0[i] - v0[j]) * (dt / m * 2 * eta * V * V * W.dW(r) / r);
    }
  auto relax = c.relaxation(eta, 1.0);
  relax_step(relax, c.view, 0.0, dt);
  const auto v1 = c.velocity();
  double diff = 0, size = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    const auto d = (v1[i] - v0[i]) - explicit_change[i];
    diff += dot(d, d);
    size += dot(explicit_change[i], explicit_change[i]);
  }
  std::printf("relative difference to the explicit step %.3g\n", std::sqrt(diff / size));
  EXPECT_GT(size, 0.0);
  EXPECT_LT(std::sqrt(diff / size), 0.02);  // second order: O(10 eta dt / (rho h^2)) with ~20-50 neighbours
}

TEST(Relaxation, SmallViscosityMatchesTheExplicitLaplacian2D) {
  const int n[2] = {16, 10};
  small_viscosity_matches_the_explicit_laplacian<2>(n);
}
TEST(Relaxation, SmallViscosityMatchesTheExplicitLaplacian3D) {
  const int n[3] = {8, 6, 6};
  small_viscosity_matches_the_explicit_laplacian<3>(n);
}

TEST(Relaxation, LargeViscosityGivesEachBodyItsMeanVelocity) {
  const int n[2] = {24, 12};
  RelaxationCase<2> c(n);
  auto r = c.relaxation(1e9, 1.0);
  const auto s = c.sums();
  for (int k = 0; k < 20; ++k) relax_step(r, c.view, 0.0, 1e-3);
  const auto v = c.velocity();
  const double m = kRho * kDp * kDp;
  for (size_t b = 0; b < 2; ++b) {
    const Index count = c.ranges[b].size();
    double worst = 0;
    for (Index i = c.ranges[b].begin; i < c.ranges[b].end; ++i)
      for (int a = 0; a < 2; ++a) worst = std::max(worst, std::abs(v[size_t(i)].v[a] - s[b][size_t(a)] / (m * count)));
    EXPECT_LT(worst, 1e-3);  // from velocities of size 1
  }
}

// Particles a condition holds keep their velocity and pull their free
// neighbours to it; the other body keeps its momentum; the reported removal
// is the kinetic energy the step took.
TEST(Relaxation, HeldParticlesKeepTheirVelocityAndDragTheirBody) {
  const int n[2] = {24, 12};
  RelaxationCase<2> c(n);
  const auto x = c.position();
  auto v = c.velocity();
  std::vector<unsigned char> held(x.size(), 0);
  for (Index i = c.ranges[0].begin; i < c.ranges[0].end; ++i)
    if (x[size_t(i)].v[0] < 2 * kDp) {
      held[size_t(i)] = 1;
      v[size_t(i)] = Vec<2, double>{{1.0, -2.0}};
    }
  from_host<Cpu>(v, c.fx.particles.template buffer<Vec<2, double>>(field::velocity));
  auto r = c.relaxation(1e9, 1.0, 1, held);
  const auto before = c.sums();
  for (int k = 0; k < 200; ++k) relax_step(r, c.view, 0.0, 1e-3);  // Gauss-Seidel sweeps: the holders' pull spreads
  const auto after = c.sums();
  const auto w = c.velocity();
  double held_change = 0, free_gap = 0;
  for (Index i = c.ranges[0].begin; i < c.ranges[0].end; ++i) {
    if (held[size_t(i)])
      held_change = std::max(held_change, norm(w[size_t(i)] - v[size_t(i)]));
    else
      free_gap = std::max(free_gap, norm(w[size_t(i)] - Vec<2, double>{{1.0, -2.0}}));
  }
  EXPECT_EQ(held_change, 0.0);
  EXPECT_LT(free_gap, 1e-3);
  for (int a = 0; a < 2; ++a) EXPECT_NEAR(after[1][size_t(a)], before[1][size_t(a)], 1e-14 * before[1][3]);
  for (size_t b = 0; b < 2; ++b) EXPECT_NEAR(r.dissipation(b), before[b][3] - after[b][3], 1e-12 * before[b][3]);
}

TEST(Relaxation, CellsOfOneColourTouchDisjointParticles) {
  const int n[3] = {14, 11, 9};
  RelaxationCase<3> c(n);
  auto r = c.relaxation(1.0, 1.0);
  const auto offsets = to_host<Cpu>(c.fx.pairs.offsets);
  const auto neighbor = to_host<Cpu>(c.fx.pairs.neighbor);
  int colours_used = 0;
  for (int colour = 0; colour < 27; ++colour) {
    const auto items = r.items_of_colour(colour);
    colours_used += items.empty() ? 0 : 1;
    std::vector<int> owner(neighbor.size() + offsets.size(), -1);
    for (size_t k = 0; k < items.size(); ++k)
      for (Index i : items[k]) {
        std::set<Index> touched{i};
        for (PairIndex p = offsets[size_t(i)]; p < offsets[size_t(i) + 1]; ++p) touched.insert(neighbor[size_t(p)]);
        for (Index t : touched) {
          EXPECT_TRUE(owner[size_t(t)] == -1 || owner[size_t(t)] == int(k)) << "colour " << colour << " particle " << t;
          owner[size_t(t)] = int(k);
        }
      }
  }
  EXPECT_EQ(colours_used, 27);
}

TEST(Relaxation, RandomChoiceRelaxesTheRequestedFractionAndRepeats) {
  const int n[2] = {12, 8};
  RelaxationCase<2> a(n), b(n), c(n);
  auto ra = a.relaxation(10.0, 0.25, 5), rb = b.relaxation(10.0, 0.25, 5), rc = c.relaxation(10.0, 0.25, 6);
  for (int k = 0; k < 4000; ++k) {
    relax_step(ra, a.view, 0.0, 1e-5);
    relax_step(rb, b.view, 0.0, 1e-5);
    relax_step(rc, c.view, 0.0, 1e-5);
  }
  EXPECT_NEAR(ra.relaxed_steps() / 4000.0, 0.25, 0.03);
  EXPECT_NEAR(rc.relaxed_steps() / 4000.0, 0.25, 0.03);
  const auto va = a.velocity(), vb = b.velocity(), vc = c.velocity();
  double same = 0, other = 0;
  for (size_t i = 0; i < va.size(); ++i) {
    same = std::max(same, norm(va[i] - vb[i]));
    other = std::max(other, norm(va[i] - vc[i]));
  }
  EXPECT_EQ(same, 0.0);  // the same seed repeats the run exactly
  EXPECT_GT(other, 0.0);
}

}  // namespace
