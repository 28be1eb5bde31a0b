#include "host/shading_field.h"

#include <algorithm>
#include <cmath>

namespace shadesim {

std::optional<AffineField> affine_field(const std::array<ScreenVertex, 3>& v,
                                        Vec3 ScreenVertex::*member) {
  const double e1x = v[1].x - v[0].x, e1y = v[1].y - v[0].y;
  const double e2x = v[2].x - v[0].x, e2y = v[2].y - v[0].y;
  const double det = e1x * e2y - e1y * e2x;
  const double e3x = v[2].x - v[1].x, e3y = v[2].y - v[1].y;
  const double longest2 =
      std::max({e1x * e1x + e1y * e1y, e2x * e2x + e2y * e2y, e3x * e3x + e3y * e3y});
  // Relative threshold: on the 2^-24 subdivision grid det is not computed exactly, so "== 0" would
  // let rounding noise through as a huge gradient.
  if (!std::isfinite(det) || !(std::fabs(det) > 1e-14 * longest2)) return std::nullopt;
  const Vec3 f0 = v[0].*member;
  const Vec3 d1 = v[1].*member - f0;
  const Vec3 d2 = v[2].*member - f0;
  AffineField field;
  field.a = (d1 * e2y - d2 * e1y) / det;
  field.b = (d2 * e1x - d1 * e2x) / det;
  field.c = f0 - field.a * v[0].x - field.b * v[0].y;
  return field;
}

double diffuse_exact(const AffineField& N, Vec3 L, double x, double y) {
  const Vec3 n = N.at(x, y);
  const double len = length(n);
  return len > 0.0 ? dot(n, L) / len : 0.0;
}

double specular_exact_infinite(const AffineField& N, Vec3 H, double x, double y) {
  return diffuse_exact(N, H, x, y);
}

double specular_exact_finite(const AffineField& N, const AffineField& E, Vec3 L, double x,
                             double y) {
  const Vec3 n = N.at(x, y);
  const Vec3 h = E.at(x, y) + L;
  const double len = std::sqrt(dot(n, n) * dot(h, h));
  return len > 0.0 ? dot(n, h) / len : 0.0;
}

double phong_cosine(Vec3 n, Vec3 L, Vec3 v) {
  const double n_len = length(n), v_len = length(v);
  if (!(n_len > 0.0) || !(v_len > 0.0)) return 0.0;
  const Vec3 n_unit = n / n_len;
  const Vec3 reflected = n_unit * (2.0 * dot(n_unit, L)) - L;
  return dot(reflected, v) / v_len;
}

double phong_exact_infinite(const AffineField& N, Vec3 L, Vec3 V, double x, double y) {
  return phong_cosine(N.at(x, y), L, V);
}

double phong_exact_finite(const AffineField& N, const AffineField& E, Vec3 L, double x, double y) {
  return phong_cosine(N.at(x, y), L, E.at(x, y));
}

Vec3 eye_direction_at_infinity(const Camera& camera) {
  return normalize(camera.position - camera.target);
}

Vec3 half_vector(Vec3 L, Vec3 V) { return normalize(L + V); }

}  // namespace shadesim
