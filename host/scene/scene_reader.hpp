// Reads a scene file (JSON): parse with line/column errors, apply command-line
// overrides (--set path=value), validate every key into a Scene and keep the
// resolved document (defaults filled in) for run.json.
#pragma once
#include <set>
#include <string>
#include <vector>

#include "host/scene/json_node.hpp"
#include "host/scene/scene.hpp"

namespace mfsd {

struct SceneDocument {
  std::string source_name;             // file path or "<default scene>"
  std::vector<std::string> overrides;  // the --set path=value assignments, in order
  Json source;                         // as read, overrides applied
  Json resolved;                       // every key with its value or default
  Scene scene;
};

// Parses JSON text; syntax errors become SceneErrors "name:line:column: ..."
// (scene_text.cpp, with apply_override, check_file_name and the loaders).
Json parse_scene_json(const std::string& text, const std::string& source_name);

// Applies "path=value": path of object keys and array indices (or array
// element names) separated by '.', e.g. solver.hourglass=laplacian,
// bodies.plate.material.poisson_ratio=0.4, constants.vf=0.1. The value is
// parsed as JSON, else taken as a string.
void apply_override(Json& doc, const std::string& assignment);

// The readers of the scene's sections, one file each (read_scene, in
// scene_reader.cpp, calls them in the scene's order):
// solver (solver_reader.cpp),
SolverSpec read_solver(JsonNode s, int dim);
// bodies[].material (material_reader.cpp): the model and its constants; then
// the checks that derived quantities are finite and that the model belongs
// to the body's method.
MaterialSpec read_material(JsonNode m, double spacing, int dim, std::vector<std::string>& warnings);
void check_body_properties(const BodySpec& body, const SolverSpec& solver, int dim, const std::string& path);
void check_method_material(const BodySpec& body, const SolverSpec& solver, const std::string& path);

// A shape object of the given dimension (shape_reader.cpp); file names
// (STL) are relative to `base_dir`, the scene file's folder.
Shape read_shape(JsonNode node, int dim, const std::string& base_dir);

// The body named by `key` (an error unless it is one of `bodies`).
std::string read_body_name(JsonNode& node, const std::string& key, const std::set<std::string>& bodies);
// "name" (or `fallback`), which must not be in `taken`; adds it there.
std::string read_unique_name(JsonNode& node, const std::string& fallback, std::set<std::string>& taken,
                             const std::string& among);

// velocity_conditions[], walls[] and loads[] into scene.conditions and
// scene.walls (condition_reader.cpp); `names` holds the clamps' names, and
// the names of all of them must differ (they are columns of boundary_forces.csv).
void read_conditions(JsonNode& root, Scene& scene, const std::set<std::string>& body_names,
                     std::set<std::string>& names);

// rigid_bodies[] into scene.rigid_bodies (rigid_body_reader.cpp); after the bodies.
void read_rigid_bodies(JsonNode& root, Scene& scene);

// contact into scene.contact (contact_reader.cpp); after bodies and rigid bodies.
void read_contact(JsonNode& root, Scene& scene);

// `key` as `count` points of `dim` coordinates (numbers or constant
// expressions), written back evaluated into the resolved scene; `what` says
// what they are in an error (points_reader.cpp).
std::vector<Point3> read_points(JsonNode& node, const std::string& key, size_t count, int dim, const std::string& what);

// material.fracture of a body with the given spacing (fracture_reader.cpp).
FractureSpec read_fracture(JsonNode node, const MaterialSpec& material, double spacing, int dim,
                           std::vector<std::string>& warnings);

// measure_planes[] into scene.measure_planes (measure_plane_reader.cpp).
void read_measure_planes(JsonNode& root, Scene& scene, const std::set<std::string>& body_names);
// observers[] (observer_reader.cpp).
void read_observers(JsonNode& root, Scene& scene, const std::set<std::string>& body_names);

// A name that becomes part of a file or folder name (`used_in`, e.g.
// "measure_<name>.csv"): letters, digits, '_', '-' and '.', at most 200
// characters (the file system's limit is 255), not "." or "..".
void check_file_name(const std::string& path, const std::string& name, const std::string& used_in);

// Validates the document into a Scene; fills `resolved`.
Scene read_scene(const Json& doc, Json& resolved, const std::string& base_dir = "");

SceneDocument load_scene_file(const std::string& path, const std::vector<std::string>& overrides);
// `base_dir`: the folder relative file names in the scene refer to.
SceneDocument load_scene_text(const std::string& text, const std::string& source_name,
                              const std::vector<std::string>& overrides, const std::string& base_dir = "");

// The scene `mfsd run` uses without a file (configs/oscillating_plate_2d.json, H/dp = 10).
const std::string& default_scene_text();

}  // namespace mfsd
