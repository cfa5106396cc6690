// Shape objects of a scene (docs/scene-reference.md, "Shapes"): one key
// naming the primitive or operation, validated for the scene's dimension.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"
#include "host/scene/stl_mesh.hpp"

namespace mfsd {

namespace {

const std::vector<std::string> kShapes2d = {"box", "circle", "polygon", "transform", "union", "difference"};
const std::vector<std::string> kShapes3d = {"box", "sphere",    "cylinder", "extrude",
                                            "stl", "transform", "union",    "difference"};

std::string list(const std::vector<std::string>& names) {
  std::string s;
  for (size_t k = 0; k < names.size(); ++k)
    s += (k ? (k + 1 == names.size() ? " or " : ", ") : "") + ('"' + names[k] + '"');
  return s;
}

Point3 point(JsonNode& node, const std::string& key, int dim) {
  const auto v = node.vector(key, size_t(dim), Range::any());
  Point3 p{0, 0, 0};
  for (int a = 0; a < dim; ++a) p[a] = v[size_t(a)];
  return p;
}

Shape read_list(JsonNode& node, const std::string& key, Shape::Kind kind, int dim, size_t min_size,
                const std::string& base_dir) {
  Shape s;
  s.kind = kind;
  auto items = node.array(key, true, min_size);
  for (size_t k = 0; k < items.size(); ++k)
    s.children.push_back(read_shape(node.element(key, k, *items[k]), dim, base_dir));
  return s;
}

void radii(JsonNode& n, Shape& s) {
  s.radius = n.number("radius", Range::positive());
  s.inner_radius = n.number("inner_radius", 0.0, Range::non_negative());
  if (s.inner_radius >= s.radius)
    throw SceneError(n.key_path("inner_radius"), std::to_string(s.inner_radius),
                     "a value smaller than radius (" + std::to_string(s.radius) + ")");
}

}  // namespace

Shape read_shape(JsonNode node, int dim, const std::string& base_dir) {
  const auto& allowed = dim == 3 ? kShapes3d : kShapes2d;
  const auto& other = dim == 3 ? kShapes2d : kShapes3d;
  std::string key;
  int count = 0;
  for (auto& k : allowed)
    if (node.has(k)) key = k, ++count;
  for (auto& k : other)
    if (node.has(k) && std::find(allowed.begin(), allowed.end(), k) == allowed.end())
      throw SceneError(node.key_path(k), "a " + k + " in a " + std::to_string(dim) + "-D scene",
                       "one of " + list(allowed));
  if (count != 1)
    throw SceneError(node.path(), count == 0 ? "no shape" : "several shapes", "exactly one of " + list(allowed));
  Shape s;
  if (key == "box") {
    JsonNode box = node.object("box");
    s = Shape::box(point(box, "min", dim), point(box, "max", dim));
    for (int a = 0; a < dim; ++a)
      if (!(s.max[a] > s.min[a]))
        throw SceneError(box.key_path("max") + "/" + std::to_string(a), std::to_string(s.max[a]),
                         "a value greater than min (" + std::to_string(s.min[a]) + ")");
    box.finish();
  } else if (key == "sphere" || key == "circle") {
    JsonNode n = node.object(key);
    s.kind = key == "sphere" ? Shape::Kind::sphere : Shape::Kind::circle;
    s.center = point(n, "center", dim);
    radii(n, s);
    n.finish();
  } else if (key == "cylinder") {
    JsonNode n = node.object(key);
    s.kind = Shape::Kind::cylinder;
    s.center = point(n, "base", 3);
    s.axis = point(n, "axis", 3);
    if (std::sqrt(s.axis[0] * s.axis[0] + s.axis[1] * s.axis[1] + s.axis[2] * s.axis[2]) == 0)
      throw SceneError(n.key_path("axis"), "a zero vector", "the vector from the base centre to the top centre");
    radii(n, s);
    n.finish();
  } else if (key == "polygon") {
    JsonNode n = node.object(key);
    s.kind = Shape::Kind::polygon;
    auto pts = n.array("points", true, 3);
    Json resolved = Json::array();
    for (size_t k = 0; k < pts.size(); ++k) {
      const Json& p = *pts[k];
      const std::string path = n.key_path("points") + "/" + std::to_string(k);
      if (!p.is_array() || p.size() != 2) throw SceneError(path, json_text(p), "a point [x, y]");
      std::array<double, 2> v{};
      for (size_t a = 0; a < 2; ++a) {
        if (p[a].is_number())
          v[a] = p[a].get<double>();
        else if (p[a].is_string())
          v[a] = n.evaluator()(p[a].get<std::string>(), path + "/" + std::to_string(a));
        else
          throw SceneError(path + "/" + std::to_string(a), json_text(p[a]), "a number or an expression");
      }
      s.vertices.push_back(v);
      resolved.push_back(Json::array({v[0], v[1]}));
    }
    n.resolved()["points"] = resolved;
    double area = 0;
    for (size_t i = 0, j = s.vertices.size() - 1; i < s.vertices.size(); j = i++)
      area += s.vertices[j][0] * s.vertices[i][1] - s.vertices[i][0] * s.vertices[j][1];
    if (area == 0)
      throw SceneError(n.key_path("points"), "a polygon of zero area", "at least 3 points enclosing an area");
    n.finish();
  } else if (key == "extrude") {
    JsonNode n = node.object(key);
    s.kind = Shape::Kind::extrude;
    s.children.push_back(read_shape(n.object("shape"), 2, base_dir));
    const auto z = n.vector("z", 2, Range::any());
    s.z_min = z[0];
    s.z_max = z[1];
    if (!(s.z_max > s.z_min))
      throw SceneError(n.key_path("z") + "/1", std::to_string(s.z_max), "a value greater than z[0]");
    n.finish();
  } else if (key == "stl") {
    JsonNode n = node.object(key);
    s.kind = Shape::Kind::mesh;
    s.source = n.string("file");
    const double scale = n.number("scale", 1.0, Range::positive());
    const std::filesystem::path file = std::filesystem::path(s.source).is_absolute() || base_dir.empty()
                                           ? std::filesystem::path(s.source)
                                           : std::filesystem::path(base_dir) / s.source;
    if (!std::filesystem::is_regular_file(file)) {  // name the folder it looked in
      std::error_code ec;
      const auto where = std::filesystem::absolute(file, ec);
      throw SceneError(n.key_path("file") + ": STL file '" + s.source + "' cannot be opened: looked for " +
                       (ec ? file.string() : where.lexically_normal().string()) +
                       (std::filesystem::path(s.source).is_absolute()
                            ? std::string()
                            : " (a relative name is taken from the scene file's folder)"));
    }
    try {
      s.triangles = TriangleMesh::load(file.string(), scale);
    } catch (const std::runtime_error& e) {
      throw SceneError(n.key_path("file") + ": " + e.what());
    }
    n.finish();
  } else if (key == "transform") {
    JsonNode n = node.object(key);
    s.kind = Shape::Kind::transform;
    s.children.push_back(read_shape(n.object("shape"), dim, base_dir));
    const auto t = n.vector("translate", size_t(dim), std::vector<double>(size_t(dim), 0.0), Range::any());
    for (int a = 0; a < dim; ++a) s.translation[a] = t[size_t(a)];
    s.scale = n.number("scale", 1.0, Range::positive());
    const double angle = n.number("rotate_degrees", 0.0, Range::any()) * M_PI / 180;
    Point3 axis{0, 0, 1};
    if (dim == 3) {
      const auto v = n.vector("axis", 3, {0.0, 0.0, 1.0}, Range::any());
      axis = {v[0], v[1], v[2]};
      if (v[0] == 0 && v[1] == 0 && v[2] == 0)
        throw SceneError(n.key_path("axis"), "a zero vector", "the rotation axis");
    }
    s.rotation = rotation_matrix(axis, angle);
    n.finish();
  } else if (key == "union") {
    s = read_list(node, "union", Shape::Kind::union_of, dim, 1, base_dir);
  } else {
    s = read_list(node, "difference", Shape::Kind::difference, dim, 2, base_dir);
  }
  node.finish();
  return s;
}

}  // namespace mfsd
