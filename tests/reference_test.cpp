// Float reference: closed-form Lambert and Blinn values at known normals, clamping, background,
// and agreement with the affine fields the Taylor series expand.
#include "host/reference.h"

#include <gtest/gtest.h>

#include <cmath>

#include "host/shading_field.h"

namespace shadesim {
namespace {

ScreenVertex vert(double x, double y, Vec3 n, Vec3 e = {0, 0, 1}) {
  ScreenVertex v;
  v.x = x;
  v.y = y;
  v.normal = n;
  v.to_eye = e;
  return v;
}

// Default camera looks from (0, 0, 5) at the origin: V = (0, 0, 1).
Scene one_light_scene(Vec3 dir, Vec3 colour, const Material& m) {
  Scene s;
  s.width = 40;
  s.height = 30;
  s.lights.push_back(DirectionalLight{dir, colour});
  s.ambient_light = {0.5, 0.5, 0.5};
  s.materials.push_back(m);
  return s;
}

// Owner buffer from an inside test at pixel centres (closed; these tests do not share edges).
std::vector<int32_t> owners(const ScreenTriangle& t, int w, int h) {
  std::vector<int32_t> o(static_cast<std::size_t>(w) * h, -1);
  const auto& v = t.v;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const double x = px + 0.5, y = py + 0.5;
      bool pos = true, neg = true;
      for (int k = 0; k < 3; ++k) {
        const auto& a = v[k];
        const auto& b = v[(k + 1) % 3];
        const double e = (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
        pos = pos && e >= 0;
        neg = neg && e <= 0;
      }
      if (pos || neg) o[static_cast<std::size_t>(py) * w + px] = 0;
    }
  return o;
}

TEST(Reference, FlatTriangleIsClosedFormPhongBlinnEverywhere) {
  Material m;
  m.ambient = {0.1, 0.2, 0.05};
  m.diffuse = {0.5, 0.4, 0.3};
  m.specular = {0.3, 0.2, 0.1};
  m.exponent = 20;
  // Light direction deliberately not unit: the reference normalises it.
  const Scene s = one_light_scene({2, 2, 4}, {0.9, 0.8, 0.7}, m);
  const Vec3 n{0.2, -0.3, 1.0};  // not unit either: normalised per pixel
  ScreenTriangle t;
  t.v = {vert(2, 3, n), vert(37, 5, n), vert(15, 28, n)};
  const auto own = owners(t, s.width, s.height);
  const ReferenceImage img = render_reference({t}, own, s.width, s.height, s, 3);
  ASSERT_EQ(img.values.size(), 40u * 30u * 3u);

  // Hand evaluation: |n| = sqrt(1.13), L = (1, 1, 2)/sqrt(6), H = normalize(L + (0, 0, 1)).
  const double nl = (0.2 - 0.3 + 2.0) / std::sqrt(6.0) / std::sqrt(1.13);
  const double lz = 2 / std::sqrt(6.0) + 1;
  const double hlen = std::sqrt(2.0 / 6.0 + lz * lz);
  const double nh = (0.2 / std::sqrt(6.0) - 0.3 / std::sqrt(6.0) + lz) / hlen / std::sqrt(1.13);
  const double spec = std::pow(nh, 20);
  const double expect[3] = {0.05 + 0.9 * (0.5 * nl + 0.3 * spec),
                            0.10 + 0.8 * (0.4 * nl + 0.2 * spec),
                            0.025 + 0.7 * (0.3 * nl + 0.1 * spec)};
  int owned = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x)
      for (int c = 0; c < 3; ++c) {
        if (own[static_cast<std::size_t>(y) * s.width + x] < 0) {
          EXPECT_EQ(img.at(x, y, c), 0.0);
        } else {
          owned += c == 0;
          EXPECT_NEAR(img.at(x, y, c), expect[c], 1e-14) << x << "," << y << " ch " << c;
        }
      }
  EXPECT_GT(owned, 300);

  const ReferenceImage grey = render_reference({t}, own, s.width, s.height, s, 1);
  ASSERT_EQ(grey.values.size(), 40u * 30u);
  EXPECT_NEAR(grey.at(15, 12, 0), expect[0], 1e-14);
}

// Vertices symmetric about the centre of pixel (20, 15), so there N is the vertex mean.
ScreenTriangle centred_triangle(Vec3 mean, Vec3 d0, Vec3 d1, Vec3 e_mean, Vec3 e0, Vec3 e1) {
  const double cx = 20.5, cy = 15.5;
  ScreenTriangle t;
  t.v = {vert(cx - 9, cy - 6, mean + d0, e_mean + e0),
         vert(cx + 12, cy - 3, mean + d1, e_mean + e1),
         vert(cx - 3, cy + 9, mean - d0 - d1, e_mean - e0 - e1)};
  return t;
}

TEST(Reference, KnownNormalGivesBlinnValue) {
  Material m;
  m.ambient = {0, 0, 0};
  m.diffuse = {0, 0, 0};
  m.specular = {1, 1, 1};
  m.exponent = 50;
  const Vec3 L = Vec3{0.3, 0.1, 1} / std::sqrt(1.1);
  const Scene s = one_light_scene(L, {1, 1, 1}, m);
  const Vec3 mean{0.3, 0.1, 0.8};
  const ScreenTriangle t = centred_triangle(mean, {0.2, 0, 0}, {0, 0.2, 0.1}, {0, 0, 1}, {}, {});
  std::vector<int32_t> own(size_t{40} * 30, -1);
  own[15 * 40 + 20] = 0;
  own[9 * 40 + 11] = 0;  // (11.5, 9.5) is vertex 0
  const ReferenceImage img = render_reference({t}, own, 40, 30, s, 1);
  const Vec3 H = normalize(L + Vec3{0, 0, 1});
  EXPECT_NEAR(img.at(20, 15, 0), std::pow(dot(normalize(mean), H), 50), 1e-13);
  EXPECT_NEAR(img.at(11, 9, 0), std::pow(dot(normalize(t.v[0].normal), H), 50), 1e-13);
}

TEST(Reference, PhongUsesRDotVWithTheEyeAtInfinityAndFinite) {
  Material m;
  m.ambient = {0, 0, 0};
  m.diffuse = {0, 0, 0};
  m.specular = {1, 1, 1};
  m.exponent = 12;
  m.specular_model = SpecularModel::kPhong;
  const Vec3 L = normalize(Vec3{0.3, 0.2, 1});
  Scene s = one_light_scene(L, {1, 1, 1}, m);
  const Vec3 mean{0.1, 0.05, 0.9}, e_mean{0.2, -0.1, 0.95};
  const ScreenTriangle t =
      centred_triangle(mean, {0.1, 0, 0}, {0, -0.1, 0}, e_mean, {0.05, 0.02, 0}, {-0.03, 0.04, 0});
  std::vector<int32_t> own(size_t{40} * 30, -1);
  own[15 * 40 + 20] = 0;
  // Closed form: R.V = 2 (N.L)(N.V) / |N|^2 - L.V, V unit.
  auto r_dot_v = [&](Vec3 n, Vec3 v) { return 2 * dot(n, L) * dot(n, v) / dot(n, n) - dot(L, v); };
  const Vec3 V_inf{0, 0, 1};  // the default camera looks from (0, 0, 5) at the origin
  ASSERT_GT(r_dot_v(mean, V_inf), 0.5);
  EXPECT_NEAR(render_reference({t}, own, 40, 30, s, 1).at(20, 15, 0),
              std::pow(r_dot_v(mean, V_inf), 12), 1e-13);
  s.eye_at_infinity = false;
  const Vec3 V_fin = normalize(e_mean);
  ASSERT_GT(r_dot_v(mean, V_fin), 0.5);
  EXPECT_NEAR(render_reference({t}, own, 40, 30, s, 1).at(20, 15, 0),
              std::pow(r_dot_v(mean, V_fin), 12), 1e-13);
  // Not Blinn's value: the two models really differ at this normal.
  EXPECT_GT(std::fabs(std::pow(r_dot_v(mean, V_fin), 12) -
                      std::pow(dot(normalize(mean), normalize(e_mean + L)), 12)),
            0.01);
  // Where R points away from the eye the term is clamped to 0, not raised: N = z, light from
  // -x, so R leans to +x (R = (0.9, 0, 0.2) / |.|), eye toward -x (V = (-1, 0, 0.3) / |.|).
  Scene away = s;
  away.lights[0].direction = normalize(Vec3{-0.9, 0, 0.2});
  const Vec3 z{0, 0, 1}, toward_minus_x = normalize(Vec3{-1, 0, 0.3});
  const Vec3 La = away.lights[0].direction;
  ASSERT_LT(2 * dot(z, La) * dot(z, toward_minus_x) - dot(La, toward_minus_x), 0.0);
  ScreenTriangle flat;
  flat.v = {vert(2, 3, z, toward_minus_x), vert(37, 5, z, toward_minus_x),
            vert(15, 28, z, toward_minus_x)};
  EXPECT_EQ(render_reference({flat}, owners(flat, 40, 30), 40, 30, away, 1).at(15, 12, 0), 0.0);
}

TEST(Reference, FiniteEyeUsesInterpolatedEyeVector) {
  Material m;
  m.ambient = {0, 0, 0};
  m.diffuse = {0, 0, 0};
  m.specular = {1, 1, 1};
  m.exponent = 30;
  const Vec3 L = normalize(Vec3{-0.2, 0.3, 1});
  Scene s = one_light_scene(L, {1, 1, 1}, m);
  s.eye_at_infinity = false;
  const Vec3 mean{0.1, 0.05, 0.9}, e_mean{0.2, -0.1, 0.95};
  const ScreenTriangle t =
      centred_triangle(mean, {0.1, 0, 0}, {0, -0.1, 0}, e_mean, {0.05, 0.02, 0}, {-0.03, 0.04, 0});
  std::vector<int32_t> own(size_t{40} * 30, -1);
  own[15 * 40 + 20] = 0;
  const ReferenceImage img = render_reference({t}, own, 40, 30, s, 1);
  const Vec3 H = normalize(e_mean + L);
  EXPECT_NEAR(img.at(20, 15, 0), std::pow(dot(normalize(mean), H), 30), 1e-13);
}

// No specular where N.L <= 0 (LM3DGP's Phong chapter), though N.H > 0 there.
TEST(Reference, SpecularIsGatedByNDotL) {
  Material m;
  m.ambient = {0, 0, 0};
  m.diffuse = {1, 1, 1};
  m.specular = {1, 1, 1};
  m.exponent = 4;
  const Vec3 L = normalize(Vec3{1, 0, 0.05});
  const Scene s = one_light_scene(L, {1, 1, 1}, m);
  const Vec3 n = normalize(Vec3{-0.3, 0, 1});
  ASSERT_LT(dot(n, L), 0.0);
  ScreenTriangle t;
  t.v = {vert(2, 3, n), vert(37, 5, n), vert(15, 28, n)};
  const ReferenceImage img = render_reference({t}, owners(t, 40, 30), 40, 30, s, 1);
  const double nh = dot(n, normalize(L + Vec3{0, 0, 1}));
  ASSERT_GT(nh, 0.0);
  EXPECT_EQ(img.at(15, 12, 0), 0.0);  // diffuse 0 and no specular, though pow(nh, 4) = 0.06
  ASSERT_GT(std::pow(nh, 4), 0.05);   // (15 8-bit LSBs)
  // The same normal turned just in front of the terminator: N.L > 0, specular present.
  const Vec3 lit = normalize(Vec3{-0.04, 0, 1});
  ASSERT_GT(dot(lit, L), 0.0);
  t.v = {vert(2, 3, lit), vert(37, 5, lit), vert(15, 28, lit)};
  const ReferenceImage img_lit = render_reference({t}, owners(t, 40, 30), 40, 30, s, 1);
  EXPECT_NEAR(img_lit.at(15, 12, 0),
              dot(lit, L) + std::pow(dot(lit, normalize(L + Vec3{0, 0, 1})), 4), 1e-14);
}

TEST(Reference, ClampsToOne) {
  Material m;
  m.diffuse = {1, 1, 1};
  const Scene s = one_light_scene({0, 0, 1}, {5, 5, 5}, m);
  ScreenTriangle t;
  t.v = {vert(2, 3, {0, 0, 1}), vert(37, 5, {0, 0, 1}), vert(15, 28, {0, 0, 1})};
  const ReferenceImage img = render_reference({t}, owners(t, 40, 30), 40, 30, s, 3);
  EXPECT_EQ(img.at(15, 12, 1), 1.0);
}

TEST(Reference, MatchesExactShadingOfTheAffineField) {
  // Diffuse-only, curved triangle: the reference (barycentric) and diffuse_exact (solved
  // gradients) are two routes to the same field.
  Material m;
  m.ambient = {0, 0, 0};
  m.diffuse = {1, 1, 1};
  m.specular = {0, 0, 0};
  const Vec3 L = normalize(Vec3{0.3, -0.4, 1});
  const Scene s = one_light_scene(L, {1, 1, 1}, m);
  ScreenTriangle t;
  t.v = {vert(2, 3, normalize(Vec3{-0.5, -0.4, 1})), vert(37, 5, normalize(Vec3{0.6, -0.2, 1})),
         vert(15, 28, normalize(Vec3{0, 0.7, 1}))};
  const auto own = owners(t, 40, 30);
  const ReferenceImage img = render_reference({t}, own, 40, 30, s, 1);
  const AffineField N = *normal_field(t);
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) {
      if (own[static_cast<std::size_t>(y) * 40 + x] == 0) {
        EXPECT_NEAR(img.at(x, y, 0), std::max(0.0, diffuse_exact(N, L, x + 0.5, y + 0.5)), 1e-13);
      }
    }
  }
}

TEST(Reference, BadInputIsRejected) {
  Material m;
  const Scene s = one_light_scene({0, 0, 1}, {1, 1, 1}, m);
  ScreenTriangle t;
  t.v = {vert(2, 3, {0, 0, 1}), vert(37, 5, {0, 0, 1}), vert(15, 28, {0, 0, 1})};
  std::vector<int32_t> own(size_t{40} * 30, -1);
  EXPECT_THROW(render_reference({t}, own, 40, 30, s, 2), std::invalid_argument);
  EXPECT_THROW(render_reference({t}, own, 41, 30, s, 3), std::invalid_argument);
  own[5] = 1;
  try {
    render_reference({t}, own, 40, 30, s, 3);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pixel (5, 0)"), std::string::npos) << e.what();
  }
  own[5] = 0;
  t.material = 2;
  EXPECT_THROW(render_reference({t}, own, 40, 30, s, 3), std::invalid_argument);
}

}  // namespace
}  // namespace shadesim
