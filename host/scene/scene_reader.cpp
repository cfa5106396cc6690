#include "host/scene/scene_reader.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

#include "host/expr/expression_error.hpp"
#include "host/expr/program.hpp"
#include "host/scene/active_potential.hpp"
#include "host/scene/body_properties.hpp"
#include "host/scene/material_plausibility.hpp"
#include "host/scene/scene_error.hpp"

namespace mfsd {

namespace {

// Names a scene constant may not take: expression variables and the
// per-body constants that body expressions receive.
const std::set<std::string> kReservedNames = {"x0", "y0", "z0", "x",  "y",  "z",  "ux", "uy", "uz",   "vx",
                                              "vy", "vz", "t",  "dt", "dx", "pi", "c0", "cs", "rho0", "h"};

// The entries of `constants` whose names occur in `text` as words.
std::map<std::string, double> named_constants(const std::string& text, const std::map<std::string, double>& constants) {
  std::map<std::string, double> named;
  auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (size_t k = 0; k < text.size();) {
    if (!word(text[k])) {
      ++k;
      continue;
    }
    size_t end = k;
    while (end < text.size() && word(text[end])) ++end;
    const auto it = constants.find(text.substr(k, end - k));
    if (it != constants.end()) named.insert(*it);
    k = end;
  }
  return named;
}

}  // namespace

Scene read_scene(const Json& doc, Json& resolved, const std::string& base_dir) {
  Scene scene;
  scene.base_dir = base_dir;
  resolved = Json::object();
  // Constants first (in file order): numbers or expressions of earlier constants.
  std::map<std::string, double> constants;
  auto eval = [&constants](const std::string& text, const std::string& path) {
    try {
      // Only the constants the text names: compile() checks every constant
      // it is given, and a scene of n constants evaluates n texts.
      expr::Program p = expr::compile(text, expr::VariableTable{}, named_constants(text, constants));
      return p.evaluate_host(nullptr);
    } catch (const expr::ExpressionError& e) {
      try {  // again with all of them, for a message that lists them
        (void)expr::compile(text, expr::VariableTable{}, constants).evaluate_host(nullptr);
      } catch (const expr::ExpressionError& all) {
        throw SceneError(path + ": " + all.what());
      }
      throw SceneError(path + ": " + e.what());
    }
  };
  JsonNode root(doc, "", resolved, eval);
  scene.name = root.string("name");
  check_file_name("/name", scene.name, "the output folder out/<name> and the snapshot files");
  scene.description = root.string("description", "");
  scene.si_units = root.choice("units", {"SI", "nondimensional"}, "SI") == "SI";
  if (!root.has("dimension")) throw SceneError("/dimension", "nothing", "2 or 3 (this key is required)");
  scene.dimension = int(root.integer("dimension", 2, 2, 3));
  const int dim = scene.dimension;

  if (auto c = root.optional_object("constants")) {
    const Json& src = doc["constants"];
    for (auto it = src.begin(); it != src.end(); ++it) {
      const std::string name = it.key();
      const std::string path = "/constants/" + name;
      if (kReservedNames.count(name))
        throw SceneError(path, "the reserved name '" + name + "'",
                         "another name (reserved: variables x0 y0 z0 x y z ux uy uz vx vy vz t dt dx, pi, and the body "
                         "constants c0 cs rho0 h)");
      if (const std::string problem = expr::name_problem(name); !problem.empty())
        throw SceneError(path, json_text(Json(name)) + ", " + problem,
                         "a name of letters, digits and '_' that starts with a letter or '_' and is neither a "
                         "function nor a reserved word (if and or skip Skip pi)");
      const double v = c->number(name, Range::any());
      constants[name] = v;
      scene.constants.emplace_back(name, v);
    }
    c->finish();
  }

  scene.solver = read_solver(root.object("solver"), dim);

  auto bodies = root.array("bodies", true, 1);
  std::set<std::string> names;
  for (size_t b = 0; b < bodies.size(); ++b) {
    JsonNode node = root.element("bodies", b, *bodies[b]);
    BodySpec body;
    body.name = node.string("name");
    const std::string body_method = node.choice("method", {"tlsph", "ulsph", "rkpm"}, to_string(scene.solver.method));
    body.method = body_method == "ulsph" ? Method::ulsph : body_method == "rkpm" ? Method::rkpm : Method::tlsph;
    if ((body.method == Method::rkpm) != (scene.solver.method == Method::rkpm))
      throw SceneError(node.key_path("method"),
                       "\"" + body_method + "\" in a scene of method \"" + to_string(scene.solver.method) + "\"",
                       "one method for every body when RKPM is involved (RKPM bodies do not yet share a scene "
                       "with SPH bodies)");
    // The settings this body runs with (solver_for: a body of the other method takes that method's defaults).
    const SolverSpec solver = solver_for(scene.solver, body.method);
    if (!names.insert(body.name).second)
      throw SceneError(node.key_path("name"), "\"" + body.name + "\"", "a name no other body has");
    body.spacing = node.number("spacing", Range::positive());
    body.geometry = read_shape(node.object("geometry"), dim, scene.base_dir);
    body.material = read_material(node.object("material"), body.spacing, dim, scene.warnings);
    if (body.material.fracture.enabled) check_file_name(node.key_path("name"), body.name, "crack_<name>.csv");
    check_method_material(body, solver, node.key_path("material"));
    if (body.material.fracture.enabled && solver.hourglass != HourglassControl::none)
      throw SceneError(
          "/solver/hourglass",
          std::string("\"") + to_string(solver.hourglass) + "\" with fracture in body \"" + body.name + "\"",
          "\"none\": the degraded stress of phase-field fracture is implemented in the standard "
          "TLSPH form (seed 001), not in the hourglass-controlled splits");
    if (body.material.model == MaterialModel::holzapfel_ogden && solver.hourglass == HourglassControl::laplacian)
      throw SceneError("/solver/hourglass",
                       std::string("\"laplacian\" with the holzapfel_ogden body \"") + body.name + "\"",
                       "\"genog\" or \"none\": the Laplacian form of seed 003 is defined for isotropic elastic "
                       "bodies; GENOG's shear term takes the Holzapfel-Ogden c = a exp[b(I1 - 3)] (seed 000)");
    if (body.material.plastic() && solver.hourglass == HourglassControl::laplacian)
      throw SceneError(node.key_path("material") + "/model",
                       std::string("\"") + to_string(body.material.model) + "\" with solver.hourglass \"laplacian\"",
                       "an elastic model, or hourglass \"genog\" or \"none\": the Laplacian form of seed 003 "
                       "is defined for elastic bodies only");
    check_body_properties(body, solver, dim, node.path());
    JsonNode v = node.object_or_empty("initial_velocity");
    const char* axes[3] = {"x", "y", "z"};
    for (int a = 0; a < dim; ++a) body.initial_velocity[size_t(a)] = v.expression(axes[a], "0");
    v.finish();
    if (auto r = node.optional_object("reference_map")) {
      const char* identity[3] = {"x0", "y0", "z0"};
      for (int a = 0; a < dim; ++a) body.reference_map[size_t(a)] = r->expression(axes[a], identity[a]);
      r->finish();
    }
    if (auto u = node.optional_object("initial_displacement")) {
      for (int a = 0; a < dim; ++a) body.initial_displacement[size_t(a)] = u->expression(axes[a], "0");
      u->finish();
    }
    node.finish();
    scene.bodies.push_back(body);
  }

  if (scene.solver.method == Method::tlsph && doc.contains("solver") && doc["solver"].is_object() &&
      doc["solver"].contains("ulsph") && std::none_of(scene.bodies.begin(), scene.bodies.end(), [](const BodySpec& b) {
        return b.method == Method::ulsph;
      }))
    throw SceneError("/solver/ulsph", "ULSPH settings in a scene without ULSPH bodies",
                     "solver.method \"ulsph\" or bodies[].method \"ulsph\", or no solver.ulsph");

  auto clamps = root.array("clamps", false);
  std::set<std::string> boundary_names;  // clamps, conditions, loads, walls: columns of boundary_forces.csv
  for (size_t c = 0; c < clamps.size(); ++c) {
    JsonNode node = root.element("clamps", c, *clamps[c]);
    ClampSpec clamp;
    clamp.name = read_unique_name(node, "clamp" + std::to_string(c), boundary_names, "clamp");
    clamp.body = read_body_name(node, "body", names);
    clamp.region = read_shape(node.object("region"), dim, scene.base_dir);
    node.finish();
    scene.clamps.push_back(clamp);
  }

  if (!scene.solver.deformed_time_step_given) scene.solver.deformed_time_step = has_plastic_body(scene);

  read_rigid_bodies(root, scene);
  read_conditions(root, scene, names, boundary_names);
  read_contact(root, scene);
  for (const std::string& r : scene.contact.rigid_bodies)
    if (!boundary_names.insert(r).second)
      throw SceneError("/contact/rigid_bodies", "\"" + r + "\"",
                       "a rigid body whose name no clamp, condition, load or wall has (its reaction is a column of "
                       "boundary_forces.csv)");
  read_measure_planes(root, scene, names);
  read_observers(root, scene, names);

  auto probes = root.array("probes", false);
  std::set<std::string> probe_names;
  for (size_t p = 0; p < probes.size(); ++p) {
    JsonNode node = root.element("probes", p, *probes[p]);
    ProbeSpec probe;
    probe.name = node.string("name");
    if (!probe_names.insert(probe.name).second)
      throw SceneError(node.key_path("name"), "\"" + probe.name + "\"", "a name no other probe has");
    const auto x = node.vector("point", size_t(dim), Range::any());
    for (int a = 0; a < dim; ++a) probe.point[a] = x[a];
    probe.radius = node.number("radius", 0.0, Range::non_negative());
    auto fields = node.array("fields", false);
    const std::set<std::string> allowed = {"position", "displacement",     "velocity",       "von_mises",
                                           "J",        "von_mises_strain", "plastic_strain", "phase_field"};
    for (size_t k = 0; k < fields.size(); ++k) {
      const Json& f = *fields[k];
      const std::string fp = node.key_path("fields") + "/" + std::to_string(k);
      if (!f.is_string() || !allowed.count(f.get<std::string>()))
        throw SceneError(fp, json_text(f),
                         "one of \"position\", \"displacement\", \"velocity\", \"von_mises\", \"J\", "
                         "\"von_mises_strain\", \"plastic_strain\", \"phase_field\"");
      probe.fields.push_back(f.get<std::string>());
      node.resolved()["fields"][k] = f;
    }
    if (probe.fields.empty()) {
      probe.fields = {"position"};
      node.resolved()["fields"] = Json::array({"position"});
    }
    node.finish();
    scene.probes.push_back(probe);
  }

  {
    JsonNode out = root.object_or_empty("output");
    // At most 1e9 rows: smaller intervals are typing errors (5e-324), and the
    // run would never end writing them.
    const double shortest = scene.solver.end_time * 1e-9;
    const Range interval{shortest, 1e308, false, false, "an interval of at least end_time / 1e9 (" + [&] {
                           std::ostringstream o;
                           o << shortest;
                           return o.str();
                         }() + " s)"};
    scene.output.interval = out.number("interval", scene.solver.end_time / 100.0, interval);
    scene.output.probe_interval = out.number("probe_interval", scene.output.interval / 20.0, interval);
    scene.output.vtu = out.boolean("vtu", true);
    // Checkpoints every checkpoint_interval of simulated time (0: none).
    scene.output.checkpoint_interval = out.number("checkpoint_interval", 0.0, Range::non_negative());
    if (scene.output.checkpoint_interval > 0 && scene.output.checkpoint_interval < shortest)
      throw SceneError("/output/checkpoint_interval", std::to_string(scene.output.checkpoint_interval),
                       "0 (no checkpoints) or an interval of at least end_time / 1e9");
    out.finish();
    // Legal but heavy: say how much a run will write before it starts.
    const double snapshots = scene.solver.end_time / scene.output.interval;
    const double rows = scene.solver.end_time / scene.output.probe_interval;
    std::ostringstream w;
    if (scene.output.vtu && snapshots > kManySnapshots)
      w << "/output/interval: the run writes about " << std::setprecision(3) << snapshots
        << " snapshots (VTU files); more than " << kManySnapshots << " is rarely meant";
    else if (rows > kManyRows)
      w << "/output/probe_interval: the run writes about " << std::setprecision(3) << rows
        << " rows per CSV file; more than " << kManyRows << " is rarely meant";
    if (!w.str().empty()) scene.warnings.push_back(w.str());
  }

  // Bounds: default = the bodies' bounding box grown by its size on every side.
  Bounds bb = scene.bodies[0].geometry.bounds(dim);
  for (auto& b : scene.bodies) {
    const Bounds c = b.geometry.bounds(dim);
    for (int a = 0; a < dim; ++a) bb.min[a] = std::min(bb.min[a], c.min[a]), bb.max[a] = std::max(bb.max[a], c.max[a]);
  }
  double size = 0;
  for (int a = 0; a < dim; ++a) size = std::max(size, bb.max[a] - bb.min[a]);
  std::vector<double> lo(static_cast<size_t>(dim)), hi(static_cast<size_t>(dim));
  for (int a = 0; a < dim; ++a) lo[size_t(a)] = bb.min[a] - size, hi[size_t(a)] = bb.max[a] + size;
  {
    JsonNode bn = root.object_or_empty("bounds");
    lo = bn.vector("min", size_t(dim), lo, Range::any());
    hi = bn.vector("max", size_t(dim), hi, Range::any());
    bn.finish();
  }
  for (int a = 0; a < dim; ++a) {
    scene.bounds.min[a] = lo[size_t(a)];
    scene.bounds.max[a] = hi[size_t(a)];
    if (!(hi[size_t(a)] > lo[size_t(a)]))
      throw SceneError("/bounds/max/" + std::to_string(a), std::to_string(hi[size_t(a)]),
                       "a value greater than /bounds/min");
  }
  root.finish();
  if (scene.si_units)
    for (auto& w : material_plausibility_warnings(scene)) scene.warnings.push_back(w);
  prepare_active_potentials(scene);
  return scene;
}

}  // namespace mfsd
