// Scene files and meshes: shipped scenes load, procedural shapes are closed and correctly wound
// with analytic normals, transforms treat normals by the inverse transpose, and every kind of bad
// input ends in a SceneError that names the file, the field and what was expected.
#include "host/scene.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <utility>

#include "host/mesh.h"
#include "host/mesh_import.h"
#include "tests/support/test_data.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kScenes = std::string(SHADESIM_SOURCE_DIR) + "/scenes/";
const std::string kAssimpModels = "/usr/share/assimp/models";

class TempDir {
 public:
  TempDir() {
    path_ = fs::temp_directory_path() / ("shadesim_scene_test_" + std::to_string(::getpid()));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    std::string p = (path_ / name).string();  // returned: moved
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  std::string path() const { return path_.string(); }

 private:
  fs::path path_;
};

// Runs `fn`, which must throw SceneError; returns its message.
std::string scene_error(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const SceneError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected SceneError, got another exception: " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected SceneError, nothing thrown";
  return "";
}

double max_abs_diff(const Vec3& a, const Vec3& b) {
  return std::max({std::fabs(a.x - b.x), std::fabs(a.y - b.y), std::fabs(a.z - b.z)});
}

// Every undirected edge (by position, so duplicated rim vertices count as one) is used exactly
// twice, once in each direction: the surface is closed and consistently oriented.
void expect_closed_and_consistent(const Mesh& mesh) {
  std::map<std::tuple<double, double, double>, int> id_of;
  std::vector<int> canon(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3& p = mesh.positions[i];
    canon[i] =
        id_of.emplace(std::make_tuple(p.x, p.y, p.z), static_cast<int>(id_of.size())).first->second;
  }
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{canon[t[k]], canon[t[(k + 1) % 3]]}];
  for (const auto& [edge, count] : directed) {
    ASSERT_EQ(count, 1) << "directed edge used more than once";
    const auto reverse = directed.find({edge.second, edge.first});
    ASSERT_TRUE(reverse != directed.end()) << "edge without a twin: surface not closed";
  }
}

// Counter-clockwise from outside: the face normal by the right-hand rule agrees with the normals.
void expect_outward_winding(const Mesh& mesh) {
  for (const auto& t : mesh.triangles) {
    const Vec3 face = cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                            mesh.positions[t[2]] - mesh.positions[t[0]]);
    const Vec3 avg = mesh.normals[t[0]] + mesh.normals[t[1]] + mesh.normals[t[2]];
    ASSERT_GT(dot(face, avg), 0.0);
  }
}

void expect_unit_normals(const Mesh& mesh) {
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  for (const Vec3& n : mesh.normals) ASSERT_NEAR(length(n), 1.0, 1e-12);
}

TEST(Shapes, SphereIsClosedOutwardWithRadialNormals) {
  const double r = 1.7;
  const Mesh m = make_sphere(r, 12);
  expect_unit_normals(m);
  expect_closed_and_consistent(m);
  expect_outward_winding(m);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    EXPECT_NEAR(length(m.positions[i]), r, 1e-12);
    EXPECT_LT(max_abs_diff(m.normals[i], m.positions[i] / r), 1e-12);
  }
  // Euler characteristic of a sphere: V - E + F = 2.
  EXPECT_EQ(static_cast<int64_t>(m.positions.size()) -
                3 * static_cast<int64_t>(m.triangles.size()) / 2 +
                static_cast<int64_t>(m.triangles.size()),
            2);
}

TEST(Shapes, TorusIsClosedOutwardWithTubeNormals) {
  const double big = 2.0, small = 0.5;
  const Mesh m = make_torus(big, small, 10);
  expect_unit_normals(m);
  expect_closed_and_consistent(m);
  expect_outward_winding(m);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const Vec3 p = m.positions[i];
    const Vec3 ring_point = normalize(Vec3{p.x, 0, p.z}) * big;
    EXPECT_NEAR(length(p - ring_point), small, 1e-12);
    EXPECT_LT(max_abs_diff(m.normals[i], (p - ring_point) / small), 1e-12);
  }
  // Genus one: V - E + F = 0.
  EXPECT_EQ(static_cast<int64_t>(m.positions.size()) - static_cast<int64_t>(m.triangles.size()) / 2,
            0);
}

TEST(Shapes, CylinderHasFlatCapsAndRadialSides) {
  const double r = 0.8, h = 3.0;
  const Mesh m = make_cylinder(r, h, 16);
  expect_unit_normals(m);
  expect_closed_and_consistent(m);
  expect_outward_winding(m);
  int cap_vertices = 0;
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const Vec3 p = m.positions[i], n = m.normals[i];
    if (std::fabs(n.y) == 1.0) {
      ++cap_vertices;
      EXPECT_EQ(p.y, n.y * h / 2);  // top cap faces up, bottom cap down
    } else {
      EXPECT_NEAR(std::hypot(p.x, p.z), r, 1e-12);
      EXPECT_NEAR(std::fabs(p.y), h / 2, 1e-12);
      EXPECT_LT(max_abs_diff(n, Vec3{p.x / r, 0, p.z / r}), 1e-12);
    }
  }
  EXPECT_EQ(cap_vertices, 2 * (16 + 1));  // rims duplicated, plus the centres
}

TEST(Shapes, PlaneFacesUp) {
  const Mesh m = make_plane(4.0, 3);
  EXPECT_EQ(m.positions.size(), 16u);
  EXPECT_EQ(m.triangles.size(), 18u);
  expect_outward_winding(m);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    EXPECT_EQ(m.positions[i].y, 0.0);
    EXPECT_LE(std::fabs(m.positions[i].x), 2.0);
    EXPECT_TRUE(m.normals[i] == (Vec3{0, 1, 0}));
  }
}

TEST(Shapes, TessellationOutOfRangeIsRejected) {
  EXPECT_THROW(make_sphere(1, 2), std::invalid_argument);
  EXPECT_THROW(make_torus(1, 0.2, kMaxTessellation + 1), std::invalid_argument);
  EXPECT_THROW(make_plane(1, 0), std::invalid_argument);
}

TEST(Transform, EulerXyzOrder) {
  Mesh point;
  point.positions = {{0, 1, 0}};
  point.normals = {{0, 1, 0}};
  Transform t;
  // Rotating +90 degrees about x takes +y to +z; then +90 about y takes +z to +x.
  t.rotate_deg = {90, 0, 0};
  EXPECT_LT(max_abs_diff(transform_mesh(point, t).positions[0], {0, 0, 1}), 1e-12);
  t.rotate_deg = {90, 90, 0};
  EXPECT_LT(max_abs_diff(transform_mesh(point, t).positions[0], {1, 0, 0}), 1e-12);
  // ... and +90 about z then takes +x to +y.
  t.rotate_deg = {90, 90, 90};
  EXPECT_LT(max_abs_diff(transform_mesh(point, t).positions[0], {0, 1, 0}), 1e-12);
  t = Transform{};
  t.scale = {2, 3, 4};
  t.translate = {1, 1, 1};
  EXPECT_LT(max_abs_diff(transform_mesh(point, t).positions[0], {1, 4, 1}), 1e-12);
}

TEST(Transform, NonUniformScaleGivesEllipsoidNormals) {
  // The ellipsoid (x/a)^2 + (y/b)^2 + (z/c)^2 = 1 has normal along (x/a^2, y/b^2, z/c^2).
  const double a = 2, b = 0.5, c = 1.25;
  Transform t;
  t.scale = {a, b, c};
  const Mesh m = transform_mesh(make_sphere(1, 10), t);
  expect_unit_normals(m);
  expect_outward_winding(m);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const Vec3 p = m.positions[i];
    const Vec3 gradient = normalize(Vec3{p.x / (a * a), p.y / (b * b), p.z / (c * c)});
    EXPECT_LT(max_abs_diff(m.normals[i], gradient), 1e-12);
  }
}

TEST(Transform, MirrorKeepsOutwardWinding) {
  Transform t;
  t.scale = {-1, 1, 1};
  const Mesh m = transform_mesh(make_torus(1, 0.3, 8), t);
  expect_outward_winding(m);
  expect_closed_and_consistent(m);
}

// ---- Shipped scenes ----

TEST(ShippedScenes, SphereIsGreyDiffuseOnly) {
  const Scene s = load_scene(kScenes + "sphere.json");
  EXPECT_EQ(s.width, 256);
  EXPECT_EQ(s.height, 256);
  EXPECT_EQ(s.camera.kind, Camera::Kind::kPerspective);
  EXPECT_TRUE(s.is_grey());
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_TRUE(s.materials[0].specular == (Vec3{0, 0, 0}));
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_NEAR(length(s.lights[0].direction), 1.0, 1e-15);
  EXPECT_LT(max_abs_diff(s.lights[0].direction, Vec3{1, 1, 1} / std::sqrt(3.0)), 1e-15);
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_GT(s.objects[0].mesh.triangles.size(), 1000u);
  EXPECT_EQ(s.error_budget_lsb, 1.0);
  EXPECT_TRUE(s.eye_at_infinity);
}

TEST(ShippedScenes, TorusSpecularAndMultiLoad) {
  const Scene torus = load_scene(kScenes + "torus.json");
  EXPECT_EQ(torus.objects.size(), 1u);
  const Scene specular = load_scene(kScenes + "specular.json");
  EXPECT_FALSE(specular.eye_at_infinity);
  EXPECT_GE(specular.materials.at(0).exponent, 40.0);
  const Scene multi = load_scene(kScenes + "multi.json");
  EXPECT_FALSE(multi.is_grey());
  EXPECT_GE(multi.objects.size(), 3u);
  EXPECT_EQ(multi.materials.size(), 2u);
  EXPECT_EQ(multi.lights.size(), 2u);
  std::set<int> used;
  for (const Object& o : multi.objects) used.insert(o.material);
  EXPECT_EQ(used.size(), 2u);
  for (const char* name : {"sphere.json", "torus.json", "multi.json", "specular.json"}) {
    const Scene s = load_scene(kScenes + name);
    EXPECT_LE(s.width, 512) << name;
    EXPECT_LE(s.height, 512) << name;
  }
}

TEST(ShippedScenes, RealMeshFromAssimpTestModels) {
  SHADESIM_NEEDS_TEST_FILE(fs::path(kAssimpModels));
  const Scene s = load_scene(kScenes + "suzanne.json");
  ASSERT_EQ(s.objects.size(), 1u);
  const Mesh& m = s.objects[0].mesh;
  EXPECT_GT(m.triangles.size(), 500u);
  expect_unit_normals(m);
}

// ---- Mesh files ----

TEST(MeshFiles, ObjWithoutNormalsGetsSmoothNormals) {
  TempDir dir;
  // Tetrahedron with outward counter-clockwise faces and no normals in the file.
  const std::string obj = dir.write("tet.obj",
                                    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const Mesh m = load_mesh_file(obj);
  EXPECT_EQ(m.triangles.size(), 4u);
  expect_unit_normals(m);
  // Smooth normal at each corner: the normalised sum of its three faces' unit normals.
  const Vec3 nx{-1, 0, 0}, ny{0, -1, 0}, nz{0, 0, -1}, slope = Vec3{1, 1, 1} / std::sqrt(3.0);
  const std::vector<std::pair<Vec3, Vec3>> expected = {{{0, 0, 0}, normalize(nx + ny + nz)},
                                                       {{1, 0, 0}, normalize(ny + nz + slope)},
                                                       {{0, 1, 0}, normalize(nx + nz + slope)},
                                                       {{0, 0, 1}, normalize(nx + ny + slope)}};
  int matched = 0;
  for (size_t i = 0; i < m.positions.size(); ++i) {
    for (const auto& [position, normal] : expected) {
      if (m.positions[i] == position) {
        EXPECT_LT(max_abs_diff(m.normals[i], normal), 1e-6);
        ++matched;
      }
    }
  }
  EXPECT_EQ(matched, static_cast<int>(m.positions.size()));
  // Faces keep the file's counter-clockwise-from-outside order.
  for (const auto& t : m.triangles) {
    const Vec3 face =
        cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
    const Vec3 centroid = (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) / 3.0;
    EXPECT_GT(dot(face, centroid - Vec3{0.25, 0.25, 0.25}), 0.0);
  }
}

// A cube whose eight corners each serve three quads (OFF shares vertices between faces, as
// assimp-testmodels' OFF/Cube.off does): the smooth normal at a corner is its diagonal, the
// normalised sum of its three faces' unit normals whichever way the quads are cut. Debian's
// assimp 5.2 aiProcess_GenSmoothNormals gave each shared vertex the normal of the last face
// naming it (+-x here), so the shading normal field of a face crossed zero and setup wrote
// non-finite or unbounded Taylor coefficients (random scenes s1_i00558 and six others).
TEST(MeshFiles, SharedVertexCubeGetsCornerNormals) {
  TempDir dir;
  const std::string off = dir.write("cube.off",
                                    "OFF\n8 6 0\n-1 -1 1\n1 -1 1\n-1 1 1\n1 1 1\n-1 1 -1\n"
                                    "1 1 -1\n-1 -1 -1\n1 -1 -1\n4 0 1 3 2\n4 2 3 5 4\n"
                                    "4 4 5 7 6\n4 6 7 1 0\n4 1 7 5 3\n4 6 0 2 4\n");
  const Mesh m = load_mesh_file(off);
  EXPECT_EQ(m.triangles.size(), 12u);
  expect_unit_normals(m);
  expect_outward_winding(m);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const Vec3& p = m.positions[i];
    const Vec3 diagonal = Vec3{p.x, p.y, p.z} / std::sqrt(3.0);  // corners at +-1
    EXPECT_LT(max_abs_diff(m.normals[i], diagonal), 1e-6)
        << "vertex " << i << " at " << p.x << " " << p.y << " " << p.z << ": normal "
        << m.normals[i].x << " " << m.normals[i].y << " " << m.normals[i].z;
  }
}

TEST(MeshFiles, PlyAndStlLoad) {
  TempDir dir;
  const std::string ply = dir.write("quad.ply",
                                    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                                    "property float y\nproperty float z\nelement face 1\n"
                                    "property list uchar int vertex_indices\nend_header\n"
                                    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  const Mesh quad = load_mesh_file(ply);
  EXPECT_EQ(quad.triangles.size(), 2u);  // the quad is triangulated
  for (const Vec3& n : quad.normals) EXPECT_LT(max_abs_diff(n, {0, 0, 1}), 1e-6);
  const std::string stl = dir.write("tri.stl",
                                    "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                                    "vertex 2 0 0\nvertex 0 2 0\nendloop\nendfacet\nendsolid t\n");
  const Mesh one = load_mesh_file(stl);
  ASSERT_EQ(one.triangles.size(), 1u);
  for (const Vec3& n : one.normals) EXPECT_LT(max_abs_diff(n, {0, 0, 1}), 1e-6);
}

TEST(MeshFiles, EveryAssimpInvalidModelGivesSceneError) {
  const fs::path invalid = fs::path(kAssimpModels) / "invalid";
  SHADESIM_NEEDS_TEST_FILE(invalid);
  MeshImporter shared;
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(invalid)) {
    const std::string path = entry.path().string();
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(path);
    if (name == "malformed2.obj") {
      // Its only fault is a reference to a missing material; the geometry (a cube of five quads
      // and an empty face line) is valid, so it must load as exactly that.
      const Mesh m = load_mesh_file(path);
      EXPECT_EQ(m.triangles.size(), 10u);
      expect_unit_normals(m);
      ++checked;
      continue;
    }
    const std::string message = scene_error([&] { load_mesh_file(path); });
    EXPECT_NE(message.find(path), std::string::npos) << message;
    // One import process for every file gives each the answer a process of its own gives.
    EXPECT_EQ(scene_error([&] { shared.load(path); }), message);
    ++checked;
  }
  EXPECT_GE(checked, 10);
}

// The import process this one forked last: the only child of this test's thread.
pid_t import_process() {
  std::ifstream children("/proc/self/task/" + std::to_string(::gettid()) + "/children");
  pid_t pid = 0;
  children >> pid;
  return pid;
}

// One importer serves kImportsPerProcess files with one process, then starts another, and the
// files keep loading the same.
TEST(MeshFiles, ImporterReplacesItsProcessAfterItsLifetime) {
  TempDir dir;
  const std::string obj = dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  MeshImporter importer;
  EXPECT_EQ(import_process(), 0);  // started by the first load, not before
  importer.load(obj);
  const pid_t first = import_process();
  ASSERT_GT(first, 0);
  for (int i = 1; i < MeshImporter::kImportsPerProcess; ++i) {
    ASSERT_EQ(importer.load(obj).triangles.size(), 1u) << "import " << i;
  }
  EXPECT_EQ(import_process(), first);
  EXPECT_EQ(importer.load(obj).triangles.size(), 1u);
  const pid_t second = import_process();
  EXPECT_GT(second, 0);
  EXPECT_NE(second, first);
}

TEST(MeshFiles, MissingFileAndNoTriangles) {
  TempDir dir;
  const std::string missing = dir.path() + "/nope.obj";
  std::string message = scene_error([&] { load_mesh_file(missing); });
  EXPECT_NE(message.find(missing), std::string::npos) << message;
  EXPECT_NE(message.find("cannot open"), std::string::npos) << message;
  const std::string points =
      dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1\np 2\nl 1 3\n");
  message = scene_error([&] { load_mesh_file(points); });
  EXPECT_NE(message.find(points), std::string::npos) << message;
  EXPECT_NE(message.find("triangle"), std::string::npos) << message;
}

// ---- Scene errors ----

json valid_scene() {
  return json::parse(R"({
    "image": {"width": 64, "height": 48},
    "camera": {"type": "perspective", "position": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0],
               "fov_y": 40},
    "lights": [{"direction": [0, 0, 2], "colour": [1, 1, 1]}],
    "ambient_light": 1,
    "materials": [{"name": "m", "diffuse": 0.5, "specular": 0.2, "exponent": 10, "unit": "ideal"},
                  {"name": "n", "diffuse": [0.5, 0.2, 0.1]}],
    "objects": [{"type": "sphere", "material": "m", "radius": 1, "tessellation": 8},
                {"type": "plane", "material": "n", "size": 3}]
  })");
}

TEST(SceneErrors, ValidBaseSceneLoads) {
  TempDir dir;
  const Scene s = load_scene(dir.write("ok.json", valid_scene().dump()));
  EXPECT_EQ(s.width, 64);
  EXPECT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.objects[1].material, 1);
  EXPECT_FALSE(s.is_grey());
  EXPECT_LT(max_abs_diff(s.lights[0].direction, {0, 0, 1}), 1e-15);
}

TEST(SceneFiles, SpecularModelDefaultsToBlinnAndMaterialOverridesScene) {
  TempDir dir;
  json j = valid_scene();
  EXPECT_EQ(load_scene(dir.write("default.json", j.dump())).materials[0].specular_model,
            SpecularModel::kBlinn);
  j["specular_model"] = "phong";
  j["materials"][1]["specular_model"] = "blinn";
  const Scene s = load_scene(dir.write("mixed.json", j.dump()));
  EXPECT_EQ(s.materials[0].specular_model, SpecularModel::kPhong);  // the scene's
  EXPECT_EQ(s.materials[1].specular_model, SpecularModel::kBlinn);  // its own
  EXPECT_EQ(load_scene(kScenes + "hard/phong.json").materials[0].specular_model,
            SpecularModel::kPhong);
  for (const char* shipped : {"sphere", "torus", "multi", "specular", "suzanne"}) {
    const std::string text = [&] {
      std::ifstream in(kScenes + shipped + ".json");
      return std::string(std::istreambuf_iterator<char>(in), {});
    }();
    EXPECT_EQ(text.find("specular_model"), std::string::npos) << shipped << " stays Blinn";
  }
}

struct BadField {
  const char* what;
  std::function<void(json&)> mutate;
  std::string field;     // JSON path that must appear in the message
  std::string expected;  // text that must appear in the message
};

TEST(SceneErrors, EveryBadFieldNamesFileFieldAndExpectation) {
  const std::vector<BadField> cases = {
      {"missing image", [](json& j) { j.erase("image"); }, "image", "expected"},
      {"width zero", [](json& j) { j["image"]["width"] = 0; }, "image.width", "[1, 4096]"},
      {"height too big", [](json& j) { j["image"]["height"] = 5000; }, "image.height", "[1, 4096]"},
      {"width fractional", [](json& j) { j["image"]["width"] = 10.5; }, "image.width", "integer"},
      {"width string", [](json& j) { j["image"]["width"] = "64"; }, "image.width", "got string"},
      {"typo in image", [](json& j) { j["image"]["widht"] = 3; }, "image.widht",
       "accepted: width, height"},
      {"typo at top", [](json& j) { j["light"] = json::array(); }, "light", "accepted:"},
      {"camera type", [](json& j) { j["camera"]["type"] = "fisheye"; }, "camera.type",
       "orthographic"},
      {"fov out of range", [](json& j) { j["camera"]["fov_y"] = 180; }, "camera.fov_y", "[1, 179]"},
      {"ortho with fov", [](json& j) { j["camera"]["type"] = "orthographic"; }, "camera.fov_y",
       "accepted:"},
      {"up parallel",
       [](json& j) {
         j["camera"]["up"] = {0, 0, 1};
       },
       "camera.up", "parallel"},
      {"position short",
       [](json& j) {
         j["camera"]["position"] = {0, 0};
       },
       "camera.position", "array of 3"},
      {"target equals position",
       [](json& j) {
         j["camera"]["target"] = {0, 0, 5};
       },
       "camera.target", "distinct"},
      {"no lights", [](json& j) { j["lights"] = json::array(); }, "lights", "non-empty array"},
      {"zero light direction",
       [](json& j) {
         j["lights"][0]["direction"] = {0, 0, 0};
       },
       "lights[0].direction", "non-zero"},
      {"negative colour",
       [](json& j) {
         j["lights"][0]["colour"] = {1, -0.5, 1};
       },
       "lights[0].colour", ">= 0"},
      {"light colour word", [](json& j) { j["lights"][0]["colour"] = "white"; }, "lights[0].colour",
       "got string"},
      {"eye", [](json& j) { j["eye"] = "near"; }, "eye", "\"infinite\" or \"finite\""},
      {"budget", [](json& j) { j["error_budget_lsb"] = 0; }, "error_budget_lsb", "positive"},
      {"ambient negative", [](json& j) { j["ambient_light"] = -1; }, "ambient_light", ">= 0"},
      {"no materials", [](json& j) { j.erase("materials"); }, "materials", "missing"},
      {"exponent zero", [](json& j) { j["materials"][0]["exponent"] = 0.5; },
       "materials[0].exponent", "[1, 1000]"},
      {"exponent big", [](json& j) { j["materials"][0]["exponent"] = 1001; },
       "materials[0].exponent", "[1, 1000]"},
      {"unknown unit", [](json& j) { j["materials"][0]["unit"] = "magic"; }, "materials[0].unit",
       "magic"},
      {"material typo", [](json& j) { j["materials"][1]["difuse"] = 0.3; }, "materials[1].difuse",
       "accepted:"},
      {"material no name", [](json& j) { j["materials"][1].erase("name"); }, "materials[1].name",
       "string"},
      {"duplicate material", [](json& j) { j["materials"][1]["name"] = "m"; }, "materials[1].name",
       "unique"},
      {"diffuse two",
       [](json& j) {
         j["materials"][0]["diffuse"] = {0.1, 0.2};
       },
       "materials[0].diffuse", "[r, g, b]"},
      {"no objects", [](json& j) { j["objects"] = json::array(); }, "objects", "non-empty"},
      {"object type", [](json& j) { j["objects"][1]["type"] = "cube"; }, "objects[1].type",
       "sphere"},
      {"unknown material", [](json& j) { j["objects"][1]["material"] = "gold"; },
       "objects[1].material", "\"m\", \"n\""},
      {"sphere with size", [](json& j) { j["objects"][0]["size"] = 2; }, "objects[0].size",
       "accepted:"},
      {"radius negative", [](json& j) { j["objects"][0]["radius"] = -1; }, "objects[0].radius",
       "positive"},
      {"tessellation low", [](json& j) { j["objects"][0]["tessellation"] = 2; },
       "objects[0].tessellation", "[3, 1024]"},
      {"tessellation huge", [](json& j) { j["objects"][0]["tessellation"] = 100000; },
       "objects[0].tessellation", "[3, 1024]"},
      {"plane tessellation zero", [](json& j) { j["objects"][1]["tessellation"] = 0; },
       "objects[1].tessellation", "[1, 1024]"},
      {"scale zero",
       [](json& j) {
         j["objects"][0]["transform"] = {{"scale", 0}};
       },
       "objects[0].transform.scale", "non-zero"},
      {"rotate typo",
       [](json& j) {
         j["objects"][0]["transform"] = {{"rotate", {1, 2, 3}}};
       },
       "objects[0].transform.rotate", "rotate_deg"},
      {"translate nan-ish",
       [](json& j) {
         j["objects"][0]["transform"] = {{"translate", {1, "x", 3}}};
       },
       "objects[0].transform.translate[1]", "finite number"},
      {"mesh without file",
       [](json& j) {
         j["objects"][1] = {{"type", "mesh"}, {"material", "m"}};
       },
       "objects[1].file", "missing"},
      {"mesh missing file",
       [](json& j) {
         j["objects"][1] = {{"type", "mesh"}, {"material", "m"}, {"file", "no.obj"}};
       },
       "objects[1].file", "cannot open"},
      {"objects not array",
       [](json& j) {
         j["objects"] = {{"type", "sphere"}};
       },
       "objects", "array"},
      {"root not object", [](json& j) { j = json::array(); }, "(top level)", "expected an object"},
      {"specular model", [](json& j) { j["specular_model"] = "cook-torrance"; }, "specular_model",
       "\"phong\" or \"blinn\""},
      {"material specular model", [](json& j) { j["materials"][1]["specular_model"] = "Phong"; },
       "materials[1].specular_model", "expected \"phong\" or \"blinn\""},
      {"specular model not a string", [](json& j) { j["materials"][0]["specular_model"] = 1; },
       "materials[0].specular_model", "got number 1"},
  };
  TempDir dir;
  for (const BadField& c : cases) {
    SCOPED_TRACE(c.what);
    json j = valid_scene();
    c.mutate(j);
    const std::string file = dir.write("bad.json", j.dump(2));
    const std::string message = scene_error([&] { load_scene(file); });
    EXPECT_EQ(message.rfind(file + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(": " + c.field + ": "), std::string::npos) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
  }
}

TEST(SceneErrors, MalformedJsonReportsLineAndColumn) {
  TempDir dir;
  // The second comma on line 2 is at column 15.
  const std::string file = dir.write("syntax.json", "{\n  \"image\": [1,,2]\n}\n");
  const std::string message = scene_error([&] { load_scene(file); });
  EXPECT_EQ(message.rfind(file + ":2:15: malformed JSON", 0), 0u) << message;
}

TEST(SceneErrors, NumberBeyondDoubleRangeIsASceneErrorWithItsPosition) {
  // nlohmann reports "1e999" as out_of_range (no position), not as a parse error; found by
  // mutation_test. The 1e999 on line 3 starts at column 14.
  TempDir dir;
  const std::string file =
      dir.write("overflow.json", "{\n  \"image\": {\n    \"width\": 1e999}\n}\n");
  const std::string message = scene_error([&] { load_scene(file); });
  EXPECT_EQ(message.rfind(file + ":3:14: malformed JSON: number overflow", 0), 0u) << message;
  const std::string negative = dir.write("negative.json", "[-1e999]");
  EXPECT_EQ(scene_error([&] { load_scene(negative); }).rfind(negative + ":1:2: malformed JSON", 0),
            0u);
}

TEST(SceneErrors, TruncatedAndGarbageFiles) {
  TempDir dir;
  const std::string text = valid_scene().dump(2);
  // Every proper prefix of a valid scene is malformed JSON and must say where it ended.
  for (size_t cut = 0; cut < text.size(); cut += 7) {
    const std::string file = dir.write("cut.json", text.substr(0, cut));
    const std::string message = scene_error([&] { load_scene(file); });
    ASSERT_EQ(message.rfind(file + ":", 0), 0u) << message;
    ASSERT_NE(message.find("malformed JSON"), std::string::npos) << message;
  }
  std::string garbage;
  for (int i = 0; i < 256; ++i) garbage.push_back(static_cast<char>((i * 73 + 11) & 0xff));
  const std::string file = dir.write("garbage.json", garbage);
  EXPECT_NE(scene_error([&] { load_scene(file); }).find("malformed JSON"), std::string::npos);
  const std::string missing = dir.path() + "/absent.json";
  EXPECT_NE(scene_error([&] { load_scene(missing); }).find(missing + ": cannot open"),
            std::string::npos);
}

TEST(SceneErrors, InvalidMeshInSceneNamesBothFiles) {
  const fs::path bad = fs::path(kAssimpModels) / "invalid" / "malformed.obj";
  SHADESIM_NEEDS_TEST_FILE(bad);
  TempDir dir;
  json j = valid_scene();
  j["objects"][1] = {{"type", "mesh"}, {"material", "m"}, {"file", bad.string()}};
  const std::string file = dir.write("mesh.json", j.dump());
  const std::string message = scene_error([&] { load_scene(file); });
  EXPECT_NE(message.find(file + ": objects[1].file: "), std::string::npos) << message;
  EXPECT_NE(message.find(bad.string()), std::string::npos) << message;
}

TEST(SceneFiles, RelativeMeshPathResolvesAgainstSceneDirectory) {
  TempDir dir;
  fs::create_directories(dir.path() + "/meshes");
  dir.write("meshes/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  json j = valid_scene();
  j["objects"][1] = {{"type", "mesh"},
                     {"material", "n"},
                     {"file", "meshes/tri.obj"},
                     {"transform", {{"translate", {0, 0, 1}}, {"scale", 2}}}};
  const Scene s = load_scene(dir.write("rel.json", j.dump()));
  const Mesh& m = s.objects.at(1).mesh;
  ASSERT_EQ(m.triangles.size(), 1u);
  for (const Vec3& n : m.normals) EXPECT_LT(max_abs_diff(n, {0, 0, 1}), 1e-12);
  for (const Vec3& p : m.positions) EXPECT_EQ(p.z, 1.0);
}

TEST(SceneFiles, OrthographicCameraAndGreyDetection) {
  TempDir dir;
  json j = valid_scene();
  j["camera"] = {{"type", "orthographic"}, {"height", 3}, {"position", {0, 0, 5}}};
  j["materials"][1]["diffuse"] = 0.4;
  j["eye"] = "finite";
  const Scene s = load_scene(dir.write("ortho.json", j.dump()));
  EXPECT_EQ(s.camera.kind, Camera::Kind::kOrthographic);
  EXPECT_EQ(s.camera.ortho_height, 3.0);
  EXPECT_FALSE(s.eye_at_infinity);
  EXPECT_TRUE(s.is_grey());
  j["lights"][0]["colour"] = {1, 1, 0.9};
  EXPECT_FALSE(load_scene(dir.write("ortho2.json", j.dump())).is_grey());
}

}  // namespace
}  // namespace shadesim
