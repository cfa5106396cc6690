#include "host/scene/scene.hpp"

namespace mfsd {

bool has_plastic_body(const Scene& scene) {
  for (const auto& b : scene.bodies)
    if (b.material.plastic()) return true;
  return false;
}

const char* to_string(MaterialModel m) {
  switch (m) {
    case MaterialModel::neo_hookean:
      return "neo_hookean";
    case MaterialModel::saint_venant_kirchhoff:
      return "saint_venant_kirchhoff";
    case MaterialModel::j2:
      return "j2";
    case MaterialModel::j2_mandel:
      return "j2_mandel";
  }
  return "?";
}
const char* to_string(HourglassControl h) {
  switch (h) {
    case HourglassControl::none:
      return "none";
    case HourglassControl::laplacian:
      return "laplacian";
    case HourglassControl::genog:
      return "genog";
  }
  return "?";
}
const char* to_string(Precision p) { return p == Precision::single_precision ? "float" : "double"; }

}  // namespace mfsd
