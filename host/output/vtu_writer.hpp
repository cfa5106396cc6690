// VTK XML unstructured-grid snapshot (.vtu) with raw appended binary data:
// one vertex cell per particle, point data id, body, constrained,
// displacement, velocity, then every named field of the snapshot. Opens in
// ParaView.
#pragma once
#include <string>

#include "host/output/snapshot.hpp"

namespace mfsd {

// `single` writes floating-point arrays as Float32 (float runs), else Float64.
void write_vtu(const std::string& path, const Snapshot& s, bool single);

}  // namespace mfsd
