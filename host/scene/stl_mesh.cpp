#include "host/scene/stl_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace mfsd {

namespace {

std::string point_text(const Point3& p) {
  std::ostringstream s;
  s << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return s.str();
}

std::vector<std::array<Point3, 3>> read_binary(const std::string& bytes, const std::string& path) {
  std::uint32_t n = 0;
  std::memcpy(&n, bytes.data() + 80, 4);
  std::vector<std::array<Point3, 3>> t(n);
  for (std::uint32_t k = 0; k < n; ++k) {
    const char* rec = bytes.data() + 84 + 50 * size_t(k) + 12;  // skip the normal
    for (int v = 0; v < 3; ++v)
      for (int a = 0; a < 3; ++a) {
        float f;
        std::memcpy(&f, rec + 12 * v + 4 * a, 4);
        if (!std::isfinite(f)) throw std::runtime_error("STL file '" + path + "': non-finite coordinate");
        t[k][size_t(v)][size_t(a)] = double(f);
      }
  }
  return t;
}

std::vector<std::array<Point3, 3>> read_ascii(const std::string& text, const std::string& path) {
  std::istringstream in(text);
  std::string word;
  std::vector<std::array<Point3, 3>> t;
  std::array<Point3, 3> tri{};
  int v = 0;
  long line_vertex = 0;
  while (in >> word) {
    if (word == "vertex") {
      ++line_vertex;
      Point3 p;
      if (!(in >> p[0] >> p[1] >> p[2]))
        throw std::runtime_error("STL file '" + path + "': vertex " + std::to_string(line_vertex) +
                                 " does not have three numbers");
      if (v == 3) throw std::runtime_error("STL file '" + path + "': a facet with more than three vertices");
      tri[size_t(v++)] = p;
    } else if (word == "endfacet") {
      if (v != 3) throw std::runtime_error("STL file '" + path + "': a facet without three vertices");
      t.push_back(tri);
      v = 0;
    }
  }
  return t;
}

}  // namespace

std::shared_ptr<const TriangleMesh> TriangleMesh::load(const std::string& path, double scale) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("STL file '" + path + "' cannot be opened");
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string bytes = ss.str();
  std::vector<std::array<Point3, 3>> t;
  bool binary = false;
  if (bytes.size() >= 84) {
    std::uint32_t n = 0;
    std::memcpy(&n, bytes.data() + 80, 4);
    binary = bytes.size() == 84 + 50 * size_t(n);
  }
  if (binary)
    t = read_binary(bytes, path);
  else if (bytes.compare(0, 5, "solid") == 0)
    t = read_ascii(bytes, path);
  else
    throw std::runtime_error("STL file '" + path +
                             "' is neither ASCII (starting with 'solid') nor binary (84 + 50 n bytes)");
  for (auto& tri : t)
    for (auto& p : tri)
      for (auto& x : p) x *= scale;
  return from_triangles(std::move(t), path);
}

std::shared_ptr<const TriangleMesh> TriangleMesh::from_triangles(std::vector<std::array<Point3, 3>> triangles,
                                                                 const std::string& name) {
  auto m = std::shared_ptr<TriangleMesh>(new TriangleMesh());
  m->name_ = name;
  m->triangles_ = std::move(triangles);
  if (m->triangles_.empty()) throw std::runtime_error("STL file '" + name + "' holds no triangle");
  // Closed: every edge (between exactly equal vertices) belongs to two triangles.
  std::map<std::pair<Point3, Point3>, int> edges;
  for (auto& tri : m->triangles_)
    for (int e = 0; e < 3; ++e) {
      Point3 a = tri[size_t(e)], b = tri[size_t((e + 1) % 3)];
      if (b < a) std::swap(a, b);
      ++edges[{a, b}];
    }
  long open = 0, over = 0;
  std::pair<Point3, Point3> first_open{}, first_over{};
  for (auto& [e, count] : edges) {
    if (count == 1 && open++ == 0) first_open = e;
    if (count > 2 && over++ == 0) first_over = e;
  }
  if (open)
    throw std::runtime_error("STL file '" + name + "' is not a closed surface: " + std::to_string(open) +
                             " edge(s) belong to one triangle only, the first from " + point_text(first_open.first) +
                             " to " + point_text(first_open.second) +
                             " (a hole in the surface; its inside is undefined)");
  if (over)
    throw std::runtime_error("STL file '" + name + "' is not a manifold surface: " + std::to_string(over) +
                             " edge(s) belong to more than two triangles, the first from " +
                             point_text(first_over.first) + " to " + point_text(first_over.second));
  m->build();
  return m;
}

void TriangleMesh::build() {
  bounds_.min = bounds_.max = triangles_[0][0];
  for (auto& tri : triangles_)
    for (auto& p : tri)
      for (int a = 0; a < 3; ++a) {
        bounds_.min[a] = std::min(bounds_.min[a], p[a]);
        bounds_.max[a] = std::max(bounds_.max[a], p[a]);
      }
  grid_ = std::max(1, std::min(256, int(std::sqrt(double(triangles_.size())))));
  for (int a = 0; a < 2; ++a) cell_[a] = std::max((bounds_.max[a] - bounds_.min[a]) / grid_, 1e-300);
  buckets_.assign(size_t(grid_) * size_t(grid_), {});
  auto index = [&](double x, int a) {
    return std::clamp(int(std::floor((x - bounds_.min[a]) / cell_[a])), 0, grid_ - 1);
  };
  for (unsigned k = 0; k < triangles_.size(); ++k) {
    const auto& t = triangles_[k];
    const int x0 = index(std::min({t[0][0], t[1][0], t[2][0]}), 0),
              x1 = index(std::max({t[0][0], t[1][0], t[2][0]}), 0);
    const int y0 = index(std::min({t[0][1], t[1][1], t[2][1]}), 1),
              y1 = index(std::max({t[0][1], t[1][1], t[2][1]}), 1);
    for (int j = y0; j <= y1; ++j)
      for (int i = x0; i <= x1; ++i) buckets_[size_t(j) * size_t(grid_) + size_t(i)].push_back(k);
  }
}

bool TriangleMesh::contains(const Point3& p) const {
  for (int a = 0; a < 3; ++a)
    if (p[a] < bounds_.min[a] || p[a] > bounds_.max[a]) return false;
  const int i = std::clamp(int(std::floor((p[0] - bounds_.min[0]) / cell_[0])), 0, grid_ - 1);
  const int j = std::clamp(int(std::floor((p[1] - bounds_.min[1]) / cell_[1])), 0, grid_ - 1);
  int crossings = 0;
  for (unsigned k : buckets_[size_t(j) * size_t(grid_) + size_t(i)]) {
    std::array<Point3, 3> t = triangles_[k];
    auto orient = [](const Point3& a, const Point3& b, const Point3& q) {
      return (b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0]);
    };
    const double area = orient(t[0], t[1], t[2]);
    if (area == 0) continue;  // vertical in projection: a ray along z does not cross it
    if (area < 0) std::swap(t[1], t[2]);
    // Inside the projected (counter-clockwise) triangle, with the top-left
    // rule on its edges: a point on an edge shared by two triangles of one
    // sheet is inside exactly one of them.
    bool in = true;
    for (int e = 0; e < 3 && in; ++e) {
      const Point3 &a = t[size_t(e)], &b = t[size_t((e + 1) % 3)];
      const double o = orient(a, b, p);
      if (o < 0) in = false;
      if (o == 0) {
        const bool top = a[1] == b[1] && b[0] < a[0];
        const bool left = b[1] < a[1];
        in = top || left;
      }
    }
    if (!in) continue;
    // Height of the triangle's plane above p (barycentric interpolation).
    const double w0 = orient(t[1], t[2], p), w1 = orient(t[2], t[0], p), w2 = orient(t[0], t[1], p);
    const double z = (w0 * t[0][2] + w1 * t[1][2] + w2 * t[2][2]) / (w0 + w1 + w2);
    if (z == p[2]) return true;  // on the surface
    if (z > p[2]) ++crossings;
  }
  return crossings % 2 == 1;
}

}  // namespace mfsd
