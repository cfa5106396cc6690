// Clamps, velocity conditions, walls and loads of a run on one backend (any
// method): the
// selected particles (in the solver's order), the compiled expressions on
// the device, and the work and force sums they produce for energies.csv and
// boundary_forces.csv. The functors are in kernels/bc/conditions.hpp.
// Include after the backend header.
#pragma once
#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "host/backend/algorithms.hpp"
#include "host/backend/device_results.hpp"
#include "host/expr/expression_error.hpp"
#include "host/expr/program.hpp"
#include "host/scene/active_potential.hpp"
#include "host/scene/particle_expressions.hpp"
#include "host/scene/particle_generator.hpp"
#include "host/scene/scene_error.hpp"
#include "host/solver/common/kinematics.hpp"
#include "host/solver/numerical_failure.hpp"
#include "host/solver/solver.hpp"
#include "kernels/bc/conditions.hpp"

namespace mfsd {

template <class B, int D, class Real>
class Conditions {
 public:
  // `where[id]` is the current index of the particle with original id `id`.
  // Compiles the expressions of every condition and load for Real (before
  // any output exists: a constant beyond float range is an input error).
  void compile(const Scene& scene) {
    scene_ = &scene;
    body_external_work_.assign(scene.bodies.size(), 0.0);
    body_boundary_work_.assign(scene.bodies.size(), 0.0);
    std::map<std::string, size_t> body_index;
    for (size_t b = 0; b < scene.bodies.size(); ++b) body_index[scene.bodies[b].name] = b;
    for (size_t c = 0; c < scene.clamps.size(); ++c) {
      Clamp k;
      k.name = scene.clamps[c].name;
      k.body = body_index.at(scene.clamps[c].body);
      clamps_.push_back(std::move(k));
    }
    for (const WallSpec& w : scene.walls) {
      Wall wall;
      wall.spec = &w;
      for (size_t b = 0; b < scene.bodies.size(); ++b)
        if (w.bodies.empty() || std::find(w.bodies.begin(), w.bodies.end(), scene.bodies[b].name) != w.bodies.end())
          wall.bodies.push_back(b);
      walls_.push_back(wall);
    }
    for (size_t c = 0; c < scene.conditions.size(); ++c) {
      const ConditionSpec& spec = scene.conditions[c];
      auto cond = std::make_unique<Condition>();
      cond->spec = &spec;
      cond->body = body_index.at(spec.body);
      const char* axis[3] = {"x", "y", "z"};
      for (int a = 0; a < D; ++a) {
        ComponentValue<Real>& cv = cond->component[a];
        cv = ComponentValue<Real>{ComponentValue<Real>::none, Real(0), {nullptr, 0, nullptr, 0}};
        if (spec.value[size_t(a)].empty()) continue;
        const std::string path = condition_path(c) + "/" + axis[a];
        cond->program[a] = compile_particle_expression(spec.value[size_t(a)], scene, cond->body, path);
        cv = compile_component(cond->program[a], path, cond->code[a], cond->consts[a]);
      }
      conditions_.push_back(std::move(cond));
    }
    for (size_t b = 0; b < scene.bodies.size(); ++b) {
      const MaterialSpec& mat = scene.bodies[b].material;
      if (mat.model != MaterialModel::holzapfel_ogden || !mat.holzapfel_ogden.active.enabled) continue;
      if (!mat.holzapfel_ogden.active.per_step) continue;  // evaluated at set-up (particle_generator.cpp)
      const std::string path = active_potential_path(b);
      expr::Program p = active_potential_program(scene, b);  // compiled by the scene reader
      auto a = std::make_unique<ActivePotential>();
      a->body = b;
      a->path = path;
      a->k = mat.holzapfel_ogden.active.tension_per_potential;
      a->component = compile_component(p, path, a->code, a->consts);
      a->program = std::move(p);
      potentials_.push_back(std::move(a));
    }
  }

  // The selected particles, after reordering: `where[id]` is the current
  // index of the particle with original id `id`; `id` the id field (for
  // error reports).
  void setup(const InitialParticles& init, const std::vector<Index>& where, const Index* id,
             const std::vector<BodyRange>& ranges) {
    id_ = id;
    ranges_ = ranges;
    for (size_t c = 0; c < clamps_.size(); ++c) upload_indices(init.clamp_particles[c], where, clamps_[c].particles);
    for (size_t c = 0; c < conditions_.size(); ++c) {
      const auto& sel = init.condition_particles[c];
      upload_indices(sel.ids, where, conditions_[c]->particles);
      std::vector<Real> area(sel.area.begin(), sel.area.end());
      from_host<B>(area, conditions_[c]->area);
      conditions_[c]->count = sel.ids.size();
    }
  }

  bool empty() const { return clamps_.empty() && conditions_.empty() && potentials_.empty(); }

  // Time-dependent active potentials at time t (the stress stage's time,
  // before it): active_tension = k V_m(t) on their bodies. A run-time
  // expression error is reported by collect().
  void apply_fields(const Kinematics<D, Real>& v, Real* active_tension, double t, double dt, long step,
                    DeviceResults<B>& results) {
    for (auto& a : potentials_) {
      const ComponentValue<Real> none{ComponentValue<Real>::none, Real(0), {nullptr, 0, nullptr, 0}};
      ActiveTensionFunctor<D, Real> f{{a->component, none, none},
                                      Real(a->k),
                                      Real(t),
                                      Real(dt),
                                      Real(scene_->bodies[a->body].spacing),
                                      ranges_[a->body].begin,
                                      v.reference_position,
                                      v.displacement,
                                      v.velocity,
                                      active_tension};
      pending_.push_back(Pending{
          nullptr, nullptr, nullptr, a.get(), a->body, &body_external_work_, t, 0.0, step,
          results.reduce(Index(0), ranges_[a->body].size(), f, ConditionSums<Real>::zero(), ConditionSumsCombine{})});
    }
  }

  // Loads at t + dt/2, after the force stage (t: time at the start of the
  // step). Their sums stay in `results` until collect().
  void apply_loads(const Kinematics<D, Real>& v, double t, double dt, long step, DeviceResults<B>& results) {
    const double te = t + 0.5 * dt;
    for (auto& c : conditions_) {
      if (c->spec->type == ConditionSpec::Type::velocity) continue;
      c->force = Point3{0, 0, 0};
      if (!c->active(te)) continue;
      const Index n = Index(c->count);
      LoadFunctor<D, Real> f{selected(*c, v, te, dt),
                             c->spec->type == ConditionSpec::Type::traction ? raw(c->area) : nullptr,
                             c->spec->type == ConditionSpec::Type::point_force ? LoadType::point
                             : c->spec->type == ConditionSpec::Type::traction  ? LoadType::traction
                                                                               : LoadType::acceleration,
                             Real(1.0 / double(n)),
                             v.velocity,
                             v.acceleration};
      pending_.push_back(Pending{c.get(), nullptr, nullptr, nullptr, c->body, &body_external_work_, te, dt, step,
                                 results.reduce(Index(0), n, f, ConditionSums<Real>::zero(), ConditionSumsCombine{})});
    }
  }

  // Velocity conditions at t + dt, then clamps (clamps win where both hold).
  void apply_boundary(const Kinematics<D, Real>& v, double t, double dt, long step, DeviceResults<B>& results) {
    const double te = t + dt;
    for (auto& c : conditions_) {
      if (c->spec->type != ConditionSpec::Type::velocity) continue;
      c->force = Point3{0, 0, 0};
      if (!c->active(te)) continue;
      velocity(*c, v, te, dt, step, results);
    }
    for (auto& w : walls_) {
      w.force = Point3{0, 0, 0};
      for (size_t b : w.bodies) {
        WallFunctor<D, Real> f{{},
                               {},
                               Real(0.5 * scene_->bodies[b].spacing),
                               Real(dt),
                               ranges_[b].begin,
                               Real(scene_->bodies[b].material.density),
                               v.reference_position,
                               v.displacement,
                               v.acceleration,
                               v.volume,
                               v.velocity,
                               v.ghost};
        for (int a = 0; a < D; ++a) f.point.v[a] = Real(w.spec->point[a]), f.normal.v[a] = Real(w.spec->normal[a]);
        pending_.push_back(Pending{
            nullptr, &w, nullptr, nullptr, b, &body_boundary_work_, te, dt, step,
            results.reduce(Index(0), ranges_[b].size(), f, ConditionSums<Real>::zero(), ConditionSumsCombine{})});
      }
    }
    for (auto& k : clamps_) clamp(k, v, dt, step, results);
  }

  // Velocity conditions whose window holds t = 0, and the clamps, at set-up
  // (no reaction, no work); their results are collected like a step's.
  void apply_initial(const Kinematics<D, Real>& v, DeviceResults<B>& results) {
    for (auto& c : conditions_)
      if (c->spec->type == ConditionSpec::Type::velocity && c->active(0.0)) velocity(*c, v, 0.0, 0.0, 0, results);
    for (auto& k : clamps_) clamp(k, v, 0.0, 0, results);
  }

  // After results.fetch(): the forces and work of this step's conditions,
  // loads, walls and clamps; a run-time expression error stops the run with
  // the condition, the component, the error and the particle.
  void collect(const DeviceResults<B>& results, const Kinematics<D, Real>& v) {
    std::vector<Pending> pending;
    pending.swap(pending_);
    for (const Pending& p : pending) {
      const ConditionSums<Real> s = results.get(p.slot);
      if (p.potential) {
        if (s.error.particle != kNoConditionError) report_potential_error(*p.potential, s.error, v, p.te, p.step);
        continue;
      }
      Point3& force = p.condition ? p.condition->force : p.wall ? p.wall->force : p.clamp->force;
      for (int a = 0; a < 3; ++a) force[a] += double(s.force[a]);
      if (p.dt > 0) (*p.work)[p.body] += double(s.power) * p.dt;
      if (p.condition && s.error.particle != kNoConditionError) report_error(*p.condition, s.error, v, p.te, p.step);
    }
  }

  // The work sums and the last step's forces (checkpoints).
  void save(StateArchive& a) const {
    a.put("conditions/external_work", body_external_work_);
    a.put("conditions/boundary_work", body_boundary_work_);
    a.put("conditions/forces", force_list());
  }
  void restore(const StateArchive& a) {
    body_external_work_ = a.get<double>("conditions/external_work", long(body_external_work_.size()));
    body_boundary_work_ = a.get<double>("conditions/boundary_work", long(body_boundary_work_.size()));
    const std::vector<Point3> f = a.get<Point3>("conditions/forces", long(force_list().size()));
    size_t k = 0;
    for (auto& c : clamps_) c.force = f[k++];
    for (auto& c : conditions_) c->force = f[k++];
    for (auto& w : walls_) w.force = f[k++];
  }

  double external_work(size_t body) const { return body_external_work_[body]; }
  double boundary_work(size_t body) const { return body_boundary_work_[body]; }

  // Reactions of clamps and velocity conditions, applied forces of loads.
  std::vector<BoundaryForceSample> forces() const {
    std::vector<BoundaryForceSample> out;
    for (auto& k : clamps_) out.push_back({k.name, k.force});
    for (auto& c : conditions_) out.push_back({c->spec->name, c->force});
    for (auto& w : walls_) out.push_back({w.spec->name, w.force});
    return out;
  }

 private:
  std::vector<Point3> force_list() const {
    std::vector<Point3> f;
    for (auto& s : forces()) f.push_back(s.force);
    return f;
  }

  struct Clamp {
    std::string name;
    size_t body = 0;
    DeviceVector<B, Index> particles;
    Point3 force{0, 0, 0};
  };
  struct Wall {
    const WallSpec* spec = nullptr;
    std::vector<size_t> bodies;
    Point3 force{0, 0, 0};
  };
  struct Condition {
    const ConditionSpec* spec = nullptr;
    size_t body = 0;
    size_t count = 0;
    DeviceVector<B, Index> particles;
    DeviceVector<B, Real> area;
    expr::Program program[3];
    DeviceVector<B, expr::Instr> code[3];
    DeviceVector<B, Real> consts[3];
    ComponentValue<Real> component[3]{};
    Point3 force{0, 0, 0};
    bool active(double t) const { return t >= spec->t_start && t <= spec->t_end; }
  };

  // A time-dependent active potential of a Holzapfel-Ogden body.
  struct ActivePotential {
    size_t body = 0;
    std::string path;
    double k = 0;  // tension_per_potential
    expr::Program program;
    DeviceVector<B, expr::Instr> code;
    DeviceVector<B, Real> consts;
    ComponentValue<Real> component{};
  };

  // A compiled expression as a component: a constant, or a program whose
  // code and constants are uploaded into `code` and `consts`.
  static ComponentValue<Real> compile_component(const expr::Program& p, const std::string& path,
                                                DeviceVector<B, expr::Instr>& code, DeviceVector<B, Real>& consts) {
    if (p.is_constant()) return ComponentValue<Real>{ComponentValue<Real>::constant, Real(p.constant_value()), {}};
    expr::ProgramView<Real> view;
    try {
      view = p.template host_view<Real>();  // checks the float range
    } catch (const expr::ExpressionError& e) {
      throw SceneError(path + ": " + e.what());
    }
    from_host<B>(p.code(), code);
    from_host<B>(std::vector<Real>(view.consts, view.consts + view.n_consts), consts);
    return ComponentValue<Real>{ComponentValue<Real>::program, Real(0),
                                expr::ProgramView<Real>{raw(code), int(p.code().size()), raw(consts), view.n_consts}};
  }

  static void upload_indices(const std::vector<long>& ids, const std::vector<Index>& where,
                             DeviceVector<B, Index>& out) {
    std::vector<Index> index;
    index.reserve(ids.size());
    for (long id : ids) index.push_back(where[size_t(id)]);
    from_host<B>(index, out);
  }

  std::string condition_path(size_t c) const {
    size_t k = 0;
    for (size_t m = 0; m < c; ++m)
      if ((scene_->conditions[m].type == ConditionSpec::Type::velocity) ==
          (scene_->conditions[c].type == ConditionSpec::Type::velocity))
        ++k;
    return (scene_->conditions[c].type == ConditionSpec::Type::velocity ? "/velocity_conditions/" : "/loads/") +
           std::to_string(k);
  }

  void velocity(Condition& c, const Kinematics<D, Real>& v, double te, double dt, long step,
                DeviceResults<B>& results) {
    VelocityConditionFunctor<D, Real> f{selected(c, v, te, dt), v.acceleration, v.velocity};
    pending_.push_back(
        Pending{&c, nullptr, nullptr, nullptr, c.body, &body_boundary_work_, te, dt, step,
                results.reduce(Index(0), Index(c.count), f, ConditionSums<Real>::zero(), ConditionSumsCombine{})});
  }

  SelectedComponents<D, Real> selected(const Condition& c, const Kinematics<D, Real>& v, double te, double dt) const {
    return SelectedComponents<D, Real>{raw(c.particles),
                                       {c.component[0], c.component[1], c.component[2]},
                                       Real(scene_->bodies[c.body].material.density),
                                       Real(te),
                                       Real(dt),
                                       Real(scene_->bodies[c.body].spacing),
                                       v.reference_position,
                                       v.displacement,
                                       v.volume};
  }

  void clamp(Clamp& k, const Kinematics<D, Real>& v, double dt, long step, DeviceResults<B>& results) {
    ClampReactionFunctor<D, Real> f{raw(k.particles), Real(scene_->bodies[k.body].material.density),
                                    Real(dt),         v.volume,
                                    v.displacement,   v.velocity};
    k.force = Point3{0, 0, 0};
    // A clamp's reaction does no work (the particle does not move): power 0.
    pending_.push_back(Pending{
        nullptr, nullptr, &k, nullptr, k.body, &body_boundary_work_, 0.0, dt, step,
        results.reduce(Index(0), Index(k.particles.size()), f, ConditionSums<Real>::zero(), ConditionSumsCombine{})});
  }

  void report_error(const Condition& c, const ConditionError& error, const Kinematics<D, Real>& v, double te,
                    long step) {
    const char* axis[3] = {"x", "y", "z"};
    const expr::Program& p = c.program[error.component];
    const Index i = error.particle;
    const std::string where = reference_position_text(v, i);
    const bool load = c.spec->type != ConditionSpec::Type::velocity;
    throw NumericalFailure(
        step, te, long(copy_element<B>(id_, i)), c.spec->body,
        std::string(load ? "load '" : "velocity condition '") + c.spec->name + "' component " + axis[error.component],
        p.describe_error(expr::Status(error.status), error.pc) + " at " + where);
  }

  std::string reference_position_text(const Kinematics<D, Real>& v, Index i) const {
    const Vec<D, Real> X = copy_element<B>(v.reference_position, i);
    std::string where = "x0 = (";
    for (int a = 0; a < D; ++a) where += (a ? ", " : "") + std::to_string(double(X.v[a]));
    return where + ")";
  }

  void report_potential_error(const ActivePotential& a, const ConditionError& error, const Kinematics<D, Real>& v,
                              double t, long step) {
    const Index i = error.particle;
    throw NumericalFailure(step, t, long(copy_element<B>(id_, i)), scene_->bodies[a.body].name,
                           "active_stress potential (" + a.path + ")",
                           a.program.describe_error(expr::Status(error.status), error.pc) + " at " +
                               reference_position_text(v, i) + ", t = " + std::to_string(t));
  }

  // A reduction of this step whose sums wait in DeviceResults: the owner
  // (one of condition, wall, clamp, potential) and where its work goes.
  struct Pending {
    Condition* condition;
    Wall* wall;
    Clamp* clamp;
    ActivePotential* potential;
    size_t body;
    std::vector<double>* work;  // external or boundary work per body
    double te, dt;
    long step;
    ResultSlot<ConditionSums<Real>> slot;
  };

  const Scene* scene_ = nullptr;
  const Index* id_ = nullptr;
  std::vector<Clamp> clamps_;
  std::vector<Wall> walls_;
  std::vector<BodyRange> ranges_;
  std::vector<std::unique_ptr<Condition>> conditions_;
  std::vector<std::unique_ptr<ActivePotential>> potentials_;
  std::vector<Pending> pending_;
  std::vector<double> body_external_work_, body_boundary_work_;
};

}  // namespace mfsd
