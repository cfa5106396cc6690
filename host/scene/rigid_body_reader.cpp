// rigid_bodies[] of a scene (docs/scene-reference.md).
#include <cmath>
#include <set>
#include <string>

#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"

namespace mfsd {

void read_rigid_bodies(JsonNode& root, Scene& scene) {
  const int dim = scene.dimension;
  std::set<std::string> names;
  for (auto& b : scene.bodies) names.insert(b.name);
  auto items = root.array("rigid_bodies", false);
  for (size_t k = 0; k < items.size(); ++k) {
    JsonNode node = root.element("rigid_bodies", k, *items[k]);
    RigidBodySpec r;
    r.name = node.string("name");
    if (!names.insert(r.name).second)
      throw SceneError(node.key_path("name"), "\"" + r.name + "\"", "a name no body or other rigid body has");
    r.shape = read_shape(node.object("shape"), dim, scene.base_dir);
    const Bounds bb = r.shape.bounds(dim);
    for (int a = 0; a < dim; ++a) r.center[a] = 0.5 * (bb.min[a] + bb.max[a]);
    const char* axes[3] = {"x", "y", "z"};
    JsonNode tr = node.object_or_empty("translation");
    for (int a = 0; a < dim; ++a) r.translation[size_t(a)] = tr.expression(axes[a], "0");
    tr.finish();
    JsonNode rot = node.object_or_empty("rotation");
    r.angle_degrees = rot.expression("angle_degrees", "0");
    if (dim == 3) {
      const auto v = rot.vector("axis", 3, {0.0, 0.0, 1.0}, Range::any());
      r.axis = {v[0], v[1], v[2]};
      if (v[0] == 0 && v[1] == 0 && v[2] == 0)
        throw SceneError(rot.key_path("axis"), "a zero vector", "the rotation axis");
    }
    const auto c =
        rot.vector("center", size_t(dim), std::vector<double>(r.center.begin(), r.center.begin() + dim), Range::any());
    for (int a = 0; a < dim; ++a) r.center[a] = c[size_t(a)];
    rot.finish();
    double smallest = 1e300;
    for (auto& b : scene.bodies) smallest = std::min(smallest, b.spacing);
    r.marker_spacing = node.number("marker_spacing", smallest, Range::positive());
    node.finish();
    scene.rigid_bodies.push_back(r);
  }
}

}  // namespace mfsd
