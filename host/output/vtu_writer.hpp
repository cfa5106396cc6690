// VTK XML unstructured-grid snapshot (.vtu) with raw appended binary data:
// one vertex cell per particle, point data id, body, constrained,
// displacement, velocity, then every named field of the snapshot. Opens in
// ParaView.
#pragma once
#include <string>
#include <vector>

#include "host/output/snapshot.hpp"

namespace mfsd {

// `single` writes floating-point arrays as Float32 (float runs), else Float64.
void write_vtu(const std::string& path, const Snapshot& s, bool single);

// The parallel index (.pvtu) over the pieces of one snapshot that the ranks
// of a distributed run wrote with write_vtu (their file names, relative to
// the index's folder); `s` is one piece, for the arrays' names.
void write_pvtu(const std::string& path, const Snapshot& s, bool single, const std::vector<std::string>& pieces);

}  // namespace mfsd
