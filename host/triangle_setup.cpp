#include "host/triangle_setup.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "host/shading_field.h"

namespace shadesim {
namespace {

double clamp01(double v) { return std::min(1.0, std::max(0.0, v)); }

// Light directions as the shading functions take them (unit), and the infinite-eye half vectors.
struct Lighting {
  std::vector<Vec3> L, colour, H;
  Vec3 V;  // toward the eye at infinity (Phong's R.V with the eye at infinity)
  bool finite_eye = false;
};

Lighting lighting_of(const Scene& scene) {
  Lighting li;
  li.finite_eye = !scene.eye_at_infinity;
  const Vec3 V = eye_direction_at_infinity(scene.camera);
  li.V = V;
  for (const DirectionalLight& light : scene.lights) {
    const Vec3 L = normalize(light.direction);
    li.L.push_back(L);
    li.colour.push_back(light.colour);
    li.H.push_back(half_vector(L, V));
  }
  return li;
}

const Material& material_of(const ScreenTriangle& tri, const Scene& scene,
                            const std::string& which) {
  if (tri.material < 0 || static_cast<std::size_t>(tri.material) >= scene.materials.size()) {
    throw std::invalid_argument("triangle setup: " + which + " has material index " +
                                std::to_string(tri.material) + ", expected 0.." +
                                std::to_string(scene.materials.size()) + " - 1 (scene.materials)");
  }
  return scene.materials[static_cast<std::size_t>(tri.material)];
}

bool all_finite(const std::vector<Quadratic>& series) {
  for (const Quadratic& q : series) {
    for (double t : q.t) {
      if (!std::isfinite(t)) return false;
    }
  }
  return true;
}

TriangleSeries setup_with(const ScreenTriangle& tri, const Lighting& li, SpecularModel model) {
  TriangleSeries s;
  const double xc = (tri.v[0].x + tri.v[1].x + tri.v[2].x) / 3.0;
  const double yc = (tri.v[0].y + tri.v[1].y + tri.v[2].y) / 3.0;
  const auto N = normal_field(tri);
  const auto E = li.finite_eye ? eye_field(tri) : std::optional<AffineField>();
  const std::size_t lights = li.L.size();
  auto degenerate = [&] {
    s.degenerate = true;
    Quadratic zero;
    zero.xc = xc;
    zero.yc = yc;
    s.diffuse.assign(lights, zero);
    s.specular.assign(lights, zero);
    return s;
  };
  if (!N || (li.finite_eye && !E)) return degenerate();
  auto expand_about = [&](double x0, double y0) {
    s.diffuse.clear();
    s.specular.clear();
    s.diffuse.reserve(lights);
    s.specular.reserve(lights);
    for (std::size_t l = 0; l < lights; ++l) {
      s.diffuse.push_back(taylor_diffuse(*N, li.L[l], x0, y0));
      if (model == SpecularModel::kPhong) {
        s.specular.push_back(li.finite_eye ? taylor_phong_finite(*N, *E, li.L[l], x0, y0)
                                           : taylor_phong_infinite(*N, li.L[l], li.V, x0, y0));
      } else {
        s.specular.push_back(li.finite_eye ? taylor_specular_finite(*N, *E, li.L[l], x0, y0)
                                           : taylor_specular_infinite(*N, li.H[l], x0, y0));
      }
    }
    return all_finite(s.diffuse) && all_finite(s.specular);
  };
  if (expand_about(xc, yc)) return s;
  // The interpolated normal (or the finite-eye half vector) is zero at the centroid: a mesh whose
  // vertex normals oppose each other across the triangle, where the field's zero set is a point
  // or a line and the shading steps across it. The series is undefined there, not the shading
  // elsewhere: expand about a point halfway from the centroid to a vertex instead. A line through
  // the centroid meets at most one of those three directions, a point none, so one is finite
  // unless the field is zero everywhere (then the reference shades no light either). The measured
  // error decides, as everywhere, whether the triangle is split further or reported over budget.
  for (const ScreenVertex& v : tri.v) {
    if (expand_about(0.5 * (xc + v.x), 0.5 * (yc + v.y))) return s;
  }
  return degenerate();
}

// Calls visit(px, py) for each pixel whose centre lies in the closed triangle and in the image.
// Row by row: on a row each edge bounds x on one side, so the work is rows + pixels, not the
// bounding box (long slivers stay cheap).
template <class Visit>
bool for_each_covered_centre(const ScreenTriangle& tri, int width, int height, Visit visit) {
  const auto& v = tri.v;
  const double area2 =
      (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x);
  if (!(area2 != 0.0) || !std::isfinite(area2)) return true;
  const double orient = area2 > 0 ? 1.0 : -1.0;
  const double ymin = std::min({v[0].y, v[1].y, v[2].y});
  const double ymax = std::max({v[0].y, v[1].y, v[2].y});
  const int py0 = std::max(0, static_cast<int>(std::ceil(ymin - 0.5)));
  const int py1 = std::min(height - 1, static_cast<int>(std::floor(ymax - 0.5)));
  constexpr double kSlack = 1e-9;  // keep centres exactly on an edge despite rounding
  for (int py = py0; py <= py1; ++py) {
    const double y = py + 0.5;
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool empty = false;
    for (int e = 0; e < 3; ++e) {
      const ScreenVertex& a = v[e];
      const ScreenVertex& b = v[(e + 1) % 3];
      // Inside: orient * ((bx - ax)(y - ay) - (by - ay)(x - ax)) >= 0, i.e. alpha x + beta >= 0.
      const double alpha = -orient * (b.y - a.y);
      const double beta = orient * ((b.x - a.x) * (y - a.y) + (b.y - a.y) * a.x);
      if (alpha > 0) {
        lo = std::max(lo, -beta / alpha);
      } else if (alpha < 0) {
        hi = std::min(hi, -beta / alpha);
      } else if (beta < -kSlack) {
        empty = true;
      }
    }
    if (empty || !(lo <= hi + 2 * kSlack)) continue;
    const double px_lo = std::max(0.0, std::ceil(lo - kSlack - 0.5));
    const double px_hi = std::min(width - 1.0, std::floor(hi + kSlack - 0.5));
    for (int px = static_cast<int>(px_lo); px <= static_cast<int>(px_hi); ++px) {
      if (!visit(px, py)) return false;
    }
  }
  return true;
}

double measure_with(const ScreenTriangle& tri, const TriangleSeries& series, const Scene& scene,
                    const Material& mat, const Lighting& li, const SetupOptions& opt,
                    double stop_above) {
  if (series.degenerate) return 0.0;
  const auto N = normal_field(tri);
  const auto E = li.finite_eye ? eye_field(tri) : std::optional<AffineField>();
  if (!N || (li.finite_eye && !E)) return 0.0;
  const std::size_t lights = li.L.size();
  const double lsb_scale = std::ldexp(1.0, opt.output_bits);
  const double ambient[3] = {mat.ambient.x * scene.ambient_light.x,
                             mat.ambient.y * scene.ambient_light.y,
                             mat.ambient.z * scene.ambient_light.z};
  const bool has_specular = mat.specular.x != 0 || mat.specular.y != 0 || mat.specular.z != 0;
  const double n_exp = mat.exponent;
  double worst = 0.0;
  const bool complete =
      for_each_covered_centre(tri, scene.width, scene.height, [&](int px, int py) {
        const double x = px + 0.5, y = py + 0.5;
        const Vec3 n = N->at(x, y);
        const double n_len = length(n);
        const Vec3 e = li.finite_eye ? E->at(x, y) : Vec3{};
        double exact[3] = {ambient[0], ambient[1], ambient[2]};
        double approx[3] = {ambient[0], ambient[1], ambient[2]};
        for (std::size_t l = 0; l < lights; ++l) {
          const Vec3& L = li.L[l];
          const double td = n_len > 0 ? dot(n, L) / n_len : 0.0;
          const double qd = series.diffuse[l].eval(x, y);
          const double d_exact = std::max(0.0, td);
          const double d_approx = opt.diffuse_clamped_per_light ? std::max(0.0, qd) : qd;
          double s_exact = 0.0, s_approx = 0.0;
          if (has_specular) {
            double ts;
            if (mat.specular_model == SpecularModel::kPhong) {
              ts = phong_cosine(n, L, li.finite_eye ? e : li.V);
            } else if (li.finite_eye) {
              const Vec3 h = e + L;
              const double len = n_len * length(h);
              ts = len > 0 ? dot(n, h) / len : 0.0;
            } else {
              ts = n_len > 0 ? dot(n, li.H[l]) / n_len : 0.0;
            }
            // The specular gate (N.L > 0) by each side's own diffuse value: where the quadratic's
            // sign differs from the exact one the whole specular term is error, and it is budgeted.
            s_exact = td > 0 ? std::pow(clamp01(ts), n_exp) : 0.0;
            s_approx = qd > 0 ? std::pow(clamp01(series.specular[l].eval(x, y)), n_exp) : 0.0;
          }
          const Vec3& c = li.colour[l];
          const double lc[3] = {c.x, c.y, c.z};
          const double kd[3] = {mat.diffuse.x, mat.diffuse.y, mat.diffuse.z};
          const double ks[3] = {mat.specular.x, mat.specular.y, mat.specular.z};
          for (int ch = 0; ch < 3; ++ch) {
            exact[ch] += lc[ch] * (kd[ch] * d_exact + ks[ch] * s_exact);
            approx[ch] += lc[ch] * (kd[ch] * d_approx + ks[ch] * s_approx);
          }
        }
        for (int ch = 0; ch < 3; ++ch) {
          const double err = std::fabs(clamp01(approx[ch]) - clamp01(exact[ch])) * lsb_scale;
          if (!std::isfinite(err) || !std::isfinite(approx[ch])) {
            worst = std::numeric_limits<double>::infinity();
            return false;
          }
          worst = std::max(worst, err);
        }
        return !(worst > stop_above);
      });
  (void)complete;
  return worst;
}

ScreenVertex midpoint(const ScreenVertex& a, const ScreenVertex& b) {
  ScreenVertex m;
  m.x = (a.x + b.x) * 0.5;
  m.y = (a.y + b.y) * 0.5;
  m.z = (a.z + b.z) * 0.5;
  m.normal = (a.normal + b.normal) * 0.5;
  m.to_eye = (a.to_eye + b.to_eye) * 0.5;
  return m;
}

double length2(const ScreenVertex& a, const ScreenVertex& b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  return dx * dx + dy * dy;
}

struct Subdivider {
  const Scene& scene;
  const Material* mat = nullptr;
  const Lighting& li;
  const SetupOptions& opt;
  double budget;
  int parent = -1;
  SetupResult& out;

  void run(const ScreenTriangle& tri, int depth) {
    TriangleSeries series = setup_with(tri, li, mat->specular_model);
    const bool may_split = depth < opt.max_depth;
    double err = measure_with(tri, series, scene, *mat, li, opt,
                              may_split ? budget : std::numeric_limits<double>::infinity());
    if (err > budget && may_split) {
      // Split the longest edge (v[k], v[k+1]); both children keep the parent's winding.
      const double l01 = length2(tri.v[0], tri.v[1]);
      const double l12 = length2(tri.v[1], tri.v[2]);
      const double l20 = length2(tri.v[2], tri.v[0]);
      const int k = (l01 >= l12 && l01 >= l20) ? 0 : (l12 >= l20 ? 1 : 2);
      const ScreenVertex& a = tri.v[k];
      const ScreenVertex& b = tri.v[(k + 1) % 3];
      const ScreenVertex& c = tri.v[(k + 2) % 3];
      const ScreenVertex m = midpoint(a, b);
      ScreenTriangle c0 = tri, c1 = tri;
      c0.v = {a, m, c};
      c1.v = {m, b, c};
      c0.parent = c1.parent = parent;
      ++out.stats.splits;
      run(c0, depth + 1);
      run(c1, depth + 1);
      return;
    }
    out.stats.max_depth_reached = std::max(out.stats.max_depth_reached, depth);
    if (err > budget) ++out.stats.over_budget;
    if (series.degenerate) ++out.stats.degenerate;
    out.stats.worst_error_lsb = std::max(out.stats.worst_error_lsb, err);
    out.triangles.push_back(tri);
    out.series.push_back(std::move(series));
    out.error_lsb.push_back(err);
  }
};

}  // namespace

TriangleSeries setup_triangle(const ScreenTriangle& tri, const Scene& scene) {
  return setup_with(tri, lighting_of(scene), material_of(tri, scene, "triangle").specular_model);
}

double measure_error_lsb(const ScreenTriangle& tri, const TriangleSeries& series,
                         const Scene& scene, const SetupOptions& opt, double stop_above) {
  const Lighting li = lighting_of(scene);
  if (!series.degenerate &&
      (series.diffuse.size() != li.L.size() || series.specular.size() != li.L.size())) {
    throw std::invalid_argument("measure_error_lsb: series has " +
                                std::to_string(series.diffuse.size()) + " diffuse and " +
                                std::to_string(series.specular.size()) +
                                " specular quadratics, expected one each per scene light (" +
                                std::to_string(li.L.size()) + ")");
  }
  return measure_with(tri, series, scene, material_of(tri, scene, "triangle"), li, opt, stop_above);
}

SetupResult subdivide_and_setup(const std::vector<ScreenTriangle>& in, const Scene& scene,
                                const SetupOptions& opt) {
  const double budget = opt.budget_lsb.value_or(scene.error_budget_lsb);
  if (!(budget > 0) || !std::isfinite(budget)) {
    throw std::invalid_argument(
        "triangle setup: error budget " + std::to_string(budget) +
        " LSB, expected a finite value > 0 (budget_lsb / error_budget_lsb)");
  }
  if (opt.max_depth < 0 || opt.max_depth > 30) {
    throw std::invalid_argument("triangle setup: max_depth " + std::to_string(opt.max_depth) +
                                ", expected 0..30");
  }
  if (opt.output_bits < 1 || opt.output_bits > 24) {
    throw std::invalid_argument("triangle setup: output_bits " + std::to_string(opt.output_bits) +
                                ", expected 1..24");
  }
  const Lighting li = lighting_of(scene);
  SetupResult out;
  out.stats.triangles_in = in.size();
  out.first_out.reserve(in.size() + 1);
  out.triangles.reserve(in.size());  // at least one out per input: less doubling growth
  out.series.reserve(in.size());
  out.error_lsb.reserve(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    out.first_out.push_back(out.triangles.size());
    const std::size_t splits_before = out.stats.splits;
    Subdivider sub{scene,  &material_of(in[i], scene, "triangle " + std::to_string(i)), li, opt,
                   budget, in[i].parent >= 0 ? in[i].parent : static_cast<int>(i),      out};
    sub.run(in[i], 0);
    if (out.stats.splits != splits_before) ++out.stats.inputs_split;
  }
  out.first_out.push_back(out.triangles.size());
  out.stats.triangles_out = out.triangles.size();
  return out;
}

}  // namespace shadesim
