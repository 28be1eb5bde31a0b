#include "host/reference.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace shadesim {
namespace {

double clamp01(double v) { return std::min(1.0, std::max(0.0, v)); }

// Barycentric weights of (x, y). Written independently of AffineField (which solves for
// gradients) so the two interpolations check each other in tests.
std::array<double, 3> barycentric(const ScreenTriangle& t, double x, double y) {
  const auto& v = t.v;
  const double area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
  if (!(area != 0.0) || !std::isfinite(area)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  std::array<double, 3> w;
  for (int k = 0; k < 3; ++k) {
    const ScreenVertex& p = v[(k + 1) % 3];
    const ScreenVertex& q = v[(k + 2) % 3];
    w[k] = ((q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x)) / area;
  }
  return w;
}

void check_shading_inputs(const std::vector<ScreenTriangle>& triangles,
                          const std::vector<int32_t>& owner, int width, int height,
                          const Scene& scene, int channels, const ShadingVariant& variant) {
  if (channels != 1 && channels != 3) {
    throw std::invalid_argument("render_reference: channels " + std::to_string(channels) +
                                ", expected 1 or 3");
  }
  if (width < 0 || height < 0 ||
      owner.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
    throw std::invalid_argument("render_reference: owner buffer has " +
                                std::to_string(owner.size()) +
                                " entries, expected width * height = " + std::to_string(width) +
                                " * " + std::to_string(height));
  }
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const int m = triangles[i].material;
    if (m < 0 || static_cast<std::size_t>(m) >= scene.materials.size()) {
      throw std::invalid_argument("render_reference: triangle " + std::to_string(i) +
                                  " has material index " + std::to_string(m) + ", expected 0.." +
                                  std::to_string(scene.materials.size()) + " - 1");
    }
  }
  if (variant.quadratics && variant.quadratics->size() != triangles.size()) {
    throw std::invalid_argument("render_variant: " + std::to_string(variant.quadratics->size()) +
                                " quadratic sets for " + std::to_string(triangles.size()) +
                                " triangles");
  }
  if (variant.gate_quadratics && variant.gate_quadratics->size() != triangles.size()) {
    throw std::invalid_argument(
        "render_variant: " + std::to_string(variant.gate_quadratics->size()) +
        " gate quadratic sets for " + std::to_string(triangles.size()) + " triangles");
  }
  if (!variant.specular.empty() && variant.specular.size() != scene.materials.size()) {
    throw std::invalid_argument("render_variant: " + std::to_string(variant.specular.size()) +
                                " specular functions for " +
                                std::to_string(scene.materials.size()) + " materials");
  }
}

// The scene's fixed directions: V toward an eye at infinity, and per light L and the halfway
// vector H for that eye.
struct LightDirections {
  Vec3 V;
  std::vector<Vec3> L, H_inf;
};

LightDirections light_directions(const Scene& scene) {
  LightDirections d;
  d.V = normalize(scene.camera.position - scene.camera.target);
  for (const DirectionalLight& light : scene.lights) {
    d.L.push_back(normalize(light.direction));
    d.H_inf.push_back(normalize(d.L.back() + d.V));
  }
  return d;
}

// One pixel's colour, unclamped, at (x, y) in triangle t: the exact cosines from the
// interpolated normal and to-eye vectors, or the variant's quadratics `q` when given.
Vec3 shade_pixel(const ScreenTriangle& t, const TriangleSeries* q, const TriangleSeries* gate_q,
                 double x, double y, const Scene& scene, const LightDirections& d,
                 const ShadingVariant& variant) {
  const Material& mat = scene.materials[static_cast<std::size_t>(t.material)];
  const auto w = barycentric(t, x, y);
  const Vec3 n = t.v[0].normal * w[0] + t.v[1].normal * w[1] + t.v[2].normal * w[2];
  const Vec3 e = t.v[0].to_eye * w[0] + t.v[1].to_eye * w[1] + t.v[2].to_eye * w[2];
  const double n_len = length(n);
  Vec3 colour{mat.ambient.x * scene.ambient_light.x, mat.ambient.y * scene.ambient_light.y,
              mat.ambient.z * scene.ambient_light.z};
  const bool phong = mat.specular_model == SpecularModel::kPhong;
  // Phong's V: unit toward the eye; the interpolated to-eye vector is not unit.
  const double e_len = length(e);
  const Vec3 V_phong = scene.eye_at_infinity ? d.V : (e_len > 0 ? e / e_len : Vec3{});
  for (std::size_t l = 0; l < d.L.size(); ++l) {
    double t_d = 0.0, t_s = 0.0;
    if (q) {
      t_d = q->degenerate ? 0.0 : q->diffuse[l].eval(x, y);
      t_s = q->degenerate ? 0.0 : q->specular[l].eval(x, y);
    } else if (n_len > 0) {
      t_d = dot(n, d.L[l]) / n_len;
      if (phong) {
        // R = L reflected about the unit normal.
        const Vec3 n_unit = n / n_len;
        const Vec3 R = n_unit * (2.0 * dot(n_unit, d.L[l])) - d.L[l];
        t_s = dot(R, V_phong);
      } else {
        const Vec3 H = scene.eye_at_infinity ? d.H_inf[l] : normalize(e + d.L[l]);
        t_s = dot(n, H) / n_len;
      }
    }
    const double diffuse = std::max(0.0, t_d);
    // No specular where N.L <= 0: a highlight never shines through the terminator.
    double specular = 0.0;
    const bool gate = gate_q ? !gate_q->degenerate && gate_q->diffuse[l].eval(x, y) > 0 : t_d > 0;
    if (gate) {
      specular = variant.specular.empty()
                     ? std::pow(q ? clamp01(t_s) : std::max(0.0, t_s), mat.exponent)
                     : variant.specular[static_cast<std::size_t>(t.material)](t_s);
    }
    const Vec3& lc = scene.lights[l].colour;
    colour.x += lc.x * (mat.diffuse.x * diffuse + mat.specular.x * specular);
    colour.y += lc.y * (mat.diffuse.y * diffuse + mat.specular.y * specular);
    colour.z += lc.z * (mat.diffuse.z * diffuse + mat.specular.z * specular);
  }
  return colour;
}

}  // namespace

// One body for the reference and its variants, so they differ only in what the variant swaps.
static ReferenceImage render_shading(const std::vector<ScreenTriangle>& triangles,
                                     const std::vector<int32_t>& owner, int width, int height,
                                     const Scene& scene, int channels,
                                     const ShadingVariant& variant) {
  check_shading_inputs(triangles, owner, width, height, scene, channels, variant);
  const LightDirections directions = light_directions(scene);
  ReferenceImage img;
  img.width = width;
  img.height = height;
  img.channels = channels;
  img.values.assign(owner.size() * static_cast<std::size_t>(channels), 0.0);
  for (int py = 0; py < height; ++py) {
    for (int px = 0; px < width; ++px) {
      const std::size_t pixel = static_cast<std::size_t>(py) * width + px;
      const int32_t o = owner[pixel];
      if (o < 0) continue;
      if (static_cast<std::size_t>(o) >= triangles.size()) {
        throw std::invalid_argument("render_reference: owner of pixel (" + std::to_string(px) +
                                    ", " + std::to_string(py) + ") is triangle " +
                                    std::to_string(o) + ", expected -1.." +
                                    std::to_string(triangles.size()) + " - 1");
      }
      const TriangleSeries* q =
          variant.quadratics ? &(*variant.quadratics)[static_cast<std::size_t>(o)] : nullptr;
      const TriangleSeries* gate_q = variant.gate_quadratics
                                         ? &(*variant.gate_quadratics)[static_cast<std::size_t>(o)]
                                         : nullptr;
      const Vec3 colour = shade_pixel(triangles[static_cast<std::size_t>(o)], q, gate_q, px + 0.5,
                                      py + 0.5, scene, directions, variant);
      double* out = &img.values[pixel * static_cast<std::size_t>(channels)];
      out[0] = clamp01(colour.x);
      if (channels == 3) {
        out[1] = clamp01(colour.y);
        out[2] = clamp01(colour.z);
      }
    }
  }
  return img;
}

ReferenceImage render_reference(const std::vector<ScreenTriangle>& triangles,
                                const std::vector<int32_t>& owner, int width, int height,
                                const Scene& scene, int channels) {
  return render_shading(triangles, owner, width, height, scene, channels, ShadingVariant{});
}

ReferenceImage render_variant(const std::vector<ScreenTriangle>& triangles, const Visibility& vis,
                              const Scene& scene, int channels, const ShadingVariant& variant) {
  return render_shading(triangles, vis.owner, vis.width, vis.height, scene, channels, variant);
}

}  // namespace shadesim
