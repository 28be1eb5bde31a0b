// Triangle setup: measured Taylor error and subdivision, checked against a brute-force
// evaluation written here (barycentric interpolation of the vertex normals, its own inside test).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "host/shading_field.h"
#include "host/triangle_setup.h"

namespace shadesim {
namespace {

constexpr double kPi = 3.14159265358979323846;

ScreenVertex vert(double x, double y, Vec3 n) {
  ScreenVertex v;
  v.x = x;
  v.y = y;
  v.z = 0.5;
  v.normal = n;
  v.to_eye = {0, 0, 1};
  return v;
}

ScreenTriangle tri(ScreenVertex a, ScreenVertex b, ScreenVertex c) {
  ScreenTriangle t;
  t.v = {a, b, c};
  return t;
}

// Unit normals tilted by `tilt` from +z at azimuths 90, 210, 330 degrees.
std::array<Vec3, 3> cone_normals(double tilt) {
  std::array<Vec3, 3> n;
  for (int k = 0; k < 3; ++k) {
    const double phi = (90.0 + 120.0 * k) * kPi / 180.0;
    n[k] = {std::sin(tilt) * std::cos(phi), std::sin(tilt) * std::sin(phi), std::cos(tilt)};
  }
  return n;
}

// Tilt whose three normals are pairwise `spread` apart: cos(spread) = c^2 - (1 - c^2) / 2.
double tilt_for_spread(double spread) {
  const double c2 = (2.0 * std::cos(spread) + 1.0) / 3.0;
  return std::acos(std::sqrt(c2));
}

double angle_between(Vec3 a, Vec3 b) { return std::acos(dot(normalize(a), normalize(b))); }

Scene diffuse_scene(Vec3 light_dir) {
  Scene s;
  s.width = s.height = 256;
  s.lights.push_back(DirectionalLight{normalize(light_dir), {1, 1, 1}});
  Material m;
  m.ambient = {0, 0, 0};
  m.diffuse = {1, 1, 1};
  m.specular = {0, 0, 0};
  s.materials.push_back(m);
  s.error_budget_lsb = 1.0;
  return s;
}

// Independent brute force: every pixel centre of the image, closed inside test by barycentric
// coordinates, exact shading from barycentric normals, one light, eye at infinity along
// camera.position - camera.target. Returns max error in 8-bit LSBs and the pixel count.
struct Brute {
  double max_lsb = 0;
  int pixels = 0;
};
Brute brute_force_error(const ScreenTriangle& t, const TriangleSeries& s, const Scene& scene) {
  const auto& v = t.v;
  const double area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
  const Material& m = scene.materials[0];
  const Vec3 L = scene.lights[0].direction;
  const Vec3 H = normalize(L + normalize(scene.camera.position - scene.camera.target));
  Brute b;
  for (int py = 0; py < scene.height; ++py) {
    for (int px = 0; px < scene.width; ++px) {
      const double x = px + 0.5, y = py + 0.5;
      double w[3];
      for (int k = 0; k < 3; ++k) {
        const ScreenVertex& p = v[(k + 1) % 3];
        const ScreenVertex& q = v[(k + 2) % 3];
        w[k] = ((q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x)) / area;
      }
      if (w[0] < -1e-12 || w[1] < -1e-12 || w[2] < -1e-12) continue;
      ++b.pixels;
      const Vec3 n = v[0].normal * w[0] + v[1].normal * w[1] + v[2].normal * w[2];
      const double td = dot(n, L) / length(n);
      const double ts = dot(n, H) / length(n);
      auto colour = [&](double d, double sp) {
        const double c = m.ambient.x * scene.ambient_light.x + m.diffuse.x * std::max(0.0, d) +
                         m.specular.x * std::pow(std::min(1.0, std::max(0.0, sp)), m.exponent);
        return std::min(1.0, std::max(0.0, c));
      };
      const double err =
          std::fabs(colour(s.diffuse[0].eval(x, y), s.specular[0].eval(x, y)) - colour(td, ts)) *
          256.0;
      b.max_lsb = std::max(b.max_lsb, err);
    }
  }
  return b;
}

ScreenTriangle big_triangle(const std::array<Vec3, 3>& n) {
  return tri(vert(30, 40, n[0]), vert(220, 60, n[1]), vert(110, 230, n[2]));
}

TEST(Setup, SixtyDegreeTriangleExceedsBudgetUnsplitAndFitsAfterSubdivision) {
  const auto n = cone_normals(tilt_for_spread(60.0 * kPi / 180.0));
  ASSERT_NEAR(angle_between(n[0], n[1]), 60.0 * kPi / 180.0, 1e-12);
  ASSERT_NEAR(angle_between(n[1], n[2]), 60.0 * kPi / 180.0, 1e-12);
  const Scene scene = diffuse_scene({0.3, -0.2, 1.0});
  const ScreenTriangle t = big_triangle(n);

  const TriangleSeries whole = setup_triangle(t, scene);
  const double unsplit = measure_error_lsb(t, whole, scene, SetupOptions());
  const Brute brute_whole = brute_force_error(t, whole, scene);
  std::printf("60 deg triangle, %d pixels: unsplit max error %.2f LSB (brute force %.2f)\n",
              brute_whole.pixels, unsplit, brute_whole.max_lsb);
  EXPECT_GT(brute_whole.max_lsb, 10.0);  // README "Checked numerical facts": tens of LSB
  EXPECT_NEAR(unsplit, brute_whole.max_lsb, 1e-9);

  const SetupResult r = subdivide_and_setup({t}, scene, SetupOptions());
  std::printf("  subdivided into %zu triangles (%zu splits, depth %d), worst %.3f LSB\n",
              r.stats.triangles_out, r.stats.splits, r.stats.max_depth_reached,
              r.stats.worst_error_lsb);
  EXPECT_GT(r.stats.splits, 0u);
  EXPECT_EQ(r.stats.triangles_out, 1 + r.stats.splits);
  EXPECT_EQ(r.stats.inputs_split, 1u);
  EXPECT_EQ(r.stats.over_budget, 0u);
  ASSERT_EQ(r.first_out.size(), 2u);
  EXPECT_EQ(r.first_out[1], r.triangles.size());
  int pixels = 0;
  double area_sum = 0;
  for (std::size_t i = 0; i < r.triangles.size(); ++i) {
    const ScreenTriangle& c = r.triangles[i];
    EXPECT_EQ(c.parent, 0);
    const Brute b = brute_force_error(c, r.series[i], scene);
    pixels += b.pixels;
    EXPECT_LE(b.max_lsb, 1.0) << "child " << i;
    EXPECT_NEAR(r.error_lsb[i], b.max_lsb, 1e-9) << "child " << i;
    const auto& v = c.v;
    area_sum += ((v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y));
  }
  const auto& v = t.v;
  EXPECT_DOUBLE_EQ(area_sum,
                   (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y));
  // Closed triangles: pixels on shared edges count in both children.
  EXPECT_GE(pixels, brute_whole.pixels);
}

TEST(Setup, SeventeenDegreeTriangleIsNearOneLsb) {
  // Worst over light directions on a grid of the upper hemisphere: the 17 degree figure is a
  // worst case, so measure it as one.
  const auto n = cone_normals(tilt_for_spread(17.0 * kPi / 180.0));
  const ScreenTriangle t = tri(vert(40, 40, n[0]), vert(200, 50, n[1]), vert(100, 200, n[2]));
  double worst = 0;
  Vec3 worst_light;
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j < 16; ++j) {
      const double theta = i * (kPi / 2) / 8, phi = j * 2 * kPi / 16;
      const Vec3 L{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                   std::cos(theta)};
      const Scene scene = diffuse_scene(L);
      const double e = brute_force_error(t, setup_triangle(t, scene), scene).max_lsb;
      if (e > worst) {
        worst = e;
        worst_light = L;
      }
    }
  }
  std::printf(
      "17 deg triangle (~160 px edges): worst unsplit error over 144 lights %.3f LSB, "
      "light (%.3f, %.3f, %.3f)\n",
      worst, worst_light.x, worst_light.y, worst_light.z);
  EXPECT_GT(worst, 0.3);
  EXPECT_LT(worst, 3.0);
}

TEST(Setup, SpecularHighExponentIsMeasuredAndSubdivided) {
  const auto n = cone_normals(tilt_for_spread(30.0 * kPi / 180.0));
  Scene scene = diffuse_scene({0.2, 0.1, 1.0});
  scene.materials[0].diffuse = {0.5, 0.5, 0.5};
  scene.materials[0].specular = {0.5, 0.5, 0.5};
  scene.materials[0].exponent = 100;
  scene.materials[0].ambient = {0.05, 0.05, 0.05};
  const ScreenTriangle t = big_triangle(n);
  const TriangleSeries whole = setup_triangle(t, scene);
  const Brute bw = brute_force_error(t, whole, scene);
  EXPECT_NEAR(measure_error_lsb(t, whole, scene, SetupOptions()), bw.max_lsb, 1e-9);
  Scene diffuse_only = scene;
  diffuse_only.materials[0].specular = {0, 0, 0};
  const double diffuse_err =
      brute_force_error(t, setup_triangle(t, diffuse_only), diffuse_only).max_lsb;
  std::printf("30 deg triangle, n = 100: unsplit %.2f LSB with specular, %.2f diffuse only\n",
              bw.max_lsb, diffuse_err);
  EXPECT_GT(bw.max_lsb, diffuse_err);  // pow amplifies the Taylor error of t_s
  const SetupResult r = subdivide_and_setup({t}, scene, SetupOptions());
  EXPECT_EQ(r.stats.over_budget, 0u);
  for (std::size_t i = 0; i < r.triangles.size(); ++i) {
    EXPECT_LE(brute_force_error(r.triangles[i], r.series[i], scene).max_lsb, 1.0);
  }
}

TEST(Setup, ChildrenCarryTheParentsField) {
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> u(0, 1);
  const auto n = cone_normals(tilt_for_spread(60.0 * kPi / 180.0));
  ScreenTriangle t = big_triangle(n);
  t.v[0].to_eye = normalize(Vec3{0.1, 0.2, 1});
  t.v[1].to_eye = normalize(Vec3{-0.2, 0.1, 1});
  t.v[2].to_eye = normalize(Vec3{0.05, -0.3, 1});
  t.parent = 17;
  const AffineField N = *normal_field(t);
  const AffineField E = *eye_field(t);
  const SetupResult r = subdivide_and_setup({t}, diffuse_scene({0.3, -0.2, 1.0}), SetupOptions());
  ASSERT_GT(r.triangles.size(), 4u);
  for (const ScreenTriangle& c : r.triangles) {
    EXPECT_EQ(c.parent, 17);  // an input's own parent is kept
    const auto cn = normal_field(c);
    const auto ce = eye_field(c);
    ASSERT_TRUE(cn && ce);
    for (int k = 0; k < 10; ++k) {
      const double x = 256 * u(gen), y = 256 * u(gen);
      const Vec3 dn = cn->at(x, y) - N.at(x, y), de = ce->at(x, y) - E.at(x, y);
      EXPECT_LT(length(dn), 1e-11);
      EXPECT_LT(length(de), 1e-11);
    }
  }
}

TEST(Setup, TriangleCoveringNoPixelCentreHasZeroError) {
  const auto n = cone_normals(1.2);
  const ScreenTriangle t =
      tri(vert(10.6, 10.6, n[0]), vert(10.9, 10.6, n[1]), vert(10.6, 10.9, n[2]));
  const Scene scene = diffuse_scene({0.3, -0.2, 1.0});
  const SetupResult r = subdivide_and_setup({t}, scene, SetupOptions());
  EXPECT_EQ(r.stats.splits, 0u);
  EXPECT_EQ(r.error_lsb.at(0), 0.0);
}

TEST(Setup, TriangleOffScreenHasZeroError) {
  const auto n = cone_normals(tilt_for_spread(60.0 * kPi / 180.0));
  const ScreenTriangle t = tri(vert(300, 40, n[0]), vert(500, 60, n[1]), vert(400, 230, n[2]));
  const Scene scene = diffuse_scene({0.3, -0.2, 1.0});
  EXPECT_EQ(measure_error_lsb(t, setup_triangle(t, scene), scene, SetupOptions()), 0.0);
}

TEST(Setup, MaxDepthStopsAndIsReported) {
  const auto n = cone_normals(tilt_for_spread(60.0 * kPi / 180.0));
  const ScreenTriangle t = big_triangle(n);
  const Scene scene = diffuse_scene({0.3, -0.2, 1.0});
  SetupOptions opt;
  opt.max_depth = 2;
  const SetupResult r = subdivide_and_setup({t, t}, scene, opt);
  EXPECT_EQ(r.stats.triangles_out, 8u);
  EXPECT_EQ(r.stats.inputs_split, 2u);
  EXPECT_EQ(r.stats.max_depth_reached, 2);
  EXPECT_GT(r.stats.over_budget, 0u);
  EXPECT_GT(r.stats.worst_error_lsb, 1.0);
  EXPECT_EQ(r.first_out, (std::vector<std::size_t>{0, 4, 8}));
  EXPECT_EQ(r.triangles[5].parent, 1);
}

// Vertex normals that oppose each other (+z, -z, +z: what assimp's broken smooth normals gave
// Cube.off, and what a file may carry): the interpolated normal is zero on the line x = 30 and
// the exact shading steps there. The first split puts the midpoint of the long edge, normal 0, on
// that line, and a child's centroid lands on it: a series expanded there is NaN unless setup
// guards it, and the encoder refuses such a frame. Every output series must be finite, and the
// error setup reports for each piece must be the one measured here independently (brute force,
// barycentric normals).
TEST(Setup, NormalFieldThroughZeroGivesFiniteSeriesAndHonestError) {
  const Vec3 up{0, 0, 1}, down{0, 0, -1};
  const ScreenTriangle t = tri(vert(10, 10, up), vert(50, 10, down), vert(10, 50, up));
  Scene scene = diffuse_scene({0.3, -0.2, 1.0});
  scene.width = scene.height = 64;
  // The centroid of the first split's first child is on the zero line: no direction there.
  const ScreenTriangle child =
      tri(vert(50, 10, down), vert(30, 30, Vec3{0, 0, 0}), vert(10, 10, up));
  const TriangleSeries at_zero = setup_triangle(child, scene);
  EXPECT_FALSE(at_zero.degenerate);
  for (const Quadratic& q : at_zero.diffuse) {
    for (double c : q.t) ASSERT_TRUE(std::isfinite(c));
    // Expanded about a point with a direction: its value there is N.L/|N| in closed form
    // (the field is +-z, so +-L.z).
    const double f = 1.0 - (q.xc - 10.0) / 20.0;  // the z component of N, affine, 0 at x = 30
    ASSERT_NE(f, 0.0);
    EXPECT_NEAR(q.t[0], (f > 0 ? 1.0 : -1.0) * scene.lights[0].direction.z, 1e-12);
  }

  // Unit vertex normals +-z cross zero halfway along an edge, where longest-edge splitting puts
  // its midpoints: the zero line becomes an edge of the pieces and each piece, on one side of
  // the step, is shaded exactly. The same with the line tilted (x + y = 40.25).
  const ScreenTriangle tilted =
      tri(vert(10.25, 10, up), vert(50.25, 10, down), vert(10.25, 50, down));
  for (const ScreenTriangle& input : {t, tilted}) {
    const SetupResult r = subdivide_and_setup({input}, scene, SetupOptions());
    ASSERT_EQ(r.series.size(), r.triangles.size());
    ASSERT_GT(r.triangles.size(), 1u);
    double worst = 0;
    for (std::size_t i = 0; i < r.triangles.size(); ++i) {
      for (const auto* series : {&r.series[i].diffuse, &r.series[i].specular}) {
        for (const Quadratic& q : *series) {
          for (double c : q.t) ASSERT_TRUE(std::isfinite(c)) << "piece " << i;
        }
      }
      const Brute b = brute_force_error(r.triangles[i], r.series[i], scene);
      EXPECT_NEAR(r.error_lsb[i], b.max_lsb, 1e-9) << "piece " << i;
      worst = std::max(worst, b.max_lsb);
    }
    EXPECT_NEAR(r.stats.worst_error_lsb, worst, 1e-9);
    EXPECT_EQ(r.stats.over_budget, 0u);
    EXPECT_LT(worst, 1e-9);
  }
}

TEST(Setup, BadInputIsRejectedWithAMessage) {
  const auto n = cone_normals(0.3);
  ScreenTriangle t = big_triangle(n);
  t.material = 3;
  const Scene scene = diffuse_scene({0, 0, 1});
  try {
    subdivide_and_setup({big_triangle(n), t}, scene, SetupOptions());
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("material index 3"), std::string::npos) << e.what();
  }
  SetupOptions opt;
  opt.budget_lsb = 0.0;
  EXPECT_THROW(subdivide_and_setup({big_triangle(n)}, scene, opt), std::invalid_argument);
}

// A sphere of radius 500 px seen orthographically, tessellated into cells x cells quads.
void run_sphere(int cells, double exponent) {
  Scene scene = diffuse_scene({0.4, -0.5, 0.8});
  scene.width = scene.height = 1024;
  scene.materials[0].diffuse = {0.6, 0.6, 0.6};
  scene.materials[0].specular = {0.4, 0.4, 0.4};
  scene.materials[0].exponent = exponent;
  const double cx = 512, cy = 512, R = 500, step = 1024.0 / cells;
  auto grid_vertex = [&](int i, int j) {
    // Snap to the 2^-8 subpixel grid the rasterizer uses.
    const double x = std::round(i * step * 256) / 256, y = std::round(j * step * 256) / 256;
    const double dx = (x - cx) / R, dy = (y - cy) / R;
    const double r = std::min(0.98, std::sqrt(dx * dx + dy * dy));
    const double s = r > 0 ? r / std::sqrt(dx * dx + dy * dy) : 0;
    return vert(x, y, Vec3{dx * s, dy * s, std::sqrt(1 - r * r)});
  };
  std::vector<ScreenTriangle> tris;
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      tris.push_back(tri(grid_vertex(i, j), grid_vertex(i + 1, j), grid_vertex(i + 1, j + 1)));
      tris.push_back(tri(grid_vertex(i, j), grid_vertex(i + 1, j + 1), grid_vertex(i, j + 1)));
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  const SetupResult r = subdivide_and_setup(tris, scene, SetupOptions());
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf(
      "sphere 1024^2, %dx%d cells, n = %g: %zu in, %zu out, %zu splits (%zu inputs split), "
      "%zu over budget, worst %.3f LSB, depth %d, %.2f s\n",
      cells, cells, exponent, r.stats.triangles_in, r.stats.triangles_out, r.stats.splits,
      r.stats.inputs_split, r.stats.over_budget, r.stats.worst_error_lsb, r.stats.max_depth_reached,
      secs);
  EXPECT_EQ(r.stats.triangles_in, tris.size());
  EXPECT_EQ(r.stats.triangles_out, tris.size() + r.stats.splits);
  EXPECT_EQ(r.stats.over_budget, 0u);
  EXPECT_LE(r.stats.worst_error_lsb, 1.0);
  double worst = 0;
  for (double e : r.error_lsb) worst = std::max(worst, e);
  EXPECT_EQ(worst, r.stats.worst_error_lsb);
}

TEST(Setup, TessellatedSphere10kTrianglesAt1024) { run_sphere(70, 40); }
TEST(Setup, CoarseSphereHighExponentSplits) { run_sphere(12, 400); }

}  // namespace
}  // namespace shadesim
