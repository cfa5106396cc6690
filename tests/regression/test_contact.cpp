// Contact between bodies (scene key contact, kernels/contact): two free
// elastic blocks meeting off-centre (tests/regression/scenes/
// colliding_blocks_2d.json). Total momentum is kept to round-off (pair forces
// are exactly opposite), particle centres of the two bodies never come closer
// than a stated fraction of dp, the blocks leave with the momentum exchange
// of a collision, and the energy balance including the contact work closes
// to second order in dt.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "scene_runner.hpp"

using namespace mfsd;

namespace {

struct CollisionRun {
  double momentum_error = 0;  // largest |p(t) - p(0)| / |p_left(0)|
  double min_distance = 1e300;
  double left_px0 = 0, left_px = 0;  // x-momentum of the left block, start and end
  double left_py = 0;                // y-momentum of the left block at the end (friction)
  double balance_drift = 0;          // largest |balance - E0| / E0
  double contact_work = 0;
  long contact_steps = 0;
};

// Momentum component a of the left body from a snapshot (equal particle masses m).
double left_momentum(const Snapshot& s, double m, int a) {
  double p = 0;
  for (size_t i = 0; i < s.n; ++i)
    if (s.body[i] == 0) p += m * s.velocity[3 * i + size_t(a)];
  return p;
}

CollisionRun collide(const std::vector<std::string>& overrides, Precision precision = Precision::double_precision) {
  const SceneDocument doc = test::load_config("scenes/colliding_blocks_2d.json", overrides);
  const InitialParticles particles = generate_particles(doc.scene);
  SolverOptions o;
  o.precision = precision;
  auto solver = make_solver(doc.scene, particles, o);
  solver->initialize();
  const double dp = doc.scene.bodies[0].spacing, m = doc.scene.bodies[0].material.density * dp * dp;
  CollisionRun r;
  const EnergySample e0 = solver->energies();
  const double E0 = e0.bodies[0].balance() + e0.bodies[1].balance();
  r.left_px0 = left_momentum(solver->snapshot(), m, 0);
  const double end = doc.scene.solver.end_time;
  while (solver->time() < end * (1 - 1e-12)) {
    solver->limit_next_dt(end - solver->time());
    solver->step();
    const Snapshot s = solver->snapshot();
    const EnergySample e = solver->energies();
    for (int a = 0; a < 2; ++a)
      r.momentum_error = std::max(r.momentum_error, std::abs(e.momentum[a] - e0.momentum[a]) / std::abs(r.left_px0));
    const double cw = e.bodies[0].contact_work + e.bodies[1].contact_work;
    if (cw != r.contact_work) ++r.contact_steps;
    r.contact_work = cw;
    r.balance_drift = std::max(r.balance_drift, std::abs(e.bodies[0].balance() + e.bodies[1].balance() - E0) / E0);
    for (size_t i = 0; i < s.n; ++i) {
      if (s.body[i] != 0) continue;
      for (size_t j = 0; j < s.n; ++j)
        if (s.body[j] == 1)
          r.min_distance = std::min(r.min_distance, std::hypot(s.position[3 * i] - s.position[3 * j],
                                                               s.position[3 * i + 1] - s.position[3 * j + 1]));
    }
    r.left_px = left_momentum(s, m, 0);
    r.left_py = left_momentum(s, m, 1);
  }
  return r;
}

}  // namespace

TEST(Contact, FreeCollisionKeepsMomentumAndSeparatesTheBodies) {
  // Elastic (e = 1), frictionless, 50 m/s each, steel, dp = 1 mm.
  const CollisionRun r = collide({});
  std::printf(
      "contact steps %ld, momentum error %.3g, closest approach %.4g dp, left x-momentum %.4g -> %.4g, "
      "balance drift %.3g, contact work %.4g J/m\n",
      r.contact_steps, r.momentum_error, r.min_distance / 1e-3, r.left_px0, r.left_px, r.balance_drift, r.contact_work);
  EXPECT_GT(r.contact_steps, 20);
  EXPECT_LT(r.momentum_error, 1e-12);       // action-reaction, to round-off
  EXPECT_GT(r.min_distance, 0.9 * 1e-3);    // interpenetration < 10 % of dp
  EXPECT_LT(r.left_px, -0.3 * r.left_px0);  // the left block bounced back
  EXPECT_LT(r.balance_drift, 0.02);
}

TEST(Contact, RkpmBodiesCollide) {
  // The same collision of two semi-Lagrangian RKPM bodies (the contact is the
  // platform's). The momentum is kept to round-off, also by the default
  // (VC, row-sum mass: the two terms that are not conservative in general,
  // test_contact_rigid.cpp; here the cells stay nearly conforming: 2e-15).
  // The energy balance drifts by 3.3 % (TLSPH: below 2 %; open: the
  // hypo-elastic work integral through a 50 m/s impact, not yet studied).
  const std::vector<std::string> rkpm = {"solver.method=rkpm", "solver.hourglass=null", "solver.damping=null",
                                         "bodies.left.material.model=linear_elastic",
                                         "bodies.right.material.model=linear_elastic"};
  std::vector<std::string> conservative = rkpm;
  conservative.push_back("solver.rkpm.variational_correction=false");
  conservative.push_back("solver.rkpm.mass=nodal");
  const CollisionRun c = collide(conservative), d = collide(rkpm);
  std::printf(
      "RKPM: contact steps %ld, momentum error %.3g (default: %.3g), closest approach %.4g dp, left "
      "x-momentum %.4g -> %.4g, balance drift %.3g\n",
      c.contact_steps, c.momentum_error, d.momentum_error, c.min_distance / 1e-3, c.left_px0, c.left_px,
      c.balance_drift);
  EXPECT_GT(c.contact_steps, 20);
  EXPECT_LT(c.momentum_error, 1e-12);
  EXPECT_GT(c.min_distance, 0.9 * 1e-3);
  EXPECT_LT(c.left_px, -0.3 * c.left_px0);
  EXPECT_LT(c.balance_drift, 0.04);
  EXPECT_LT(d.momentum_error, 1e-12);
}

TEST(Contact, FrictionAndRestitutionDissipateAndKeepMomentum) {
  // Head-on (offset 0), the right block sliding up at 10 m/s; the particle
  // rows are 0.2 dp out of line when they meet. Measured left y-momentum at
  // the end: -16.6 kg m/s per m frictionless, -1.03 with mu = 0.5 (left
  // x-momentum at the start: 39.3). Frictionless, the pair normals tilt with
  // the rows' offset and push the left block down: a pairwise contact surface
  // is bumpy at the scale dp (theory.md, "Contact"); friction drags it up.
  const CollisionRun elastic = collide({"constants.offset=0"});
  const CollisionRun lossy = collide({"constants.offset=0", "contact.restitution=0.5", "contact.friction=0.5"});
  EXPECT_LT(lossy.momentum_error, 1e-12);
  EXPECT_LT(lossy.contact_work, elastic.contact_work - 0.02 * 2100.0);  // the pair law takes energy
  // Friction drags the left block along the right one's sliding (+y) motion.
  std::printf("left block y-momentum: frictionless %.4g, friction 0.5 %.4g (kg m/s per m)\n", elastic.left_py,
              lossy.left_py);
  EXPECT_GT(lossy.left_py, elastic.left_py + 0.25 * lossy.left_px0);
  EXPECT_LT(lossy.balance_drift, 0.03);  // the loss is in contact_work (measured drift 2.0 % at CFL 0.6)
}

TEST(Contact, EnergyBalanceConvergesSecondOrder) {
  // With e = 1 the net contact work after separation is a time-step error.
  // Measured drift 5.4e-3, 1.3e-3, 3.3e-4 at CFL 0.6, 0.3, 0.15; net contact
  // work -8.7, 0.62, -0.27 J/m of 2100 J/m.
  const CollisionRun coarse = collide({"solver.cfl=0.3"});
  const CollisionRun fine = collide({"solver.cfl=0.15"});
  std::printf("CFL 0.3: drift %.3g, contact work %.4g J/m; CFL 0.15: drift %.3g, contact work %.4g J/m\n",
              coarse.balance_drift, coarse.contact_work, fine.balance_drift, fine.contact_work);
  EXPECT_LT(fine.balance_drift, 0.35 * coarse.balance_drift);
  EXPECT_LT(std::abs(fine.contact_work), 2.5e-4 * 2100.0);
  EXPECT_LT(fine.balance_drift, 1e-3);
}

TEST(Contact, FloatRunFollowsDouble) {
  const CollisionRun d = collide({});
  const CollisionRun f = collide({}, Precision::single_precision);
  EXPECT_NEAR(f.left_px / f.left_px0, d.left_px / d.left_px0, 0.02);
  EXPECT_GT(f.min_distance, 0.9 * 1e-3);
  EXPECT_LT(f.momentum_error, 1e-5);
}

TEST(Contact, SelfContactOfADisconnectedBodyMatchesTwoBodies) {
  // The two blocks as one body (a union of two boxes, the same particles):
  // with self_contact its distant parts touch exactly as two bodies do;
  // without it they pass through each other.
  const std::string one_body =
      R"J(bodies=[{"name": "pair", "spacing": "dp", "geometry": {"union": [{"box": {"min": ["-a - dp", 0], "max": ["-dp", "a"]}}, {"box": {"min": ["dp", "offset * a"], "max": ["a + dp", "(1 + offset) * a"]}}]}, "material": {"model": "neo_hookean", "density": 7850, "youngs_modulus": 200e9, "poisson_ratio": 0.3}, "initial_velocity": {"x": "if(x0 < 0, v0, -v0)", "y": "if(x0 < 0, 0, 0.2 * v0)"}}])J";
  auto final_positions = [&](const std::vector<std::string>& overrides, bool contact = true) {
    SceneDocument doc = test::load_config("scenes/colliding_blocks_2d.json", {});
    if (!contact) doc.source.erase("contact");
    doc = load_scene_text(doc.source.dump(), "colliding_blocks_2d", overrides);
    const InitialParticles particles = generate_particles(doc.scene);
    auto solver = make_solver(doc.scene, particles, SolverOptions{});
    solver->initialize();
    while (solver->time() < 4e-5 * (1 - 1e-12)) {
      solver->limit_next_dt(4e-5 - solver->time());
      solver->step();
    }
    const Snapshot s = solver->snapshot();
    // Keyed by the reference position (the ids of the union run in lattice order).
    std::map<std::pair<long, long>, std::array<double, 3>> x;
    for (size_t i = 0; i < s.n; ++i) {
      const double X = s.position[3 * i] - s.displacement[3 * i], Y = s.position[3 * i + 1] - s.displacement[3 * i + 1];
      x[{std::lround(X / 1e-4), std::lround(Y / 1e-4)}] = {s.position[3 * i], s.position[3 * i + 1], s.velocity[3 * i]};
    }
    return x;
  };
  const auto two = final_positions({});
  const auto self = final_positions({one_body, "contact.self_contact=[\"pair\"]"});
  const auto none = final_positions({one_body}, false);
  ASSERT_EQ(two.size(), self.size());
  double diff = 0, left_vx_self = 0, left_vx_none = 0;
  for (const auto& [X, a] : two) {
    ASSERT_TRUE(self.count(X) && none.count(X));
    const auto& b = self.at(X);
    diff = std::max(diff, std::hypot(a[0] - b[0], a[1] - b[1]));
    if (X.first < 0) left_vx_self += b[2], left_vx_none += none.at(X)[2];
  }
  EXPECT_LT(diff, 1e-12);        // the same pairs, the same forces
  EXPECT_LT(left_vx_self, 0.0);  // bounced
  EXPECT_GT(left_vx_none, 0.0);  // passed through: nothing pushed back
}
