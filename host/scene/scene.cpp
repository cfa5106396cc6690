#include "host/scene/scene.hpp"

namespace mfsd {

const char* to_string(MaterialModel m) {
  return m == MaterialModel::neo_hookean ? "neo_hookean" : "saint_venant_kirchhoff";
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
