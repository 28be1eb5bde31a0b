// Scene JSON reader. Every check names the file, the JSON path of the field and what was expected,
// because scene files are hand-written and a typo should cost seconds, not a debugging session.
#include "host/scene.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "host/mesh.h"
#include "host/mesh_import.h"
#include "model/json_error.h"

namespace shadesim {
namespace {

using nlohmann::json;

std::string describe(const json& value) {
  std::string text = value.dump();
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return std::string(value.type_name()) + " " + text;
}

std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string index(const std::string& path, size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

std::string format_number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// Checked access to one scene file's JSON.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& message) const {
    throw SceneError(file_ + ": " + (path.empty() ? "(top level)" : path) + ": " + message);
  }
  [[noreturn]] void fail_raw(const std::string& message) const {
    throw SceneError(file_ + ": " + message);
  }
  [[noreturn]] void fail_expected(const std::string& path, const std::string& expected,
                                  const json& got) const {
    fail(path, "expected " + expected + ", got " + describe(got));
  }

  // The object at `path` must be a JSON object whose keys are all in `accepted`.
  void check_keys(const json& object, const std::string& path,
                  std::initializer_list<const char*> accepted) const {
    if (!object.is_object()) fail_expected(path, "an object", object);
    for (const auto& item : object.items()) {
      const bool known = std::any_of(accepted.begin(), accepted.end(),
                                     [&](const char* k) { return item.key() == k; });
      if (!known) {
        std::string list;
        for (const char* k : accepted) list += std::string(list.empty() ? "" : ", ") + k;
        fail(join(path, item.key()), "unknown key \"" + item.key() + "\" (accepted: " + list + ")");
      }
    }
  }

  const json* find(const json& object, const char* key) const {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
  }

  const json& require(const json& object, const std::string& path, const char* key,
                      const std::string& expected) const {
    const json* value = find(object, key);
    if (value == nullptr)
      fail(join(path, key), "expected " + expected + ", got nothing (key missing)");
    return *value;
  }

  double number(const json& value, const std::string& path, double lo, double hi) const {
    const std::string expected =
        "a number in [" + format_number(lo) + ", " + format_number(hi) + "]";
    if (!value.is_number()) fail_expected(path, expected, value);
    const double v = value.get<double>();
    if (!(v >= lo && v <= hi)) fail_expected(path, expected, value);
    return v;
  }

  double number(const json& object, const std::string& path, const char* key, double lo, double hi,
                std::optional<double> fallback) const {
    const json* value = find(object, key);
    if (value == nullptr) {
      if (fallback) return *fallback;
      fail(join(path, key), "expected a number in [" + format_number(lo) + ", " +
                                format_number(hi) + "], got nothing (key missing)");
    }
    return number(*value, join(path, key), lo, hi);
  }

  // Strictly positive finite number.
  double positive(const json& object, const std::string& path, const char* key,
                  std::optional<double> fallback) const {
    const json* value = find(object, key);
    const std::string where = join(path, key);
    if (value == nullptr) {
      if (fallback) return *fallback;
      fail(where, "expected a positive number, got nothing (key missing)");
    }
    if (!value->is_number() || !(value->get<double>() > 0) ||
        !std::isfinite(value->get<double>())) {
      fail_expected(where, "a positive number", *value);
    }
    return value->get<double>();
  }

  int integer(const json& object, const std::string& path, const char* key, int lo, int hi,
              std::optional<int> fallback) const {
    const json* value = find(object, key);
    const std::string where = join(path, key);
    const std::string expected =
        "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (value == nullptr) {
      if (fallback) return *fallback;
      fail(where, expected + ", got nothing (key missing)");
    }
    if (!value->is_number()) fail_expected(where, expected, *value);
    const double v = value->get<double>();
    if (!(v >= lo && v <= hi) || v != std::floor(v)) fail_expected(where, expected, *value);
    return static_cast<int>(v);
  }

  std::string string(const json& object, const std::string& path, const char* key,
                     std::optional<std::string> fallback) const {
    const json* value = find(object, key);
    const std::string where = join(path, key);
    if (value == nullptr) {
      if (fallback) return *fallback;
      fail(where, "expected a string, got nothing (key missing)");
    }
    if (!value->is_string()) fail_expected(where, "a string", *value);
    return value->get<std::string>();
  }

  Vec3 vec3(const json& value, const std::string& path, const std::string& what) const {
    const std::string expected = what + " (array of 3 finite numbers)";
    if (!value.is_array() || value.size() != 3) fail_expected(path, expected, value);
    double c[3];
    for (size_t i = 0; i < 3; ++i) {
      if (!value[i].is_number() || !std::isfinite(value[i].get<double>())) {
        fail_expected(index(path, i), "a finite number", value[i]);
      }
      c[i] = value[i].get<double>();
    }
    return {c[0], c[1], c[2]};
  }

  Vec3 vec3(const json& object, const std::string& path, const char* key, const std::string& what,
            std::optional<Vec3> fallback) const {
    const json* value = find(object, key);
    if (value == nullptr) {
      if (fallback) return *fallback;
      fail(join(path, key),
           "expected " + what + " (array of 3 finite numbers), got nothing (key missing)");
    }
    return vec3(*value, join(path, key), what);
  }

  Vec3 direction(const json& object, const std::string& path, const char* key) const {
    const Vec3 v = vec3(object, path, key, "a direction", std::nullopt);
    if (!(length(v) > 1e-12)) {
      fail_expected(join(path, key), "a non-zero direction (it is normalised to unit length)",
                    object.at(key));
    }
    return normalize(v);
  }

  // A colour is [r, g, b] or one number for grey; components >= 0.
  Vec3 colour(const json& object, const std::string& path, const char* key, Vec3 fallback) const {
    const json* value = find(object, key);
    if (value == nullptr) return fallback;
    const std::string where = join(path, key);
    const std::string expected = "a colour: [r, g, b] or one number for grey, each >= 0";
    if (value->is_number()) {
      const double g = value->get<double>();
      if (!(g >= 0) || !std::isfinite(g)) fail_expected(where, expected, *value);
      return {g, g, g};
    }
    if (!value->is_array() || value->size() != 3) fail_expected(where, expected, *value);
    const Vec3 c = vec3(*value, where, "a colour");
    if (!(c.x >= 0 && c.y >= 0 && c.z >= 0)) fail_expected(where, expected, *value);
    return c;
  }

  const json& array(const json& object, const std::string& path, const char* key,
                    const std::string& of_what) const {
    const json& value = require(object, path, key, "a non-empty array of " + of_what);
    if (!value.is_array() || value.empty()) {
      fail_expected(join(path, key), "a non-empty array of " + of_what, value);
    }
    return value;
  }

 private:
  std::string file_;
};

std::string directory_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash == 0 ? 1 : slash);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open scene file (expected a readable JSON file)");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

json parse_text(const std::string& text, const std::string& path) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    const JsonTextError error = describe_json_error(text, e);
    throw SceneError(path + error.place + ": malformed JSON: " + error.reason);
  }
}

Camera read_camera(const Reader& r, const json& j, const std::string& path) {
  Camera camera;
  const std::string type = r.string(j, path, "type", std::string("perspective"));
  if (type == "perspective") {
    r.check_keys(j, path, {"type", "position", "target", "up", "fov_y", "near", "far"});
    camera.kind = Camera::Kind::kPerspective;
    camera.fov_y_deg = r.number(j, path, "fov_y", 1.0, 179.0, camera.fov_y_deg);
  } else if (type == "orthographic") {
    r.check_keys(j, path, {"type", "position", "target", "up", "height", "near", "far"});
    camera.kind = Camera::Kind::kOrthographic;
    camera.ortho_height = r.positive(j, path, "height", camera.ortho_height);
  } else {
    r.fail_expected(join(path, "type"), "\"perspective\" or \"orthographic\"", j.at("type"));
  }
  camera.position = r.vec3(j, path, "position", "a position", camera.position);
  camera.target = r.vec3(j, path, "target", "a position", camera.target);
  camera.up = r.vec3(j, path, "up", "a direction", camera.up);
  camera.near_plane = r.positive(j, path, "near", camera.near_plane);
  camera.far_plane = r.positive(j, path, "far", camera.far_plane);
  if (!(camera.far_plane > camera.near_plane)) {
    r.fail(join(path, "far"), "expected far > near (" + format_number(camera.near_plane) +
                                  "), got " + format_number(camera.far_plane));
  }
  const Vec3 forward = camera.target - camera.position;
  if (!(length(forward) > 1e-12))
    r.fail(join(path, "target"), "expected a target distinct from position");
  if (!(length(camera.up) > 1e-12)) r.fail(join(path, "up"), "expected a non-zero up vector");
  if (!(length(cross(normalize(forward), normalize(camera.up))) > 1e-6)) {
    r.fail(join(path, "up"), "expected an up vector not parallel to the view direction");
  }
  camera.up = normalize(camera.up);
  return camera;
}

SpecularModel read_specular_model(const Reader& r, const json& j, const std::string& path,
                                  SpecularModel fallback) {
  const json* value = r.find(j, "specular_model");
  if (value == nullptr) return fallback;
  const std::string where = join(path, "specular_model");
  const std::string accepted =
      "\"phong\" or \"blinn\" (the specular cosine: Phong's R.V or Blinn's N.H)";
  if (!value->is_string()) r.fail_expected(where, accepted, *value);
  const std::string name = value->get<std::string>();
  if (name == "phong") return SpecularModel::kPhong;
  if (name == "blinn") return SpecularModel::kBlinn;
  r.fail_expected(where, accepted, *value);
}

Material read_material(const Reader& r, const json& j, const std::string& path,
                       SpecularModel scene_model) {
  r.check_keys(j, path,
               {"name", "ambient", "diffuse", "specular", "exponent", "unit", "specular_model"});
  Material m;
  m.name = r.string(j, path, "name", std::nullopt);
  if (m.name.empty()) r.fail(join(path, "name"), "expected a non-empty material name");
  m.ambient = r.colour(j, path, "ambient", m.ambient);
  m.diffuse = r.colour(j, path, "diffuse", m.diffuse);
  m.specular = r.colour(j, path, "specular", m.specular);
  m.exponent = r.number(j, path, "exponent", 1.0, 1000.0, m.exponent);
  const std::string unit = r.string(j, path, "unit", std::string("ideal"));
  try {
    m.unit = parse_specular_unit(unit, join(path, "unit"));
  } catch (const std::invalid_argument& e) {
    // The message already names the field (passed as `what`); add only the file.
    r.fail_raw(e.what());
  }
  m.specular_model = read_specular_model(r, j, path, scene_model);
  return m;
}

Transform read_transform(const Reader& r, const json& j, const std::string& path) {
  r.check_keys(j, path, {"translate", "rotate_deg", "scale"});
  Transform t;
  t.translate = r.vec3(j, path, "translate", "a translation", t.translate);
  t.rotate_deg = r.vec3(j, path, "rotate_deg", "Euler XYZ angles in degrees", t.rotate_deg);
  if (const json* s = r.find(j, "scale")) {
    const std::string where = join(path, "scale");
    const std::string expected = "a non-zero scale: one number or [x, y, z]";
    if (s->is_number()) {
      const double v = s->get<double>();
      if (v == 0 || !std::isfinite(v)) r.fail_expected(where, expected, *s);
      t.scale = {v, v, v};
    } else {
      if (!s->is_array()) r.fail_expected(where, expected, *s);
      t.scale = r.vec3(*s, where, "a scale");
      if (t.scale.x == 0 || t.scale.y == 0 || t.scale.z == 0) r.fail_expected(where, expected, *s);
    }
  }
  return t;
}

Object read_object(const Reader& r, const json& j, const std::string& path,
                   const std::vector<Material>& materials, const std::string& scene_path) {
  if (!j.is_object()) r.fail_expected(path, "an object", j);
  const std::string type = r.string(j, path, "type", std::nullopt);
  Object object;
  object.name = r.string(j, path, "name", path);
  const std::string material = r.string(j, path, "material", std::nullopt);
  const auto found = std::find_if(materials.begin(), materials.end(),
                                  [&](const Material& m) { return m.name == material; });
  if (found == materials.end()) {
    std::string names;
    for (const Material& m : materials)
      names += std::string(names.empty() ? "" : ", ") + "\"" + m.name + "\"";
    r.fail(join(path, "material"),
           "expected the name of a material (one of " + names + "), got \"" + material + "\"");
  }
  object.material = static_cast<int>(found - materials.begin());

  auto tessellation = [&](int minimum, int fallback) {
    return r.integer(j, path, "tessellation", minimum, kMaxTessellation, fallback);
  };
  Mesh mesh;
  if (type == "sphere") {
    r.check_keys(j, path, {"name", "type", "material", "tessellation", "radius", "transform"});
    mesh = make_sphere(r.positive(j, path, "radius", 1.0), tessellation(kMinTessellation, 32));
  } else if (type == "torus") {
    r.check_keys(
        j, path,
        {"name", "type", "material", "tessellation", "major_radius", "minor_radius", "transform"});
    const double major = r.positive(j, path, "major_radius", 1.0);
    const double minor = r.positive(j, path, "minor_radius", 0.25);
    mesh = make_torus(major, minor, tessellation(kMinTessellation, 32));
  } else if (type == "cylinder") {
    r.check_keys(j, path,
                 {"name", "type", "material", "tessellation", "radius", "height", "transform"});
    const double radius = r.positive(j, path, "radius", 1.0);
    const double height = r.positive(j, path, "height", 2.0);
    mesh = make_cylinder(radius, height, tessellation(kMinTessellation, 32));
  } else if (type == "plane") {
    r.check_keys(j, path, {"name", "type", "material", "tessellation", "size", "transform"});
    mesh = make_plane(r.positive(j, path, "size", 2.0), tessellation(1, 1));
  } else if (type == "mesh") {
    r.check_keys(j, path, {"name", "type", "material", "file", "transform"});
    std::string file = r.string(j, path, "file", std::nullopt);
    if (file.empty()) r.fail(join(path, "file"), "expected a mesh file path, got an empty string");
    file = mesh_file_path(scene_path, file);
    try {
      mesh = load_mesh_file(file);
    } catch (const SceneError& e) {
      r.fail(join(path, "file"), e.what());
    }
  } else {
    r.fail_expected(join(path, "type"),
                    "\"sphere\", \"torus\", \"cylinder\", \"plane\" or \"mesh\"", j.at("type"));
  }
  Transform transform;
  if (const json* t = r.find(j, "transform"))
    transform = read_transform(r, *t, join(path, "transform"));
  object.mesh = transform_mesh(mesh, transform);
  return object;
}

bool grey(const Vec3& c) { return c.x == c.y && c.y == c.z; }

}  // namespace

bool Scene::is_grey() const {
  if (!grey(ambient_light)) return false;
  for (const DirectionalLight& light : lights)
    if (!grey(light.colour)) return false;
  for (const Material& m : materials)
    if (!grey(m.ambient) || !grey(m.diffuse) || !grey(m.specular)) return false;
  return true;
}

std::string mesh_file_path(const std::string& scene_path, const std::string& file) {
  return file.empty() || file.front() == '/' ? file : directory_of(scene_path) + "/" + file;
}

Scene load_scene(const std::string& path) { return parse_scene(read_file(path), path); }

Scene parse_scene(const std::string& text, const std::string& path) {
  const json root = parse_text(text, path);
  const Reader r(path);
  r.check_keys(root, "",
               {"image", "camera", "lights", "ambient_light", "eye", "error_budget_lsb",
                "specular_model", "materials", "objects"});
  Scene scene;
  scene.path = path;

  const json& image = r.require(root, "", "image", "an object {\"width\", \"height\"}");
  r.check_keys(image, "image", {"width", "height"});
  scene.width = r.integer(image, "image", "width", 1, 4096, std::nullopt);
  scene.height = r.integer(image, "image", "height", 1, 4096, std::nullopt);

  scene.camera = read_camera(r, r.require(root, "", "camera", "a camera object"), "camera");

  const json& lights = r.array(root, "", "lights", "lights {\"direction\", \"colour\"}");
  for (size_t i = 0; i < lights.size(); ++i) {
    const std::string where = index("lights", i);
    r.check_keys(lights[i], where, {"direction", "colour"});
    DirectionalLight light;
    light.direction = r.direction(lights[i], where, "direction");
    light.colour = r.colour(lights[i], where, "colour", light.colour);
    scene.lights.push_back(light);
  }

  scene.ambient_light = r.colour(root, "", "ambient_light", scene.ambient_light);
  const std::string eye = r.string(root, "", "eye", std::string("infinite"));
  if (eye != "infinite" && eye != "finite") {
    r.fail_expected("eye", "\"infinite\" or \"finite\"", root.at("eye"));
  }
  scene.eye_at_infinity = eye == "infinite";
  scene.error_budget_lsb = r.positive(root, "", "error_budget_lsb", 1.0);

  const SpecularModel scene_model = read_specular_model(r, root, "", SpecularModel::kBlinn);
  const json& materials = r.array(root, "", "materials", "materials");
  for (size_t i = 0; i < materials.size(); ++i) {
    Material m = read_material(r, materials[i], index("materials", i), scene_model);
    for (const Material& earlier : scene.materials) {
      if (earlier.name == m.name) {
        r.fail(index("materials", i) + ".name",
               "expected a unique name, \"" + m.name + "\" is used twice");
      }
    }
    scene.materials.push_back(m);
  }

  const json& objects = r.array(root, "", "objects", "objects");
  for (size_t i = 0; i < objects.size(); ++i) {
    scene.objects.push_back(read_object(r, objects[i], index("objects", i), scene.materials, path));
  }
  return scene;
}

}  // namespace shadesim
