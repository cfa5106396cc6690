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
    check_file_name(node.key_path("name"), m.name, "measure_<name>.csv");
    m.body = node.string("body", "");
    if (!m.body.empty() && !body_names.count(m.body))
      throw SceneError(node.key_path("body"), "\"" + m.body + "\"", "the name of a body");
    m.points = read_points(node, "points", corners, dim,
                           dim == 3 ? "4 corners of a planar quadrilateral" : "the 2 ends of a segment");
    m.thickness = node.number("thickness", 0.0, Range::non_negative());
    node.finish();
    scene.measure_planes.push_back(m);
  }
}

}  // namespace mfsd
