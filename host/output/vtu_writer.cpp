#include "host/output/vtu_writer.hpp"

#include <cstdint>
#include <cstring>
#include <sstream>
#include <vector>

#include "host/output/atomic_file.hpp"

namespace mfsd {

namespace {

struct Appended {
  std::string xml;
  std::string data;  // raw appended section: [UInt64 byte count][bytes] per array

  template <class T>
  void array(const char* name, const char* type, int components, const std::vector<T>& values) {
    std::ostringstream s;
    s << "        <DataArray type=\"" << type << "\"";
    if (name) s << " Name=\"" << name << "\"";
    if (components > 1) s << " NumberOfComponents=\"" << components << "\"";
    s << " format=\"appended\" offset=\"" << data.size() << "\"/>\n";
    xml += s.str();
    const std::uint64_t bytes = values.size() * sizeof(T);
    data.append(reinterpret_cast<const char*>(&bytes), sizeof(bytes));
    data.append(reinterpret_cast<const char*>(values.data()), bytes);
  }

  void real(const char* name, int components, const std::vector<double>& v, bool single) {
    if (!single) return array(name, "Float64", components, v);
    std::vector<float> f(v.begin(), v.end());
    array(name, "Float32", components, f);
  }
};

}  // namespace

void write_vtu(const std::string& path, const Snapshot& s, bool single) {
  const size_t n = s.n;
  std::vector<std::int64_t> id(s.id.begin(), s.id.end());
  std::vector<std::int32_t> body(s.body.begin(), s.body.end());
  std::vector<std::uint8_t> constrained(s.constrained.begin(), s.constrained.end());

  Appended a;  // all arrays share one appended block; xml pieces are collected per section
  a.array("id", "Int64", 1, id);
  a.array("body", "Int32", 1, body);
  a.array("constrained", "UInt8", 1, constrained);
  a.real("displacement", 3, s.displacement, single);
  a.real("velocity", 3, s.velocity, single);
  for (const auto& f : s.fields) a.real(f.name.c_str(), 1, f.values, single);
  const std::string point_xml = a.xml;
  a.xml.clear();
  a.real(nullptr, 3, s.position, single);
  const std::string points_xml = a.xml;
  a.xml.clear();
  std::vector<std::int64_t> connectivity(n), offsets(n);
  std::vector<std::uint8_t> types(n, 1);  // VTK_VERTEX
  for (size_t i = 0; i < n; ++i) {
    connectivity[i] = std::int64_t(i);
    offsets[i] = std::int64_t(i + 1);
  }
  a.array("connectivity", "Int64", 1, connectivity);
  a.array("offsets", "Int64", 1, offsets);
  a.array("types", "UInt8", 1, types);
  const std::string cells_xml = a.xml;

  std::ostringstream x;
  x << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
    << "  <UnstructuredGrid>\n"
    << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n << "\">\n"
    << "      <PointData Scalars=\"von_mises\" Vectors=\"velocity\">\n"
    << point_xml << "      </PointData>\n"
    << "      <Points>\n"
    << points_xml << "      </Points>\n"
    << "      <Cells>\n"
    << cells_xml << "      </Cells>\n"
    << "    </Piece>\n"
    << "  </UnstructuredGrid>\n"
    << "  <AppendedData encoding=\"raw\">\n_";
  std::string content = x.str();
  content += a.data;
  content += "\n  </AppendedData>\n</VTKFile>\n";
  write_file_atomically(path, content);
}

void write_pvtu(const std::string& path, const Snapshot& s, bool single, const std::vector<std::string>& pieces) {
  const char* real = single ? "Float32" : "Float64";
  std::ostringstream x;
  x << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
    << "  <PUnstructuredGrid GhostLevel=\"0\">\n"
    << "    <PPointData Scalars=\"von_mises\" Vectors=\"velocity\">\n"
    << "      <PDataArray type=\"Int64\" Name=\"id\"/>\n"
    << "      <PDataArray type=\"Int32\" Name=\"body\"/>\n"
    << "      <PDataArray type=\"UInt8\" Name=\"constrained\"/>\n"
    << "      <PDataArray type=\"" << real << "\" Name=\"displacement\" NumberOfComponents=\"3\"/>\n"
    << "      <PDataArray type=\"" << real << "\" Name=\"velocity\" NumberOfComponents=\"3\"/>\n";
  for (const auto& f : s.fields) x << "      <PDataArray type=\"" << real << "\" Name=\"" << f.name << "\"/>\n";
  x << "    </PPointData>\n"
    << "    <PPoints>\n"
    << "      <PDataArray type=\"" << real << "\" NumberOfComponents=\"3\"/>\n"
    << "    </PPoints>\n";
  for (const auto& piece : pieces) x << "    <Piece Source=\"" << piece << "\"/>\n";
  x << "  </PUnstructuredGrid>\n</VTKFile>\n";
  write_file_atomically(path, x.str());
}

}  // namespace mfsd
