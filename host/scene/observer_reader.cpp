// observers[] of a scene (issue 28; docs/scene-reference.md, "observers").
#include <set>
#include <string>

#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"

namespace mfsd {

void read_observers(JsonNode& root, Scene& scene, const std::set<std::string>& body_names) {
  const int dim = scene.dimension;
  std::set<std::string> names;
  auto observers = root.array("observers", false);
  for (size_t k = 0; k < observers.size(); ++k) {
    JsonNode node = root.element("observers", k, *observers[k]);
    ObserverSpec o;
    o.name = node.string("name");
    if (!names.insert(o.name).second)
      throw SceneError(node.key_path("name"), "\"" + o.name + "\"", "a name no other observer has");
    o.body = node.string("body", "");
    if (!o.body.empty() && !body_names.count(o.body))
      throw SceneError(node.key_path("body"), "\"" + o.body + "\"", "the name of a body");
    const bool has_points = node.has("points"), has_line = node.has("line");
    if (has_points == has_line)
      throw SceneError(node.path(), has_points ? "both \"points\" and \"line\"" : "neither \"points\" nor \"line\"",
                       "one of them: \"points\": [[x, y], ...] or \"line\": {\"from\": .., \"to\": .., \"count\": N}");
    if (has_points) {
      auto points = node.array("points", true, 1);
      for (size_t p = 0; p < points.size(); ++p) {
        const std::string path = node.key_path("points") + "/" + std::to_string(p);
        const Json& v = *points[p];
        if (!v.is_array() || v.size() != size_t(dim))
          throw SceneError(path, json_text(v), std::to_string(dim) + " coordinates");
        Point3 x{0, 0, 0};
        for (int a = 0; a < dim; ++a) {
          if (!v[size_t(a)].is_number()) throw SceneError(path, json_text(v), "numbers");
          x[size_t(a)] = v[size_t(a)].get<double>();
        }
        o.points.push_back(x);
      }
    } else {
      JsonNode line = node.object("line");
      const auto from = line.vector("from", size_t(dim), Range::any());
      const auto to = line.vector("to", size_t(dim), Range::any());
      const long count = line.integer("count", 11, 2, 100000);
      for (long p = 0; p < count; ++p) {
        const double s = double(p) / double(count - 1);
        Point3 x{0, 0, 0};
        for (int a = 0; a < dim; ++a) x[size_t(a)] = from[size_t(a)] + s * (to[size_t(a)] - from[size_t(a)]);
        o.points.push_back(x);
      }
      line.finish();
    }
    auto fields = node.array("fields", true, 1);
    for (size_t f = 0; f < fields.size(); ++f) {
      const Json& v = *fields[f];
      if (!v.is_string() || v.get<std::string>().empty())
        throw SceneError(node.key_path("fields") + "/" + std::to_string(f), json_text(v),
                         "the name of a particle field (\"velocity\", \"von_mises\", ...; mfsd.Simulation.fields lists "
                         "them) or \"position\"");
      o.fields.push_back(v.get<std::string>());
    }
    o.radius = node.number("radius", 0.0, Range::non_negative());
    o.freeze = node.boolean("freeze", false);
    o.interpolation = node.choice("interpolation", {"shepard", "linear"}, "shepard") == "linear"
                          ? ObserverSpec::Interpolation::linear
                          : ObserverSpec::Interpolation::shepard;
    node.finish();
    scene.observers.push_back(o);
  }
}

}  // namespace mfsd
