// A scene as read from scene JSON: image, camera, lights, materials and objects in world space.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/vec3.h"
#include "model/specular_config.h"

namespace shadesim {

// Bad scene or mesh input. what() names the file, the field or line, and what was expected.
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Camera {
  enum class Kind { kOrthographic, kPerspective };
  Kind kind = Kind::kPerspective;
  Vec3 position{0, 0, 5};
  Vec3 target{0, 0, 0};
  Vec3 up{0, 1, 0};
  double fov_y_deg = 40.0;    // perspective: vertical field of view
  double ortho_height = 2.0;  // orthographic: world-space height of the view
  double near_plane = 0.1;
  double far_plane = 100.0;
};

struct DirectionalLight {
  Vec3 direction{0, 0, 1};  // unit vector from the surface toward the light
  Vec3 colour{1, 1, 1};
};

// Which specular cosine t the lobe t^n raises: Blinn's N.H (the default) or Phong's R.V, R the
// light direction reflected about the normal. Both are smooth in screen space, so both reach the
// unit as one Taylor series; the hardware does not know which it gets.
enum class SpecularModel { kBlinn, kPhong };
inline const char* to_string(SpecularModel m) {
  return m == SpecularModel::kPhong ? "phong" : "blinn";
}

struct Material {
  std::string name;
  Vec3 ambient{0.1, 0.1, 0.1};  // multiplied by the scene's ambient light
  Vec3 diffuse{0.7, 0.7, 0.7};
  Vec3 specular{0.3, 0.3, 0.3};
  double exponent = 32.0;  // n, 1..1000, need not be an integer
  SpecularUnitKind unit = SpecularUnitKind::kIdeal;
  // JSON "specular_model" of the material, else of the scene, else blinn.
  SpecularModel specular_model = SpecularModel::kBlinn;
};

// Triangle mesh in world space. normals[i] is the unit vertex normal of positions[i].
struct Mesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<std::array<uint32_t, 3>> triangles;  // counter-clockwise seen from outside
};

struct Object {
  std::string name;
  Mesh mesh;
  int material = 0;  // index into Scene::materials
};

struct Scene {
  std::string path;  // file it was read from, for messages
  int width = 256;
  int height = 256;
  Camera camera;
  std::vector<DirectionalLight> lights;
  Vec3 ambient_light{1, 1, 1};
  bool eye_at_infinity = true;  // false: finite eye at camera.position (Bishop's finite form)
  std::vector<Material> materials;
  std::vector<Object> objects;
  double error_budget_lsb = 1.0;  // Taylor error allowed per triangle, in output LSBs

  // True when every colour in the scene is grey, so one channel carries the image.
  bool is_grey() const;
};

// Reads and checks a scene file. Throws SceneError on any problem.
Scene load_scene(const std::string& path);

// The same for a scene file's text already in memory; `path` names it in errors, and mesh files
// are found relative to its folder.
Scene parse_scene(const std::string& text, const std::string& path);

// The file a mesh object's "file" names, as load_scene opens it: an absolute path as written, a
// relative one from the scene file's folder. (The derivation cache keys on that file's bytes.)
std::string mesh_file_path(const std::string& scene_path, const std::string& file);

}  // namespace shadesim
