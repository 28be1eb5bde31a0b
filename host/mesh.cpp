#include "host/mesh.h"

#include <cmath>
#include <utility>
#include <vector>

namespace shadesim {
namespace {

constexpr double kPi = 3.14159265358979323846;

uint32_t add_vertex(Mesh& mesh, const Vec3& position, const Vec3& normal) {
  mesh.positions.push_back(position);
  mesh.normals.push_back(normalize(normal));
  return static_cast<uint32_t>(mesh.positions.size() - 1);
}

// Quad a=(s,t) b=(s+1,t) c=(s+1,t+1) d=(s,t+1) of a grid whose cross(d/ds, d/dt) points outward.
void add_quad(Mesh& mesh, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  mesh.triangles.push_back({a, b, c});
  mesh.triangles.push_back({a, c, d});
}

void check_tessellation(int tessellation, int minimum, const char* shape) {
  if (tessellation < minimum || tessellation > kMaxTessellation) {
    throw std::invalid_argument(std::string(shape) + " tessellation must be in " +
                                std::to_string(minimum) + ".." + std::to_string(kMaxTessellation) +
                                ", got " + std::to_string(tessellation));
  }
}

struct Mat3 {
  double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  Vec3 operator*(const Vec3& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  Mat3 operator*(const Mat3& o) const {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        r.m[i][j] = m[i][0] * o.m[0][j] + m[i][1] * o.m[1][j] + m[i][2] * o.m[2][j];
    return r;
  }
};

Mat3 rotation_x(double rad) {
  Mat3 r;
  r.m[1][1] = std::cos(rad);
  r.m[1][2] = -std::sin(rad);
  r.m[2][1] = std::sin(rad);
  r.m[2][2] = std::cos(rad);
  return r;
}
Mat3 rotation_y(double rad) {
  Mat3 r;
  r.m[0][0] = std::cos(rad);
  r.m[0][2] = std::sin(rad);
  r.m[2][0] = -std::sin(rad);
  r.m[2][2] = std::cos(rad);
  return r;
}
Mat3 rotation_z(double rad) {
  Mat3 r;
  r.m[0][0] = std::cos(rad);
  r.m[0][1] = -std::sin(rad);
  r.m[1][0] = std::sin(rad);
  r.m[1][1] = std::cos(rad);
  return r;
}

}  // namespace

Mesh make_sphere(double radius, int tessellation) {
  check_tessellation(tessellation, kMinTessellation, "sphere");
  const int bands = tessellation;
  const int segments = 2 * tessellation;
  Mesh mesh;
  const uint32_t north = add_vertex(mesh, {0, radius, 0}, {0, 1, 0});
  std::vector<uint32_t> ring_start(bands + 1, 0);
  for (int i = 1; i < bands; ++i) {
    const double theta = kPi * i / bands;
    ring_start[i] = static_cast<uint32_t>(mesh.positions.size());
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * kPi * j / segments;
      const Vec3 n{std::sin(theta) * std::cos(phi), std::cos(theta),
                   std::sin(theta) * std::sin(phi)};
      add_vertex(mesh, n * radius, n);
    }
  }
  const uint32_t south = add_vertex(mesh, {0, -radius, 0}, {0, -1, 0});
  // s runs along phi, t along theta: cross(d/dphi, d/dtheta) points outward.
  auto at = [&](int i, int j) -> uint32_t {
    if (i == 0) return north;
    if (i == bands) return south;
    return ring_start[i] + static_cast<uint32_t>(j % segments);
  };
  for (int i = 0; i < bands; ++i) {
    for (int j = 0; j < segments; ++j) {
      const uint32_t a = at(i, j), b = at(i, j + 1), c = at(i + 1, j + 1), d = at(i + 1, j);
      if (i != 0) mesh.triangles.push_back({a, b, c});
      if (i != bands - 1) mesh.triangles.push_back({a, c, d});
    }
  }
  return mesh;
}

Mesh make_torus(double major_radius, double minor_radius, int tessellation) {
  check_tessellation(tessellation, kMinTessellation, "torus");
  const int around = 2 * tessellation;  // phi, around the y axis
  const int tube = tessellation;        // theta, around the tube
  Mesh mesh;
  for (int j = 0; j < around; ++j) {
    const double phi = 2 * kPi * j / around;
    const Vec3 radial{std::cos(phi), 0, std::sin(phi)};
    for (int i = 0; i < tube; ++i) {
      const double theta = 2 * kPi * i / tube;
      const Vec3 n = radial * std::cos(theta) + Vec3{0, std::sin(theta), 0};
      add_vertex(mesh, radial * major_radius + n * minor_radius, n);
    }
  }
  // s runs along theta, t along phi: cross(d/dtheta, d/dphi) points outward.
  auto at = [&](int i, int j) { return static_cast<uint32_t>((j % around) * tube + (i % tube)); };
  for (int j = 0; j < around; ++j)
    for (int i = 0; i < tube; ++i)
      add_quad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
  return mesh;
}

Mesh make_cylinder(double radius, double height, int tessellation) {
  check_tessellation(tessellation, kMinTessellation, "cylinder");
  const int around = tessellation;
  const double half = height / 2;
  Mesh mesh;
  std::vector<Vec3> rim(around);
  for (int j = 0; j < around; ++j) {
    const double phi = 2 * kPi * j / around;
    rim[j] = {std::cos(phi), 0, std::sin(phi)};
  }
  // Side: rows y = -half (index j) and y = +half (index around + j).
  for (int row = 0; row < 2; ++row)
    for (int j = 0; j < around; ++j)
      add_vertex(mesh, rim[j] * radius + Vec3{0, row ? half : -half, 0}, rim[j]);
  // s runs along y, t along phi: cross(d/dy, d/dphi) points outward.
  for (int j = 0; j < around; ++j) {
    const uint32_t j0 = static_cast<uint32_t>(j), j1 = static_cast<uint32_t>((j + 1) % around);
    const uint32_t top = static_cast<uint32_t>(around);
    add_quad(mesh, j0, top + j0, top + j1, j1);
  }
  // Caps: fans about their centres, rim vertices duplicated with the flat cap normal.
  for (int cap = 0; cap < 2; ++cap) {
    const double y = cap ? half : -half;
    const Vec3 normal{0, cap ? 1.0 : -1.0, 0};
    const uint32_t centre = add_vertex(mesh, {0, y, 0}, normal);
    const uint32_t first = static_cast<uint32_t>(mesh.positions.size());
    for (int j = 0; j < around; ++j) add_vertex(mesh, rim[j] * radius + Vec3{0, y, 0}, normal);
    for (int j = 0; j < around; ++j) {
      const uint32_t a = first + static_cast<uint32_t>(j);
      const uint32_t b = first + static_cast<uint32_t>((j + 1) % around);
      // Increasing phi runs clockwise seen from +y, so the top cap takes (centre, b, a).
      if (cap)
        mesh.triangles.push_back({centre, b, a});
      else
        mesh.triangles.push_back({centre, a, b});
    }
  }
  return mesh;
}

Mesh make_plane(double size, int tessellation) {
  check_tessellation(tessellation, 1, "plane");
  const int n = tessellation;
  Mesh mesh;
  // Index (i along x, k along z).
  for (int k = 0; k <= n; ++k)
    for (int i = 0; i <= n; ++i)
      add_vertex(mesh, {size * (double(i) / n - 0.5), 0, size * (double(k) / n - 0.5)}, {0, 1, 0});
  auto at = [&](int i, int k) { return static_cast<uint32_t>(k * (n + 1) + i); };
  // s runs along z, t along x: cross(d/dz, d/dx) = +y.
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i)
      add_quad(mesh, at(i, k), at(i, k + 1), at(i + 1, k + 1), at(i + 1, k));
  return mesh;
}

Mesh transform_mesh(const Mesh& mesh, const Transform& transform) {
  const double deg = kPi / 180.0;
  const Mat3 rotation = rotation_z(transform.rotate_deg.z * deg) *
                        rotation_y(transform.rotate_deg.y * deg) *
                        rotation_x(transform.rotate_deg.x * deg);
  const Vec3 s = transform.scale;
  if (s.x == 0 || s.y == 0 || s.z == 0)
    throw std::invalid_argument("transform scale must be non-zero");
  Mat3 scale, inverse_scale;
  scale.m[0][0] = s.x;
  scale.m[1][1] = s.y;
  scale.m[2][2] = s.z;
  inverse_scale.m[0][0] = 1 / s.x;
  inverse_scale.m[1][1] = 1 / s.y;
  inverse_scale.m[2][2] = 1 / s.z;
  const Mat3 linear = rotation * scale;
  // (R S)^-T = R^-T S^-T = R S^-1 for a rotation R and diagonal S.
  const Mat3 normal_matrix = rotation * inverse_scale;
  Mesh out;
  out.positions.reserve(mesh.positions.size());
  out.normals.reserve(mesh.normals.size());
  for (const Vec3& p : mesh.positions) out.positions.push_back(linear * p + transform.translate);
  for (const Vec3& n : mesh.normals) out.normals.push_back(normalize(normal_matrix * n));
  out.triangles = mesh.triangles;
  if (s.x * s.y * s.z < 0) {
    for (auto& t : out.triangles) std::swap(t[1], t[2]);
  }
  return out;
}

}  // namespace shadesim
