// Test helper: runs a scene of configs/ through the library (no files
// written) and records the probes at every step.
#pragma once
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "host/scene/particle_generator.hpp"
#include "host/scene/scene_reader.hpp"
#include "host/solver/numerical_failure.hpp"
#include "host/solver/solver.hpp"

namespace mfsd::test {

struct Trace {
  std::vector<double> time;
  std::vector<std::vector<ProbeSample>> probes;  // [sample][probe]
  std::vector<EnergySample> energies;            // at `energy_every` steps
  std::unique_ptr<Solver> solver;
  SetupReport setup;
};

// `name` is a file of configs/, or of tests/regression/scenes/ when it starts with "scenes/".
inline SceneDocument load_config(const std::string& name, const std::vector<std::string>& overrides) {
  const std::string dir = name.rfind("scenes/", 0) == 0 ? "/tests/regression/" : "/configs/";
  return load_scene_file(std::string(MFSD_SOURCE_DIR) + dir + name, overrides);
}

// Runs to the scene's end time (or max_steps); samples probes every step.
inline Trace run_config(const std::string& name, const std::vector<std::string>& overrides,
                        Precision precision = Precision::double_precision, long max_steps = 0, long energy_every = 0,
                        int threads = 0, SolverOptions::PairLoop pair_loop = SolverOptions::PairLoop::automatic) {
  const SceneDocument doc = load_config(name, overrides);
  const InitialParticles particles = generate_particles(doc.scene);
  SolverOptions o;
  o.precision = precision;
  o.threads = threads;
  o.pair_loop = pair_loop;
  Trace t;
  t.solver = make_solver(doc.scene, particles, o);
  t.solver->initialize();
  t.setup = t.solver->setup_report();
  const double end = doc.scene.solver.end_time;
  t.time.push_back(0);
  t.probes.push_back(t.solver->probes());
  if (energy_every) t.energies.push_back(t.solver->energies());
  while (t.solver->time() < end * (1 - 1e-12) && (max_steps == 0 || t.solver->steps() < max_steps)) {
    t.solver->limit_next_dt(end - t.solver->time());
    t.solver->step();
    t.time.push_back(t.solver->time());
    t.probes.push_back(t.solver->probes());
    if (energy_every && t.solver->steps() % energy_every == 0) t.energies.push_back(t.solver->energies());
  }
  return t;
}

// Oscillation period from the zero crossings of s(t) = y(t) - y(0): a least-
// squares fit t_k = t_0 + k T/2 over all crossings (the start is one).
// Runs a scene that must stop with a NumericalFailure; returns its message
// ("" and a test failure when it ran to the end).
inline std::string numerical_failure_message(const std::string& name, const std::vector<std::string>& overrides) {
  try {
    run_config(name, overrides);
  } catch (const NumericalFailure& e) {
    return e.what();
  }
  ADD_FAILURE() << name << " ran without a numerical failure";
  return "";
}

inline double oscillation_period(const std::vector<double>& t, const std::vector<double>& y) {
  std::vector<double> crossings{t.front()};
  const double y0 = y.front();
  for (size_t i = 2; i < t.size(); ++i) {
    const double a = y[i - 1] - y0, b = y[i] - y0;
    if (a != 0 && a * b <= 0) crossings.push_back(t[i - 1] + (t[i] - t[i - 1]) * a / (a - b));
  }
  const double n = double(crossings.size());
  if (n < 3) return 0;
  double sk = 0, st = 0, skk = 0, skt = 0;
  for (size_t k = 0; k < crossings.size(); ++k) {
    sk += double(k);
    st += crossings[k];
    skk += double(k) * double(k);
    skt += double(k) * crossings[k];
  }
  const double half = (n * skt - sk * st) / (n * skk - sk * sk);
  return 2 * half;
}

}  // namespace mfsd::test
