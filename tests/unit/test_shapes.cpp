// Scene geometry: primitives, operations and STL meshes, checked by filling
// them with the generator's lattice (particle counts against exact lattice
// counts) and by the errors for bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "host/scene/particle_generator.hpp"
#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"
#include "host/scene/stl_mesh.hpp"

using namespace mfsd;
namespace fs = std::filesystem;

namespace {

// Particles of a one-body scene with the given geometry (JSON) and spacing.
long count(int dim, const std::string& geometry, double dp, const std::string& base_dir = "") {
  const std::string text =
      R"({"name": "s", "dimension": )" + std::to_string(dim) +
      R"(, "solver": {"end_time": 1}, "bodies": [{"name": "b", "spacing": )" + std::to_string(dp) +
      R"(, "geometry": )" + geometry +
      R"(, "material": {"model": "neo_hookean", "density": 1, "youngs_modulus": 1, "poisson_ratio": 0.3}}]})";
  return long(generate_particles(load_scene_text(text, "test", {}, base_dir).scene).size());
}

std::string scene_error(int dim, const std::string& geometry, const std::string& base_dir = "") {
  try {
    count(dim, geometry, 0.1, base_dir);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "no error";
}

// Lattice points (k + 1/2) dp of the bounding box [lo, hi]^dim inside `inside`.
template <class F>
long lattice_count(int dim, double lo, double hi, double dp, F inside) {
  const long n = std::lround((hi - lo) / dp);
  long c = 0;
  for (long k = 0; k < (dim == 3 ? n : 1); ++k)
    for (long j = 0; j < n; ++j)
      for (long i = 0; i < n; ++i) {
        const double x = lo + (i + 0.5) * dp, y = lo + (j + 0.5) * dp, z = dim == 3 ? lo + (k + 0.5) * dp : 0;
        c += inside(x, y, z);
      }
  return c;
}

using Tri = std::array<Point3, 3>;

// The 12 triangles of the box [a, b]^3, outward-oriented.
std::vector<Tri> cube(double a, double b) {
  const Point3 p[8] = {{a, a, a}, {b, a, a}, {b, b, a}, {a, b, a}, {a, a, b}, {b, a, b}, {b, b, b}, {a, b, b}};
  const int f[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                        {2, 3, 7}, {2, 7, 6}, {1, 2, 6}, {1, 6, 5}, {3, 0, 4}, {3, 4, 7}};
  std::vector<Tri> t;
  for (auto& k : f) t.push_back({p[k[0]], p[k[1]], p[k[2]]});
  return t;
}

// A closed triangulated sphere (latitude-longitude) of radius r about c.
std::vector<Tri> uv_sphere(const Point3& c, double r, int nlat, int nlon) {
  auto at = [&](int i, int j) {
    const double th = M_PI * i / nlat, ph = 2 * M_PI * j / nlon;
    if (i == 0) return Point3{c[0], c[1], c[2] + r};
    if (i == nlat) return Point3{c[0], c[1], c[2] - r};
    return Point3{c[0] + r * std::sin(th) * std::cos(ph), c[1] + r * std::sin(th) * std::sin(ph),
                  c[2] + r * std::cos(th)};
  };
  std::vector<Tri> t;
  for (int i = 0; i < nlat; ++i)
    for (int j = 0; j < nlon; ++j) {
      const int jn = (j + 1) % nlon;
      if (i > 0) t.push_back({at(i, j), at(i + 1, j), at(i, jn)});
      if (i + 1 < nlat) t.push_back({at(i, jn), at(i + 1, j), at(i + 1, jn)});
    }
  return t;
}

void write_ascii(const fs::path& f, const std::vector<Tri>& t) {
  std::ofstream o(f);
  o.precision(17);
  o << "solid test\n";
  for (auto& tri : t) {
    o << " facet normal 0 0 0\n  outer loop\n";
    for (auto& p : tri) o << "   vertex " << p[0] << " " << p[1] << " " << p[2] << "\n";
    o << "  endloop\n endfacet\n";
  }
  o << "endsolid test\n";
}

void write_binary(const fs::path& f, const std::vector<Tri>& t) {
  std::ofstream o(f, std::ios::binary);
  char header[80] = {};
  o.write(header, 80);
  const std::uint32_t n = std::uint32_t(t.size());
  o.write(reinterpret_cast<const char*>(&n), 4);
  for (auto& tri : t) {
    float rec[12] = {};
    for (int v = 0; v < 3; ++v)
      for (int a = 0; a < 3; ++a) rec[3 + 3 * v + a] = float(tri[size_t(v)][size_t(a)]);
    o.write(reinterpret_cast<const char*>(rec), 48);
    const std::uint16_t attr = 0;
    o.write(reinterpret_cast<const char*>(&attr), 2);
  }
}

class StlFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() / ("mfsd_stl_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                     "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

}  // namespace

TEST(Shapes, CircleAnnulusAndPolygon2d) {
  const double dp = 0.05;
  EXPECT_EQ(count(2, R"({"circle": {"center": [0, 0], "radius": 0.5}})", dp),
            lattice_count(2, -0.5, 0.5, dp, [](double x, double y, double) { return x * x + y * y <= 0.25 + 1e-12; }));
  EXPECT_EQ(count(2, R"({"circle": {"center": [0, 0], "radius": 0.5, "inner_radius": 0.3}})", dp),
            lattice_count(2, -0.5, 0.5, dp, [](double x, double y, double) {
              const double r2 = x * x + y * y;
              return r2 <= 0.25 + 1e-12 && r2 >= 0.09 - 1e-12;
            }));
  // A triangle with its right angle at the origin: the lattice points strictly
  // below the diagonal x + y = 1 plus those on it.
  EXPECT_EQ(count(2, R"({"polygon": {"points": [[0, 0], [1, 0], [0, 1]]}})", 0.1),
            lattice_count(2, 0, 1, 0.1, [](double x, double y, double) { return x + y <= 1 + 1e-9; }));
}

TEST(Shapes, SphereCylinderAndExtrusion3d) {
  const double dp = 0.1;
  EXPECT_EQ(
      count(3, R"({"sphere": {"center": [0, 0, 0], "radius": 1}})", dp),
      lattice_count(3, -1, 1, dp, [](double x, double y, double z) { return x * x + y * y + z * z <= 1 + 1e-12; }));
  // A tube along z from z = -1 to 1 equals the extruded annulus.
  const long tube =
      count(3, R"({"cylinder": {"base": [0, 0, -1], "axis": [0, 0, 2], "radius": 1, "inner_radius": 0.5}})", dp);
  EXPECT_EQ(tube, count(3,
                        R"({"extrude": {"shape": {"circle": {"center": [0, 0], "radius": 1, "inner_radius": 0.5}},
                            "z": [-1, 1]}})",
                        dp));
  EXPECT_EQ(tube, lattice_count(3, -1, 1, dp, [](double x, double y, double) {
              const double r2 = x * x + y * y;
              return r2 <= 1 + 1e-12 && r2 >= 0.25 - 1e-12;
            }));
  // The same tube along x, by a transform (rotation about y by 90 degrees).
  EXPECT_EQ(tube, count(3,
                        R"({"transform": {"shape": {"cylinder": {"base": [0, 0, -1], "axis": [0, 0, 2], "radius": 1,
                            "inner_radius": 0.5}}, "axis": [0, 1, 0], "rotate_degrees": 90}})",
                        dp));
}

TEST(Shapes, TransformTranslatesScalesAndRotates) {
  // A unit square scaled by 2 and moved: a 2 x 2 square of 20 x 20 particles.
  EXPECT_EQ(count(2, R"({"transform": {"shape": {"box": {"min": [0, 0], "max": [1, 1]}}, "scale": 2,
                         "translate": [5, -3]}})",
                  0.1),
            400);
  // A square rotated by 45 degrees holds the points with |x| + |y| <= 1/sqrt(2).
  EXPECT_EQ(count(2, R"({"transform": {"shape": {"box": {"min": [-0.5, -0.5], "max": [0.5, 0.5]}},
                         "rotate_degrees": 45}})",
                  0.05),
            lattice_count(2, -std::sqrt(0.5), std::sqrt(0.5) + 0.05 - 1e-9, 0.05, [](double x, double y, double) {
              return std::abs(x) + std::abs(y) <= std::sqrt(0.5) + 1e-9;
            }));
}

TEST(Shapes, WrongDimensionAndBadValuesAreErrors) {
  EXPECT_NE(scene_error(2, R"({"sphere": {"center": [0, 0], "radius": 1}})").find("one of"), std::string::npos);
  EXPECT_NE(scene_error(3, R"({"circle": {"center": [0, 0, 0], "radius": 1}})").find("/geometry/circle"),
            std::string::npos);
  EXPECT_NE(scene_error(2, R"({"circle": {"center": [0, 0], "radius": 1, "inner_radius": 2}})").find("inner_radius"),
            std::string::npos);
  EXPECT_NE(scene_error(2, R"({"polygon": {"points": [[0, 0], [1, 1], [2, 2]]}})").find("zero area"),
            std::string::npos);
  EXPECT_NE(scene_error(3, R"({"cylinder": {"base": [0, 0, 0], "axis": [0, 0, 0], "radius": 1}})").find("axis"),
            std::string::npos);
  EXPECT_NE(scene_error(2, R"({"circle": {"center": [0, 0], "radius": 0.01}})").find("holds at least one particle"),
            std::string::npos);
}

TEST_F(StlFiles, ClosedCubeFillsLikeTheBox) {
  // ASCII and binary cube meshes whose diagonals pass through lattice points
  // (x = y on the faces): the tie-break counts each point once.
  write_ascii(dir_ / "cube.stl", cube(0, 1));
  write_binary(dir_ / "cube_bin.stl", cube(0, 1));
  const long box = count(3, R"({"box": {"min": [0, 0, 0], "max": [1, 1, 1]}})", 0.1);
  EXPECT_EQ(box, 1000);
  EXPECT_EQ(count(3, R"({"stl": {"file": "cube.stl"}})", 0.1, dir_.string()), box);
  EXPECT_EQ(count(3, R"({"stl": {"file": "cube_bin.stl"}})", 0.1, dir_.string()), box);
  EXPECT_EQ(count(3, R"({"stl": {"file": "cube.stl", "scale": 2}})", 0.1, dir_.string()), 8 * box);
}

TEST_F(StlFiles, TriangulatedSphereIsBetweenItsInscribedAndCircumscribedBalls) {
  // The inside test on a lattice that does not line up with the mesh: the
  // points inside are those of the inscribed ball plus some between the balls.
  const Point3 c{0.013, -0.007, 0.004};
  write_binary(dir_ / "sphere.stl", uv_sphere(c, 1.0, 48, 96));
  const auto mesh = TriangleMesh::load((dir_ / "sphere.stl").string());
  const double ri = std::cos(M_PI / 48) * std::cos(M_PI / 96);  // below every facet's distance from c
  long n = 0, inner = 0, outer = 0, wrong = 0;
  lattice_count(3, -1.2, 1.2, 0.05, [&](double x, double y, double z) {
    const double r2 = std::pow(x - c[0], 2) + std::pow(y - c[1], 2) + std::pow(z - c[2], 2);
    const bool in = mesh->contains({x, y, z});
    n += in;
    inner += r2 <= ri * ri;
    outer += r2 <= 1;
    wrong += (r2 <= ri * ri && !in) || (r2 > 1 && in);
    return in;
  });
  EXPECT_EQ(wrong, 0);
  EXPECT_GE(n, inner);
  EXPECT_LE(n, outer);
  EXPECT_GT(inner, 30000);
  // And through the scene: a body from the file is not empty and within the ball's count.
  const long body = count(3, R"({"stl": {"file": "sphere.stl"}})", 0.1, dir_.string());
  EXPECT_GT(body, 4000);
  EXPECT_LT(body, 4300);
}

TEST_F(StlFiles, MeshWithAHoleIsAClearError) {
  auto t = cube(0, 1);
  t.pop_back();  // one triangle of a face missing
  write_ascii(dir_ / "open.stl", t);
  const std::string e = scene_error(3, R"({"stl": {"file": "open.stl"}})", dir_.string());
  EXPECT_NE(e.find("/geometry/stl/file"), std::string::npos) << e;
  EXPECT_NE(e.find("not a closed surface"), std::string::npos) << e;
  EXPECT_NE(e.find("3 edge(s)"), std::string::npos) << e;
  const std::string missing = scene_error(3, R"({"stl": {"file": "none.stl"}})", dir_.string());
  EXPECT_NE(missing.find("cannot be opened: looked for " + (dir_ / "none.stl").lexically_normal().string() +
                         " (a relative name is taken from the scene file's folder)"),
            std::string::npos)
      << missing;
  std::ofstream(dir_ / "junk.stl") << "not an stl file";
  EXPECT_NE(scene_error(3, R"({"stl": {"file": "junk.stl"}})", dir_.string()).find("neither ASCII"), std::string::npos);
}
