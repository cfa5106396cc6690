// The contact object of a scene (docs/scene-reference.md, "contact").
#include <set>
#include <string>
#include <vector>

#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"

namespace mfsd {

namespace {

// An array of distinct names, each one of `allowed`.
std::vector<std::string> read_names(JsonNode& node, const std::string& key, const std::set<std::string>& allowed,
                                    const std::string& what) {
  std::vector<std::string> out;
  std::set<std::string> seen;
  auto list = node.array(key, false);
  for (size_t k = 0; k < list.size(); ++k) {
    const Json& v = *list[k];
    const std::string path = node.key_path(key) + "/" + std::to_string(k);
    if (!v.is_string() || !allowed.count(v.get<std::string>())) throw SceneError(path, json_text(v), what);
    if (!seen.insert(v.get<std::string>()).second) throw SceneError(path, json_text(v), "a name not listed before");
    out.push_back(v.get<std::string>());
    node.resolved()[key][k] = v;
  }
  if (list.empty()) node.resolved()[key] = Json::array();
  return out;
}

}  // namespace

void read_contact(JsonNode& root, Scene& scene) {
  auto node = root.optional_object("contact");
  if (!node) return;
  ContactSpec& c = scene.contact;
  c.enabled = true;
  std::set<std::string> bodies, rigid;
  for (auto& b : scene.bodies) bodies.insert(b.name);
  for (auto& r : scene.rigid_bodies) rigid.insert(r.name);
  c.bodies = read_names(*node, "bodies", bodies, "the name of a body");
  if (c.bodies.empty()) {
    for (auto& b : scene.bodies) c.bodies.push_back(b.name);
    for (size_t k = 0; k < c.bodies.size(); ++k) node->resolved()["bodies"][k] = c.bodies[k];
  }
  const std::set<std::string> taking_part(c.bodies.begin(), c.bodies.end());
  c.self_contact = read_names(*node, "self_contact", taking_part, "the name of a body listed in contact.bodies");
  c.rigid_bodies = read_names(*node, "rigid_bodies", rigid, "the name of a rigid body");
  c.stiffness = node->number("stiffness", 1.0, Range::positive());
  // e = 0 would need an infinite dashpot: the pair law cannot stop dead (use a small e).
  c.restitution = node->number("restitution", 1.0, Range{0.0, 1.0, true, false, "a restitution in (0, 1]"});
  c.friction = node->number("friction", 0.0, Range::non_negative());
  if (c.bodies.size() < 2 && c.self_contact.empty() && c.rigid_bodies.empty())
    throw SceneError(node->path(), "contact with one body and no partner",
                     "two bodies in contact.bodies, a rigid body in contact.rigid_bodies or a body in "
                     "contact.self_contact");
  node->finish();
}

}  // namespace mfsd
