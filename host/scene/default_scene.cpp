// The scene `mfsd run` runs without a file: configs/oscillating_plate_2d.json,
// embedded at build time.
#include <string>

#include "host/scene/scene_reader.hpp"

namespace mfsd {

const std::string& default_scene_text() {
  static const std::string text =
#include "generated/default_scene.inc"
      ;
  return text;
}

}  // namespace mfsd
