// measure_planes[] of a scene (docs/scene-reference.md; seed 001 Fig. 7).
#include <cmath>
#include <set>
#include <string>

#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"

namespace mfsd {

void read_measure_planes(JsonNode& root, Scene& scene, const std::set<std::string>& body_names) {
  const int dim = scene.dimension;
  const size_t corners = dim == 3 ? 4 : 2;
  std::set<std::string> names;
  auto planes = root.array("measure_planes", false);
  for (size_t k = 0; k < planes.size(); ++k) {
    JsonNode node = root.element("measure_planes", k, *planes[k]);
    MeasurePlaneSpec m;
    m.name = node.string("name");
    if (!names.insert(m.name).second)
      throw SceneError(node.key_path("name"), "\"" + m.name + "\"", "a name no other measure plane has");
    for (char c : m.name)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
        throw SceneError(node.key_path("name"), "\"" + m.name + "\"",
                         "a name of letters, digits, '_', '-' and '.' (it names measure_<name>.csv)");
    m.body = node.string("body", "");
    if (!m.body.empty() && !body_names.count(m.body))
      throw SceneError(node.key_path("body"), "\"" + m.body + "\"", "the name of a body");
    auto pts = node.array("points", true, corners);
    if (pts.size() != corners)
      throw SceneError(node.key_path("points"), std::to_string(pts.size()) + " points",
                       dim == 3 ? "4 corners of a planar quadrilateral" : "the 2 ends of a segment");
    for (size_t c = 0; c < corners; ++c) {
      const Json& p = *pts[c];
      const std::string path = node.key_path("points") + "/" + std::to_string(c);
      if (!p.is_array() || p.size() != size_t(dim))
        throw SceneError(path, json_text(p), "an array of " + std::to_string(dim) + " numbers");
      Point3 x{0, 0, 0};
      for (int a = 0; a < dim; ++a) {
        const Json& v = p[size_t(a)];
        if (v.is_number())
          x[a] = v.get<double>();
        else if (v.is_string())
          x[a] = node.evaluator()(v.get<std::string>(), path + "/" + std::to_string(a));
        else
          throw SceneError(path + "/" + std::to_string(a), json_text(v), "a number or an expression");
      }
      m.points.push_back(x);
    }
    Json resolved_points = Json::array();  // run.json holds the evaluated numbers
    for (const Point3& x : m.points) resolved_points.push_back(Json(std::vector<double>(x.begin(), x.begin() + dim)));
    node.resolved()["points"] = resolved_points;
    m.thickness = node.number("thickness", 0.0, Range::non_negative());
    node.finish();
    scene.measure_planes.push_back(m);
  }
}

}  // namespace mfsd
