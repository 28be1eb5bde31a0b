// Second-order Taylor quadratics of the shading cosines, by forward-mode automatic
// differentiation (no hand-expanded closed forms: the printed ones carry errata).
#pragma once

#include <cmath>

#include "host/shading_field.h"
#include "host/vec3.h"

namespace shadesim {

// q(x, y) = t0 + t1 v + t2 u + t3 v^2 + t4 u v + t5 u^2 with u = x - xc, v = y - yc: Bishop's
// T5 x^2 + T4 xy + T3 y^2 + T2 x + T1 y + T0 about the centre (xc, yc), in pixels.
struct Quadratic {
  double xc = 0.0, yc = 0.0;
  double t[6] = {0, 0, 0, 0, 0, 0};

  double eval(double x, double y) const {
    const double u = x - xc, v = y - yc;
    return t[0] + t[1] * v + t[2] * u + t[3] * v * v + t[4] * u * v + t[5] * u * u;
  }
  // The same polynomial expanded about (x0, y0) (exact in real arithmetic; one rounding per term).
  Quadratic recentred(double x0, double y0) const;
};

// Value, gradient and Hessian of a function of screen (x, y) at one point.
struct Jet2 {
  double v = 0, dx = 0, dy = 0, dxx = 0, dxy = 0, dyy = 0;

  static Jet2 constant(double c) { return Jet2{c, 0, 0, 0, 0, 0}; }
  // a x + b y + c, expanded at (x0, y0).
  static Jet2 affine(double a, double b, double c, double x0, double y0) {
    return Jet2{a * x0 + b * y0 + c, a, b, 0, 0, 0};
  }
};

inline Jet2 operator+(const Jet2& p, const Jet2& q) {
  return {p.v + q.v, p.dx + q.dx, p.dy + q.dy, p.dxx + q.dxx, p.dxy + q.dxy, p.dyy + q.dyy};
}
inline Jet2 operator-(const Jet2& p, const Jet2& q) {
  return {p.v - q.v, p.dx - q.dx, p.dy - q.dy, p.dxx - q.dxx, p.dxy - q.dxy, p.dyy - q.dyy};
}
inline Jet2 operator-(const Jet2& p) { return {-p.v, -p.dx, -p.dy, -p.dxx, -p.dxy, -p.dyy}; }
inline Jet2 operator*(const Jet2& p, double s) {
  return {p.v * s, p.dx * s, p.dy * s, p.dxx * s, p.dxy * s, p.dyy * s};
}
inline Jet2 operator*(double s, const Jet2& p) { return p * s; }
inline Jet2 operator+(const Jet2& p, double s) {
  Jet2 r = p;
  r.v += s;
  return r;
}
inline Jet2 operator*(const Jet2& p, const Jet2& q) {
  return {p.v * q.v,
          p.dx * q.v + p.v * q.dx,
          p.dy * q.v + p.v * q.dy,
          p.dxx * q.v + 2.0 * p.dx * q.dx + p.v * q.dxx,
          p.dxy * q.v + p.dx * q.dy + p.dy * q.dx + p.v * q.dxy,
          p.dyy * q.v + 2.0 * p.dy * q.dy + p.v * q.dyy};
}
// g(p) given g(p.v), g'(p.v), g''(p.v): the second-order chain rule.
inline Jet2 chain(const Jet2& p, double g0, double g1, double g2) {
  return {g0,
          g1 * p.dx,
          g1 * p.dy,
          g1 * p.dxx + g2 * p.dx * p.dx,
          g1 * p.dxy + g2 * p.dx * p.dy,
          g1 * p.dyy + g2 * p.dy * p.dy};
}
inline Jet2 reciprocal(const Jet2& p) {
  const double r = 1.0 / p.v;
  return chain(p, r, -r * r, 2.0 * r * r * r);
}
inline Jet2 operator/(const Jet2& p, const Jet2& q) { return p * reciprocal(q); }
inline Jet2 sqrt(const Jet2& p) {
  const double s = std::sqrt(p.v);
  return chain(p, s, 0.5 / s, -0.25 / (s * p.v));
}

struct JetVec3 {
  Jet2 x, y, z;
};
inline JetVec3 jet_of(const AffineField& f, double x0, double y0) {
  return {Jet2::affine(f.a.x, f.b.x, f.c.x, x0, y0), Jet2::affine(f.a.y, f.b.y, f.c.y, x0, y0),
          Jet2::affine(f.a.z, f.b.z, f.c.z, x0, y0)};
}
inline JetVec3 operator+(const JetVec3& p, Vec3 q) { return {p.x + q.x, p.y + q.y, p.z + q.z}; }
inline Jet2 dot(const JetVec3& p, Vec3 q) { return p.x * q.x + p.y * q.y + p.z * q.z; }
inline Jet2 dot(const JetVec3& p, const JetVec3& q) { return p.x * q.x + p.y * q.y + p.z * q.z; }

// T0..T5 = f, f_y, f_x, f_yy/2, f_xy, f_xx/2 of a jet taken at (xc, yc).
Quadratic quadratic_from_jet(const Jet2& f, double xc, double yc);

// Taylor quadratics about (xc, yc) (setup uses the triangle centroid). Same functions as
// diffuse_exact, specular_exact_infinite, specular_exact_finite. Where |N| or |H| is zero at the
// centre the coefficients are not finite; callers check.
Quadratic taylor_diffuse(const AffineField& N, Vec3 L, double xc, double yc);
Quadratic taylor_specular_infinite(const AffineField& N, Vec3 H, double xc, double yc);
Quadratic taylor_specular_finite(const AffineField& N, const AffineField& E, Vec3 L, double xc,
                                 double yc);
// Phong's R.V, the functions of phong_exact_infinite and phong_exact_finite, differentiated in
// the form 2 (N.L)(N.V) / (N.N) - L.V (V = E / sqrt(E.E) for the finite eye): R never needs to be
// formed, and the only non-polynomial parts are one reciprocal (and one square root).
Quadratic taylor_phong_infinite(const AffineField& N, Vec3 L, Vec3 V, double xc, double yc);
Quadratic taylor_phong_finite(const AffineField& N, const AffineField& E, Vec3 L, double xc,
                              double yc);

}  // namespace shadesim
