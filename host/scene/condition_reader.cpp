// velocity_conditions[] and loads[] of a scene (docs/scene-reference.md):
// seed 001's bcvel and bcforce cards as JSON. Expressions are kept as text
// here and compiled by the particle generator, which knows the body constants.
#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"

namespace mfsd {

namespace {

SelectionSpec read_selection(JsonNode& node, const Scene& scene) {
  const int dim = scene.dimension;
  const std::string& base_dir = scene.base_dir;
  SelectionSpec s;
  const int given = int(node.has("region")) + int(node.has("where")) + int(node.has("near"));
  if (given > 1) throw SceneError(node.path(), "several selections", "at most one of \"region\", \"where\", \"near\"");
  if (node.has("near")) {
    JsonNode n = node.object("near");
    s.kind = SelectionSpec::Kind::near;
    s.rigid_body = n.string("rigid_body");
    bool known = false;
    for (auto& r : scene.rigid_bodies) known = known || r.name == s.rigid_body;
    if (!known) throw SceneError(n.key_path("rigid_body"), "\"" + s.rigid_body + "\"", "the name of a rigid body");
    s.distance = n.number("distance", Range::non_negative());
    n.finish();
  }
  if (node.has("region")) {
    s.kind = SelectionSpec::Kind::region;
    s.region = read_shape(node.object("region"), dim, base_dir);
  } else if (node.has("where")) {
    s.kind = SelectionSpec::Kind::expression;
    s.expression = node.expression("where", "1");
  }
  return s;
}

void read_components(JsonNode& node, ConditionSpec& c, int dim) {
  const char* axes[3] = {"x", "y", "z"};
  bool any = false;
  for (int a = 0; a < dim; ++a)
    if (node.has(axes[a])) {
      c.value[size_t(a)] = node.expression(axes[a], "");
      any = true;
    }
  if (!any)
    throw SceneError(node.path(), "no component", dim == 3 ? "at least one of \"x\", \"y\", \"z\"" : "\"x\" or \"y\"");
}

void read_window(JsonNode& node, ConditionSpec& c) {
  c.t_start = node.number("t_start", 0.0, Range::non_negative());
  c.t_end = node.number("t_end", 1e300, Range::non_negative());
  if (!(c.t_end >= c.t_start)) throw SceneError(node.key_path("t_end"), std::to_string(c.t_end), "a time >= t_start");
}

}  // namespace

std::string read_body_name(JsonNode& node, const std::string& key, const std::set<std::string>& bodies) {
  const std::string name = node.string(key);
  if (!bodies.count(name)) throw SceneError(node.key_path(key), "\"" + name + "\"", "the name of a body");
  return name;
}

std::string read_unique_name(JsonNode& node, const std::string& fallback, std::set<std::string>& taken,
                             const std::string& among) {
  const std::string name = node.string("name", fallback);
  if (!taken.insert(name).second)
    throw SceneError(node.key_path("name"), "\"" + name + "\"", "a name no other " + among + " has");
  return name;
}

void read_conditions(JsonNode& root, Scene& scene, const std::set<std::string>& body_names,
                     std::set<std::string>& names) {
  const int dim = scene.dimension;
  const std::string among = "clamp, condition, load or wall";
  auto read_common = [&](JsonNode& node, ConditionSpec& c, const std::string& default_name) {
    c.name = read_unique_name(node, default_name, names, among);
    c.body = read_body_name(node, "body", body_names);
    c.select = read_selection(node, scene);
    read_components(node, c, dim);
    read_window(node, c);
  };

  auto velocity = root.array("velocity_conditions", false);
  for (size_t k = 0; k < velocity.size(); ++k) {
    JsonNode node = root.element("velocity_conditions", k, *velocity[k]);
    ConditionSpec c;
    c.type = ConditionSpec::Type::velocity;
    read_common(node, c, "velocity" + std::to_string(k));
    node.finish();
    scene.conditions.push_back(c);
  }
  auto walls = root.array("walls", false);
  for (size_t k = 0; k < walls.size(); ++k) {
    JsonNode node = root.element("walls", k, *walls[k]);
    WallSpec w;
    w.name = read_unique_name(node, "wall" + std::to_string(k), names, among);
    const auto p = node.vector("point", size_t(dim), Range::any());
    const auto n = node.vector("normal", size_t(dim), Range::any());
    double len = 0;
    for (int a = 0; a < dim; ++a) len += n[size_t(a)] * n[size_t(a)];
    if (len == 0)
      throw SceneError(node.key_path("normal"), "a zero vector",
                       "the wall's normal, pointing to the side the bodies stay on");
    w.normal = {0, 0, 0};
    for (int a = 0; a < dim; ++a) w.point[a] = p[size_t(a)], w.normal[a] = n[size_t(a)] / std::sqrt(len);
    auto list = node.array("bodies", false);
    for (size_t b = 0; b < list.size(); ++b) {
      const Json& v = *list[b];
      const std::string path = node.key_path("bodies") + "/" + std::to_string(b);
      if (!v.is_string() || !body_names.count(v.get<std::string>()))
        throw SceneError(path, json_text(v), "the name of a body");
      w.bodies.push_back(v.get<std::string>());
      node.resolved()["bodies"][b] = v;
    }
    node.finish();
    scene.walls.push_back(w);
  }

  auto loads = root.array("loads", false);
  for (size_t k = 0; k < loads.size(); ++k) {
    JsonNode node = root.element("loads", k, *loads[k]);
    ConditionSpec c;
    const std::string type = node.choice("type", {"point", "traction", "acceleration"});
    c.type = type == "point"      ? ConditionSpec::Type::point_force
             : type == "traction" ? ConditionSpec::Type::traction
                                  : ConditionSpec::Type::acceleration;
    read_common(node, c, "load" + std::to_string(k));
    if (node.has("face")) {
      if (c.type != ConditionSpec::Type::traction)
        throw SceneError(node.key_path("face"), "a face on a " + type + " load", "\"face\" only on traction loads");
      std::vector<std::string> faces = {"-x", "+x", "-y", "+y"};
      if (dim == 3) faces.insert(faces.end(), {"-z", "+z"});
      const std::string f = node.choice("face", faces);
      c.face = int(std::find(faces.begin(), faces.end(), f) - faces.begin());
    }
    node.finish();
    scene.conditions.push_back(c);
  }
}

}  // namespace mfsd
