// Lists of points in a scene (measure planes, notches).
#include <string>
#include <vector>

#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"

namespace mfsd {

std::vector<Point3> read_points(JsonNode& node, const std::string& key, size_t count, int dim,
                                const std::string& what) {
  auto pts = node.array(key, true, count);
  if (pts.size() != count) throw SceneError(node.key_path(key), std::to_string(pts.size()) + " points", what);
  std::vector<Point3> points;
  for (size_t c = 0; c < count; ++c) {
    const Json& p = *pts[c];
    const std::string path = node.key_path(key) + "/" + std::to_string(c);
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
    points.push_back(x);
  }
  Json resolved = Json::array();  // run.json holds the evaluated numbers
  for (const Point3& x : points) resolved.push_back(Json(std::vector<double>(x.begin(), x.begin() + dim)));
  node.resolved()[key] = resolved;
  return points;
}

}  // namespace mfsd
