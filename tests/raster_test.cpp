// Rasterization and visibility: the top-left rule on hand-worked cases, agreement with a
// brute-force point-in-triangle reference, exact partition under midpoint subdivision, closed
// meshes shaded exactly once, z-buffer ownership, span structure, and projection against
// closed-form cameras.
#include "host/raster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <stdexcept>
#include <vector>

#include "host/mesh.h"
#include "host/scene.h"

namespace shadesim {
namespace {

ScreenTriangle tri(double x0, double y0, double x1, double y1, double x2, double y2,
                   double z = 0.5) {
  ScreenTriangle t;
  t.v[0].x = x0;
  t.v[0].y = y0;
  t.v[0].z = z;
  t.v[1].x = x1;
  t.v[1].y = y1;
  t.v[1].z = z;
  t.v[2].x = x2;
  t.v[2].y = y2;
  t.v[2].z = z;
  return t;
}

// Coverage count per pixel (no depth test).
std::vector<int> coverage(const std::vector<ScreenTriangle>& tris, int w, int h) {
  std::vector<int> count(static_cast<size_t>(w) * h, 0);
  for (const ScreenTriangle& t : tris)
    for (const CoveredRow& r : covered_rows(t, w, h))
      for (int x = r.x_begin; x < r.x_end; ++x) ++count[static_cast<size_t>(r.y) * w + x];
  return count;
}

std::vector<int> coverage(const ScreenTriangle& t, int w, int h) {
  return coverage(std::vector<ScreenTriangle>{t}, w, h);
}

// Independent reference: the top-left rule is "the pixel centre, nudged right by an infinitesimal
// e1 and down by a far smaller e2, lies strictly inside". For an edge function E (positive inside)
// with gradient g, E(c + (e1, e2)) = E(c) + g.x e1 + g.y e2, whose sign is that of E(c), else of
// g.x, else of g.y. Evaluated in double, exact for coordinates on a coarse grid.
bool reference_covers(const ScreenTriangle& t, double cx, double cy) {
  double x[3], y[3];
  for (int i = 0; i < 3; ++i) {
    x[i] = t.v[i].x;
    y[i] = t.v[i].y;
  }
  const double area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  if (area == 0) return false;
  const double s = area > 0 ? 1 : -1;  // orient so the interior is positive
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const double e = s * ((x[j] - x[i]) * (cy - y[i]) - (y[j] - y[i]) * (cx - x[i]));
    const double gx = -s * (y[j] - y[i]), gy = s * (x[j] - x[i]);
    const double sign = e != 0 ? e : (gx != 0 ? gx : gy);
    if (!(sign > 0)) return false;
  }
  return true;
}

TEST(TopLeft, RightTriangleWithEdgesThroughCentres) {
  // Legs along the row y = 0.5 (top edge) and column x = 0.5 (left edge): included. Hypotenuse
  // x + y = 5 has the interior above-left: a right edge, excluded. So pixels px + py <= 3.
  const std::vector<int> c = coverage(tri(0.5, 0.5, 4.5, 0.5, 0.5, 4.5), 8, 8);
  for (int py = 0; py < 8; ++py)
    for (int px = 0; px < 8; ++px)
      EXPECT_EQ(c[py * 8 + px], px + py <= 3 ? 1 : 0) << px << "," << py;
}

TEST(TopLeft, ComplementaryTriangleTakesTheDiagonal) {
  // Right leg x = 4.5 (right edge) and bottom leg y = 4.5 (bottom edge) excluded; the hypotenuse is
  // now a left edge and included: pixels with px, py <= 3 and px + py >= 4.
  const std::vector<int> c = coverage(tri(4.5, 0.5, 4.5, 4.5, 0.5, 4.5), 8, 8);
  for (int py = 0; py < 8; ++py)
    for (int px = 0; px < 8; ++px)
      EXPECT_EQ(c[py * 8 + px], (px <= 3 && py <= 3 && px + py >= 4) ? 1 : 0) << px << "," << py;
}

TEST(TopLeft, WindingDoesNotMatter) {
  const ScreenTriangle a = tri(0.5, 0.5, 4.5, 0.5, 0.5, 4.5);
  const ScreenTriangle b = tri(0.5, 0.5, 0.5, 4.5, 4.5, 0.5);
  EXPECT_EQ(coverage(a, 8, 8), coverage(b, 8, 8));
}

TEST(TopLeft, FlatBottomAndFlatTopShareTheirHorizontalEdge) {
  // Diamond split along the row y = 3.5: that row is the upper half's bottom edge (excluded) and
  // the lower half's top edge (included), so row 3 belongs to the lower half.
  const ScreenTriangle upper = tri(4.5, 0.5, 7.5, 3.5, 1.5, 3.5);
  const ScreenTriangle lower = tri(1.5, 3.5, 7.5, 3.5, 4.5, 6.5);
  for (const CoveredRow& r : covered_rows(upper, 10, 10)) EXPECT_LT(r.y, 3);
  bool lower_has_row3 = false;
  for (const CoveredRow& r : covered_rows(lower, 10, 10)) {
    if (r.y == 3) {
      lower_has_row3 = true;
      EXPECT_EQ(r.x_begin, 1);  // left end x = 1.5 is on the left edge: included
      EXPECT_EQ(r.x_end, 7);    // right end x = 7.5 is on the right edge: excluded
    }
  }
  EXPECT_TRUE(lower_has_row3);
}

TEST(TopLeft, FanAroundAPixelCentreCoversEachPixelOnce) {
  // Eight triangles share the vertex (10.5, 10.5); every spoke runs through pixel centres.
  const double cx = 10.5, cy = 10.5;
  const double ring[8][2] = {{16.5, 10.5}, {16.5, 16.5}, {10.5, 16.5}, {4.5, 16.5},
                             {4.5, 10.5},  {4.5, 4.5},   {10.5, 4.5},  {16.5, 4.5}};
  std::vector<ScreenTriangle> fan;
  for (int k = 0; k < 8; ++k) {
    const auto& a = ring[k];
    const auto& b = ring[(k + 1) % 8];
    fan.push_back(tri(cx, cy, a[0], a[1], b[0], b[1]));
  }
  const std::vector<int> c = coverage(fan, 24, 24);
  // The union is the square [4.5, 16.5]^2 under the top-left rule: pixels 4..15 in x and y.
  for (int py = 0; py < 24; ++py)
    for (int px = 0; px < 24; ++px) {
      const bool inside = px >= 4 && px <= 15 && py >= 4 && py <= 15;
      EXPECT_EQ(c[py * 24 + px], inside ? 1 : 0) << px << "," << py;
    }
}

TEST(Coverage, MatchesBruteForceReferenceOnRandomTriangles) {
  std::mt19937 rng(7);
  // Coordinates on a coarse grid (quarter pixels) so edges often hit centres and vertices exactly.
  std::uniform_int_distribution<int> coord(-8, 4 * 40 + 8);
  const int w = 40, h = 40;
  for (int n = 0; n < 400; ++n) {
    const ScreenTriangle t = tri(coord(rng) / 4.0, coord(rng) / 4.0, coord(rng) / 4.0,
                                 coord(rng) / 4.0, coord(rng) / 4.0, coord(rng) / 4.0);
    const std::vector<int> c = coverage(t, w, h);
    for (int py = 0; py < h; ++py)
      for (int px = 0; px < w; ++px)
        ASSERT_EQ(c[py * w + px], reference_covers(t, px + 0.5, py + 0.5) ? 1 : 0)
            << "triangle " << n << " pixel " << px << "," << py;
  }
}

TEST(Coverage, AreaOfBigTriangleMatchesAnalyticArea) {
  const ScreenTriangle t = tri(12.3125, 40.75, 980.5, 103.25, 300.0078125, 1010.5);
  const std::vector<int> c = coverage(t, 1024, 1024);
  double count = 0;
  for (int v : c) count += v;
  const double area = 0.5 * std::fabs((980.5 - 12.3125) * (1010.5 - 40.75) -
                                      (103.25 - 40.75) * (300.0078125 - 12.3125));
  // Boundary pixels are the only ones that can disagree: fewer than the perimeter (+ corners).
  const double perimeter = std::hypot(980.5 - 12.3125, 103.25 - 40.75) +
                           std::hypot(300.0078125 - 980.5, 1010.5 - 103.25) +
                           std::hypot(12.3125 - 300.0078125, 40.75 - 1010.5);
  EXPECT_NEAR(count, area, perimeter + 4) << "area " << area;
  EXPECT_NEAR(count / area, 1.0, 0.001);
}

TEST(Coverage, OffGridCoordinateIsALogicError) {
  EXPECT_THROW(covered_rows(tri(0.1, 0, 5, 0, 0, 5), 8, 8), std::logic_error);
  EXPECT_THROW(covered_rows(tri(0, 0, 5, 0, 0, std::ldexp(1.0, -25)), 8, 8), std::logic_error);
  EXPECT_THROW(covered_rows(tri(0, 0, 5, 0, 0, std::nan("")), 8, 8), std::logic_error);
  EXPECT_NO_THROW(covered_rows(tri(0, 0, 5, 0, 0, std::ldexp(1.0, -24)), 8, 8));
}

TEST(Coverage, ClipsToTheScreen) {
  const std::vector<CoveredRow> rows = covered_rows(tri(-100, -100, 300, -100, -100, 300), 16, 8);
  ASSERT_EQ(rows.size(), 8u);
  for (const CoveredRow& r : rows) {
    EXPECT_EQ(r.x_begin, 0);
    EXPECT_EQ(r.x_end, 16);
  }
}

ScreenVertex midpoint(const ScreenVertex& a, const ScreenVertex& b) {
  ScreenVertex m;
  m.x = (a.x + b.x) / 2;  // exact: one more fraction bit
  m.y = (a.y + b.y) / 2;
  m.z = (a.z + b.z) / 2;
  return m;
}

// Splits edge k (from vertex k to k+1) at its midpoint.
std::pair<ScreenTriangle, ScreenTriangle> split(const ScreenTriangle& t, int k) {
  const ScreenVertex& a = t.v[k];
  const ScreenVertex& b = t.v[(k + 1) % 3];
  const ScreenVertex& c = t.v[(k + 2) % 3];
  const ScreenVertex m = midpoint(a, b);
  ScreenTriangle first = t, second = t;
  first.v = {a, m, c};
  second.v = {m, b, c};
  return {first, second};
}

TEST(Partition, MidpointSplitCoversExactlyTheParent) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> coord(0, 64 * 256);  // 2^-8 grid over 64 pixels
  const int w = 64, h = 64;
  for (int n = 0; n < 300; ++n) {
    const ScreenTriangle parent = tri(coord(rng) / 256.0, coord(rng) / 256.0, coord(rng) / 256.0,
                                      coord(rng) / 256.0, coord(rng) / 256.0, coord(rng) / 256.0);
    const auto [a, b] = split(parent, n % 3);
    const std::vector<int> whole = coverage(parent, w, h);
    const std::vector<int> parts = coverage(std::vector<ScreenTriangle>{a, b}, w, h);
    ASSERT_EQ(whole, parts) << "triangle " << n;
  }
}

TEST(Partition, SixteenLevelsOfMidpointsStayExact) {
  // Repeatedly split the piece containing one corner: after 16 levels the coordinates need all 24
  // fraction bits, and the leaves must still tile the parent exactly.
  const ScreenTriangle parent = tri(3.00390625, 2.5, 60.99609375, 9.75, 17.25, 61.00390625);
  std::vector<ScreenTriangle> leaves;
  ScreenTriangle current = parent;
  for (int level = 0; level < 16; ++level) {
    auto [a, b] = split(current, level % 3);
    leaves.push_back(b);
    current = a;
  }
  leaves.push_back(current);
  EXPECT_EQ(coverage(parent, 64, 64), coverage(leaves, 64, 64));
  // One more level leaves the 2^-24 grid: the rasterizer must refuse rather than round.
  const ScreenTriangle finest = tri(std::ldexp(1.0, -24), 0, 8, 0, 0, 8);
  const auto [p, q] = split(finest, 0);
  (void)q;
  EXPECT_THROW(covered_rows(p, 8, 8), std::logic_error);
}

// A scene with one object, built in code.
Scene one_object_scene(Mesh mesh, Camera camera, int w, int h) {
  Scene s;
  s.width = w;
  s.height = h;
  s.camera = camera;
  s.lights.push_back(DirectionalLight{});
  s.materials.push_back(Material{});
  Object o;
  o.mesh = std::move(mesh);
  s.objects.push_back(std::move(o));
  return s;
}

TEST(ClosedMesh, SphereFrontFacesCoverSilhouetteExactlyOnce) {
  Camera camera;
  camera.position = {0.3, 0.2, 4};
  camera.fov_y_deg = 45;
  for (int tessellation : {6, 17, 48}) {
    SCOPED_TRACE(tessellation);
    const Scene s = one_object_scene(make_sphere(1.0, tessellation), camera, 200, 160);
    ProjectStats stats;
    const std::vector<ScreenTriangle> tris = project_scene(s, &stats);
    const std::vector<int> c = coverage(tris, s.width, s.height);
    // Front faces of a convex closed mesh never overlap, and they tile its silhouette: each row's
    // covered pixels are one run, all covered exactly once.
    int covered_rows_count = 0;
    for (int y = 0; y < s.height; ++y) {
      int first = -1, last = -1;
      for (int x = 0; x < s.width; ++x) {
        const int n = c[y * s.width + x];
        ASSERT_LE(n, 1) << "pixel " << x << "," << y << " shaded twice";
        if (n == 1) {
          if (first < 0) first = x;
          last = x;
        }
      }
      if (first < 0) continue;
      ++covered_rows_count;
      for (int x = first; x <= last; ++x)
        ASSERT_EQ(c[y * s.width + x], 1) << "hole at " << x << "," << y;
    }
    EXPECT_GT(covered_rows_count, 40);
    EXPECT_EQ(stats.clipped_near, 0);
    EXPECT_EQ(stats.triangles_in, stats.culled_back_face + stats.culled_near +
                                      stats.dropped_out_of_range + stats.emitted);
  }
}

TEST(ClosedMesh, TorusVisibilityOwnsEveryCoveredPixelOnce) {
  // Not convex: front faces overlap, so check resolve_visibility against the coverage union.
  Camera camera;
  camera.position = {0, 2.2, 3};
  const Scene s = one_object_scene(make_torus(1.0, 0.4, 20), camera, 160, 120);
  const std::vector<ScreenTriangle> tris = project_scene(s, nullptr);
  const std::vector<int> c = coverage(tris, s.width, s.height);
  const Visibility v = resolve_visibility(tris, s.width, s.height);
  for (size_t i = 0; i < c.size(); ++i) {
    ASSERT_EQ(v.owner[i] >= 0, c[i] > 0) << "pixel " << i;
  }
  // Owners really cover their pixels.
  for (const Span& sp : v.spans) {
    for (const CoveredRow& r : covered_rows(tris[sp.triangle], s.width, s.height)) {
      if (r.y == sp.y) {
        EXPECT_LE(r.x_begin, sp.x0);
        EXPECT_GE(r.x_end, sp.x0 + sp.length);
      }
    }
  }
}

TEST(Visibility, NearerWinsAndTiesGoToLowerIndex) {
  const ScreenTriangle big_far = tri(0, 0, 16, 0, 0, 16, 0.8);
  const ScreenTriangle small_near = tri(2, 2, 10, 2, 2, 10, 0.2);
  for (int order = 0; order < 2; ++order) {
    const std::vector<ScreenTriangle> tris = order == 0
                                                 ? std::vector<ScreenTriangle>{big_far, small_near}
                                                 : std::vector<ScreenTriangle>{small_near, big_far};
    const int near_index = order == 0 ? 1 : 0;
    const Visibility v = resolve_visibility(tris, 16, 16);
    EXPECT_EQ(v.owner[3 * 16 + 3], near_index);
    EXPECT_EQ(v.owner[12 * 16 + 1], 1 - near_index);
    EXPECT_EQ(v.owner[15 * 16 + 15], -1);
  }
  const ScreenTriangle same = tri(0, 0, 16, 0, 0, 16, 0.5);
  const Visibility tie = resolve_visibility({same, same, same}, 16, 16);
  for (int32_t o : tie.owner) EXPECT_TRUE(o == 0 || o == -1);
}

TEST(Visibility, DepthIsInterpolatedAcrossTheTriangle) {
  // Two triangles crossing each other: one tilted in depth along x, one flat at 0.5. The tilted
  // one (z = x / 16) is nearer left of x = 8.
  ScreenTriangle tilted = tri(0, 0, 16, 0, 0, 16);
  tilted.v[0].z = 0;
  tilted.v[1].z = 1;
  tilted.v[2].z = 0;
  ScreenTriangle flat = tri(0, 0, 16, 0, 0, 16, 0.5);
  const Visibility v = resolve_visibility({flat, tilted}, 16, 16);
  for (int x = 0; x < 15; ++x) {
    const double z_tilted = (x + 0.5) / 16;
    EXPECT_EQ(v.owner[0 * 16 + x], z_tilted < 0.5 ? 1 : 0) << x;
  }
}

void check_spans(const Visibility& v, size_t triangle_count) {
  // Spans rebuild the owner buffer exactly, each pixel once.
  std::vector<int32_t> rebuilt(v.owner.size(), -1);
  for (const Span& s : v.spans) {
    ASSERT_GT(s.length, 0);
    ASSERT_LT(s.triangle, triangle_count);
    for (int x = s.x0; x < s.x0 + s.length; ++x) {
      ASSERT_EQ(rebuilt[static_cast<size_t>(s.y) * v.width + x], -1) << "pixel in two spans";
      rebuilt[static_cast<size_t>(s.y) * v.width + x] = static_cast<int32_t>(s.triangle);
    }
  }
  ASSERT_EQ(rebuilt, v.owner);
  // Order: triangle ascending, then y, then x0; runs are maximal.
  for (size_t i = 1; i < v.spans.size(); ++i) {
    const Span& a = v.spans[i - 1];
    const Span& b = v.spans[i];
    const bool ordered =
        a.triangle < b.triangle ||
        (a.triangle == b.triangle && (a.y < b.y || (a.y == b.y && a.x0 + a.length < b.x0)));
    ASSERT_TRUE(ordered) << "span " << i;
  }
  // last_in_row: exactly the last span of each row in stream order.
  std::map<int, size_t> last;
  for (size_t i = 0; i < v.spans.size(); ++i) last[v.spans[i].y] = i;
  for (size_t i = 0; i < v.spans.size(); ++i)
    ASSERT_EQ(v.spans[i].last_in_row, last[v.spans[i].y] == i) << i;
}

TEST(Spans, ReconstructOwnerBufferAndFollowStreamOrder) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> coord(-256, 100 * 256);
  std::uniform_real_distribution<double> depth(0, 1);
  std::vector<ScreenTriangle> tris;
  tris.reserve(200);
  for (int n = 0; n < 200; ++n) {
    tris.push_back(tri(coord(rng) / 256.0, coord(rng) / 256.0, coord(rng) / 256.0,
                       coord(rng) / 256.0, coord(rng) / 256.0, coord(rng) / 256.0, depth(rng)));
  }
  const Visibility v = resolve_visibility(tris, 96, 80);
  EXPECT_EQ(v.width, 96);
  EXPECT_EQ(v.height, 80);
  check_spans(v, tris.size());
  EXPECT_GT(v.spans.size(), 200u);
}

TEST(Spans, SphereSceneSpans) {
  Camera camera;
  const Scene s = one_object_scene(make_sphere(1.0, 24), camera, 128, 128);
  const std::vector<ScreenTriangle> tris = project_scene(s, nullptr);
  const Visibility v = resolve_visibility(tris, s.width, s.height);
  check_spans(v, tris.size());
}

TEST(Projection, OrthographicMatchesClosedForm) {
  Camera camera;
  camera.kind = Camera::Kind::kOrthographic;
  camera.position = {0, 0, 5};
  camera.ortho_height = 4;
  Mesh mesh = make_sphere(1.0, 8);
  const Scene s = one_object_scene(mesh, camera, 100, 100);
  ProjectStats stats;
  const std::vector<ScreenTriangle> tris = project_scene(s, &stats);
  ASSERT_FALSE(tris.empty());
  // 25 pixels per unit, origin at (50, 50), y flipped; z is the distance along the view axis.
  for (const ScreenTriangle& t : tris) {
    for (const ScreenVertex& v : t.v) {
      // Find the world vertex by its normal (sphere: normal = position).
      const Vec3 p = v.normal;
      EXPECT_NEAR(v.x, 50 + 25 * p.x, 1.0 / 512);
      EXPECT_NEAR(v.y, 50 - 25 * p.y, 1.0 / 512);
      EXPECT_EQ(v.x * 256, std::floor(v.x * 256));
      EXPECT_NEAR(v.z, 5 - p.z, 1e-12);
      EXPECT_NEAR(length(v.to_eye - normalize(camera.position - p)), 0, 1e-12);
    }
    // Front faces only: the triangle's normals point toward the viewer.
    EXPECT_GT(t.v[0].normal.z + t.v[1].normal.z + t.v[2].normal.z, 0);
    EXPECT_EQ(t.parent, -1);
  }
  EXPECT_EQ(stats.triangles_in, static_cast<int64_t>(mesh.triangles.size()));
  EXPECT_EQ(stats.emitted, static_cast<int64_t>(tris.size()));
  EXPECT_GT(stats.culled_back_face, 0);
}

TEST(Projection, PerspectiveMatchesClosedForm) {
  Camera camera;
  camera.position = {0, 0, 5};
  camera.fov_y_deg = 90;  // focal length = (height / 2) / tan(45 deg) = height / 2
  camera.near_plane = 0.5;
  camera.far_plane = 50;
  Mesh mesh;
  mesh.positions = {{0, 1, 0}, {-1, -1, 1}, {2, -1, -1}};
  mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  mesh.triangles = {{0, 1, 2}};
  const Scene s = one_object_scene(mesh, camera, 120, 100);
  const std::vector<ScreenTriangle> tris = project_scene(s, nullptr);
  ASSERT_EQ(tris.size(), 1u);
  for (int i = 0; i < 3; ++i) {
    const Vec3 p = mesh.positions[i];
    const double d = 5 - p.z;
    const ScreenVertex& v = tris[0].v[i];
    EXPECT_NEAR(v.x, 60 + 50 * p.x / d, 1.0 / 512);
    EXPECT_NEAR(v.y, 50 - 50 * p.y / d, 1.0 / 512);
    EXPECT_NEAR(v.z, 50 * (d - 0.5) / (d * 49.5), 1e-12);
  }
  // Reversed winding faces away and is culled.
  Scene back = s;
  back.objects[0].mesh.triangles = {{0, 2, 1}};
  ProjectStats stats;
  EXPECT_TRUE(project_scene(back, &stats).empty());
  EXPECT_EQ(stats.culled_back_face, 1);
}

// Every candidate (an unclipped triangle or a clipping piece) ends culled, dropped or emitted.
void expect_projection_accounted(const ProjectStats& st) {
  EXPECT_EQ(st.triangles_in - st.culled_near - st.clipped_near + st.clipped_pieces,
            st.culled_back_face + st.dropped_out_of_range + st.emitted);
}

TEST(Projection, FloorAroundTheCameraIsClippedCulledAndCounted) {
  Camera camera;
  camera.position = {0, 0, 0};
  camera.target = {0, 0, -1};
  camera.near_plane = 0.1;
  // A floor plane around the camera: some triangles lie wholly behind it, some cross it.
  Transform t;
  t.translate = {0, -1, 0};
  const Scene s = one_object_scene(transform_mesh(make_plane(20, 10), t), camera, 64, 64);
  ProjectStats stats;
  const std::vector<ScreenTriangle> tris = project_scene(s, &stats);
  EXPECT_GT(stats.culled_near, 0);
  EXPECT_GT(stats.clipped_near, 0);
  EXPECT_LE(stats.clipped_pieces, 6 * stats.clipped_near);  // near plane + 4 guard-band sides
  EXPECT_GT(stats.emitted, 0);
  expect_projection_accounted(stats);
  for (const ScreenTriangle& tr : tris)
    for (const ScreenVertex& v : tr.v) EXPECT_GE(v.z, 0.0);
  // Without the guard band the clip points at depth 0.1 would land up to 10 / 0.1 * 88 pixels
  // (focal length 32 / tan 20 deg) off-centre. Every emitted vertex that is not a projected mesh
  // vertex is a clip point, and lies within kGuardBandPixels of the image, plus the snapping.
  const double focal = 32 / std::tan(20 * 3.14159265358979323846 / 180);
  auto is_mesh_vertex = [&](const ScreenVertex& v) {
    for (const Vec3& p : s.objects[0].mesh.positions) {
      const double d = -p.z;
      if (d < 0.1) continue;
      if (std::fabs(v.x - (32 + focal * p.x / d)) < 1.0 / 256 &&
          std::fabs(v.y - (32 - focal * p.y / d)) < 1.0 / 256)
        return true;
    }
    return false;
  };
  double worst_outside = 0;
  int clip_points = 0;
  for (const ScreenTriangle& tr : tris) {
    for (const ScreenVertex& v : tr.v) {
      if (is_mesh_vertex(v)) continue;
      ++clip_points;
      worst_outside = std::max({worst_outside, -v.x, v.x - 64, -v.y, v.y - 64});
    }
  }
  EXPECT_GT(clip_points, 0);
  EXPECT_GT(worst_outside, kGuardBandPixels - 1);  // the band is reached: it did cut
  EXPECT_LE(worst_outside, kGuardBandPixels + 1.0 / 256);
}

// Camera at the origin looking down -z, 90 degree field of view on 120 x 100: a point (x, y, z)
// at depth d = -z lands on (60 + 50 x / d, 50 - 50 y / d). The floor y = -1 faces the camera.
Camera clip_camera() {
  Camera camera;
  camera.position = {0, 0, 0};
  camera.target = {0, 0, -1};
  camera.fov_y_deg = 90;
  camera.near_plane = 0.5;
  camera.far_plane = 50;
  return camera;
}

void expect_screen(const ScreenVertex& v, double x, double y, double z) {
  EXPECT_NEAR(v.x, x, 1.0 / 512);
  EXPECT_NEAR(v.y, y, 1.0 / 512);
  EXPECT_NEAR(v.z, z, 1e-12);
}

void expect_vec(Vec3 got, Vec3 want) {
  EXPECT_NEAR(got.x, want.x, 1e-14);
  EXPECT_NEAR(got.y, want.y, 1e-14);
  EXPECT_NEAR(got.z, want.z, 1e-14);
}

TEST(Projection, OneVertexBehindTheNearPlaneBecomesTwoTriangles) {
  // A (d = 2) and C (d = 2) in front, B (d = 0) behind. Both crossing edges meet d = 0.5 at
  // t = (2 - 0.5) / (2 - 0) = 0.75 from their front end: on C-B at (0.5, -1, -0.5), on A-B at
  // (0.75, -1, -0.5), which land on (110, 150) and (135, 150) with screen depth 0.
  Mesh mesh;
  const Vec3 nA{0, 1, 0}, nC = normalize(Vec3{-1, 1, 0}), nB = normalize(Vec3{1, 1, 0});
  mesh.positions = {{0, -1, -2}, {-1, -1, -2}, {1, -1, 0}};
  mesh.normals = {nA, nC, nB};
  mesh.triangles = {{0, 1, 2}};
  const Scene s = one_object_scene(mesh, clip_camera(), 120, 100);
  ProjectStats stats;
  const std::vector<ScreenTriangle> tris = project_scene(s, &stats);
  ASSERT_EQ(tris.size(), 2u);
  EXPECT_EQ(stats.clipped_near, 1);
  EXPECT_EQ(stats.clipped_pieces, 2);
  expect_projection_accounted(stats);
  // The polygon A, C, P_CB, P_AB in mesh order, fanned from A.
  const double z_front = 50 * (2 - 0.5) / (2 * 49.5);
  expect_screen(tris[0].v[0], 60, 75, z_front);
  expect_screen(tris[0].v[1], 35, 75, z_front);
  expect_screen(tris[0].v[2], 110, 150, 0);
  expect_screen(tris[1].v[0], 60, 75, z_front);
  expect_screen(tris[1].v[1], 110, 150, 0);
  expect_screen(tris[1].v[2], 135, 150, 0);
  // Normals interpolated along the edge and renormalised; to-eye vectors at the clip points.
  expect_vec(tris[0].v[2].normal, normalize(nC * 0.25 + nB * 0.75));
  expect_vec(tris[1].v[2].normal, normalize(nA * 0.25 + nB * 0.75));
  expect_vec(tris[0].v[2].to_eye, normalize(Vec3{-0.5, 1, 0.5}));
  expect_vec(tris[1].v[2].to_eye, normalize(Vec3{-0.75, 1, 0.5}));
  expect_vec(tris[0].v[0].to_eye, normalize(Vec3{0, 1, 2}));
  // The two pieces do not overlap, and together they cover the pixels of the clipped quad.
  const std::vector<int> c = coverage(tris, 120, 100);
  for (int n : c) ASSERT_LE(n, 1);
  int pieces = 0;
  for (int n : c) pieces += n;
  // The quad (60,75) (35,75) (110,150) (135,150) is a parallelogram: rows 75 < y < 150, and
  // 35 + (y - 75) <= x < 60 + (y - 75). Centres fall exactly on both slanted sides; by the
  // top-left rule the left one is in and the right one out.
  int quad = 0;
  for (int py = 0; py < 100; ++py)
    for (int px = 0; px < 120; ++px) {
      const double x = px + 0.5, y = py + 0.5;
      if (y > 75 && y < 150 && x >= 35 + (y - 75) && x < 60 + (y - 75)) ++quad;
    }
  EXPECT_GT(quad, 0);
  EXPECT_EQ(pieces, quad);
}

TEST(Projection, OrthographicCameraClipsAtTheNearPlaneToo) {
  // Orthographic, 2 units tall on 100 rows: (x, y, z) lands on (60 + 50 x, 50 - 50 y), depth
  // d = -z. A (d = 2) and C (d = 2) in front, B (d = 0) behind the near plane at 0.5; the
  // crossing edges meet it at t = 0.75 from their front ends: A-B at (0.75, 0.5, -0.5), C-B at
  // (0.5, 0.5, -0.5).
  Camera camera = clip_camera();
  camera.kind = Camera::Kind::kOrthographic;
  camera.ortho_height = 2;
  Mesh mesh;
  mesh.positions = {{0, -1, -2}, {1, 1, 0}, {-1, -1, -2}};
  mesh.normals = {{0, -0.7071, 0.7071}, {0, -0.7071, 0.7071}, {0, -0.7071, 0.7071}};
  mesh.triangles = {{0, 1, 2}};
  const Scene s = one_object_scene(mesh, camera, 120, 100);
  ProjectStats stats;
  const std::vector<ScreenTriangle> tris = project_scene(s, &stats);
  ASSERT_EQ(tris.size(), 2u);
  EXPECT_EQ(stats.clipped_near, 1);
  expect_projection_accounted(stats);
  // The polygon A, P_AB, P_CB, C, fanned from A; orthographic depth is the view depth.
  expect_screen(tris[0].v[0], 60, 100, 2);
  expect_screen(tris[0].v[1], 97.5, 25, 0.5);
  expect_screen(tris[0].v[2], 85, 25, 0.5);
  expect_screen(tris[1].v[2], 10, 100, 2);
  expect_vec(tris[0].v[1].to_eye, normalize(Vec3{-0.75, -0.5, 0.5}));
}

TEST(Projection, TwoVerticesBehindTheNearPlaneLeaveOneTriangle) {
  Mesh mesh;
  mesh.positions = {{0, -1, -2}, {-1, -1, 0}, {1, -1, 0}};
  mesh.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}};
  const Scene s = one_object_scene(mesh, clip_camera(), 120, 100);
  ProjectStats stats;
  const std::vector<ScreenTriangle> tris = project_scene(s, &stats);
  ASSERT_EQ(tris.size(), 1u);
  EXPECT_EQ(stats.clipped_pieces, 1);
  expect_projection_accounted(stats);
  // A, then the clip points on A-C at (-0.75, -1, -0.5) and on B-A at (0.75, -1, -0.5).
  expect_screen(tris[0].v[0], 60, 75, 50 * 1.5 / (2 * 49.5));
  expect_screen(tris[0].v[1], -15, 150, 0);
  expect_screen(tris[0].v[2], 135, 150, 0);

  // Wholly behind: culled, not clipped.
  Scene behind = s;
  for (Vec3& p : behind.objects[0].mesh.positions) p.z += 2;
  ProjectStats behind_stats;
  EXPECT_TRUE(project_scene(behind, &behind_stats).empty());
  EXPECT_EQ(behind_stats.culled_near, 1);
  EXPECT_EQ(behind_stats.clipped_near, 0);
  expect_projection_accounted(behind_stats);
}

TEST(Projection, TrianglesSharingAClippedEdgeShareItsClipPoint) {
  // Two triangles of a quad whose diagonal crosses the near plane, listed so that they traverse
  // the shared edge in opposite directions: the clip point on it must be bit-identical.
  Mesh mesh;
  mesh.positions = {{-1, -1, -3}, {-1, -1, 1}, {1, -1, 1}, {1, -1, -3}};
  mesh.normals = {{0, 1, 0}, {0.3, 1, 0}, {0, 1, 0.2}, {0.1, 1, 0}};
  for (Vec3& n : mesh.normals) n = normalize(n);
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  const Scene s = one_object_scene(mesh, clip_camera(), 120, 100);
  const std::vector<ScreenTriangle> tris = project_scene(s, nullptr);
  // Diagonal 0-2 meets d = 0.5 at one point; count the screen vertices that sit at depth 0 with
  // that point's x (it is the only clip point with 0 < x < 1 in world space: x = -1 + 2 * 0.625).
  const double x_expect = 60 + 50 * 0.25 / 0.5;
  std::vector<ScreenVertex> on_diagonal;
  for (const ScreenTriangle& t : tris)
    for (const ScreenVertex& v : t.v)
      if (v.z == 0 && std::fabs(v.x - x_expect) < 1.0 / 256) on_diagonal.push_back(v);
  ASSERT_GE(on_diagonal.size(), 2u);
  for (const ScreenVertex& v : on_diagonal) {
    EXPECT_EQ(v.x, on_diagonal[0].x);
    EXPECT_EQ(v.y, on_diagonal[0].y);
    EXPECT_EQ(v.normal, on_diagonal[0].normal);
    EXPECT_EQ(v.to_eye, on_diagonal[0].to_eye);
  }
  // And the two clipped triangles leave no hole along it: the clipped quad's rows are one run.
  const std::vector<int> c = coverage(tris, 120, 100);
  for (int y = 0; y < 100; ++y) {
    int first = -1, last = -1;
    for (int x = 0; x < 120; ++x) {
      ASSERT_LE(c[y * 120 + x], 1);
      if (c[y * 120 + x] == 1) {
        if (first < 0) first = x;
        last = x;
      }
    }
    for (int x = first; first >= 0 && x <= last; ++x) EXPECT_EQ(c[y * 120 + x], 1) << x << "," << y;
  }
}

TEST(Projection, ObjectAndMaterialIndicesCarryThrough) {
  Camera camera;
  Scene s = one_object_scene(make_sphere(0.5, 6), camera, 64, 64);
  s.materials.push_back(Material{});
  Object second;
  Transform t;
  t.translate = {1, 0, 0};
  second.mesh = transform_mesh(make_sphere(0.5, 6), t);
  second.material = 1;
  s.objects.push_back(second);
  const std::vector<ScreenTriangle> tris = project_scene(s, nullptr);
  int seen[2] = {0, 0};
  for (const ScreenTriangle& tr : tris) {
    ASSERT_TRUE(tr.object == 0 || tr.object == 1);
    EXPECT_EQ(tr.material, tr.object);
    ++seen[tr.object];
  }
  EXPECT_GT(seen[0], 0);
  EXPECT_GT(seen[1], 0);
}

}  // namespace
}  // namespace shadesim
