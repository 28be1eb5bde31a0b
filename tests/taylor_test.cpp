// Taylor coefficients by automatic differentiation, checked against Bishop & Weimer's closed forms
// (with the errata in README "Checked numerical facts") and against central finite differences
// of the exact shading functions.
#include "host/taylor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "host/shading_field.h"

namespace shadesim {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

struct Rng {
  std::mt19937_64 gen{0x5eed2024u};
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(gen);
  }
  Vec3 vec(double r) { return {uniform(-r, r), uniform(-r, r), uniform(-r, r)}; }
};

// A random field in absolute screen coordinates and the same field relative to (xc, yc), the form
// the paper's closed forms expand about (0, 0).
struct FieldCase {
  AffineField abs;
  Vec3 A, B, C;  // N(xc + x', yc + y') = A x' + B y' + C
  double xc, yc;
  double rate;  // (|A| + |B|) / |C|: relative change per pixel
};

FieldCase random_field(Rng& rng, Vec3 centre_value, double rate) {
  FieldCase fc;
  fc.xc = rng.uniform(0, 1024);
  fc.yc = rng.uniform(0, 1024);
  fc.C = centre_value;
  const double scale = rate * length(centre_value) / 2.0;
  fc.A = normalize(rng.vec(1)) * scale;
  fc.B = normalize(rng.vec(1)) * scale;
  fc.rate = (length(fc.A) + length(fc.B)) / length(fc.C);
  fc.abs = AffineField{fc.A, fc.B, fc.C - fc.A * fc.xc - fc.B * fc.yc};
  return fc;
}

// Bishop & Weimer, diffuse form, T5 corrected (printed "3ig^2"; README "Checked numerical facts").
std::array<double, 6> closed_diffuse(Vec3 A, Vec3 B, Vec3 C, Vec3 L, bool printed_t5 = false) {
  const double a = dot(L, A), b = dot(L, B), c = dot(L, C);
  const double d = dot(A, A), e = 2 * dot(A, B), f = dot(B, B);
  const double g = 2 * dot(A, C), h = 2 * dot(B, C), i = dot(C, C);
  const double si = std::sqrt(i);
  std::array<double, 6> T;
  T[5] = ((printed_t5 ? 3 * i * g * g : 3 * c * g * g) - 4 * c * d * i - 4 * a * g * i) /
         (8 * i * i * si);
  T[4] = (3 * c * g * h - 2 * c * e * i - 2 * b * g * i - 2 * a * h * i) / (4 * i * i * si);
  T[3] = (3 * c * h * h - 4 * c * f * i - 4 * b * h * i) / (8 * i * i * si);
  T[2] = (2 * a * i - c * g) / (2 * i * si);
  T[1] = (2 * b * i - c * h) / (2 * i * si);
  T[0] = c / si;
  return T;
}

// Finite eye: N = A x + B y + C, H = D x + E y + F. Corrected T5, T4 and m = D.D, o = E.E
// (README "Checked numerical facts"); T3..T0 as printed. printed_m_o uses the paper's m = E.E,
// o = 2 D.E instead.
std::array<double, 6> closed_finite(Vec3 A, Vec3 B, Vec3 C, Vec3 D, Vec3 E, Vec3 F,
                                    bool printed_m_o = false) {
  const double a = dot(A, D), b = dot(A, E) + dot(B, D), c = dot(B, E);
  const double d = dot(A, F) + dot(C, D), e = dot(B, F) + dot(C, E), f = dot(C, F);
  const double g = dot(A, A), h = 2 * dot(A, B), i = dot(B, B);
  const double j = 2 * dot(A, C), k = 2 * dot(B, C), l = dot(C, C);
  const double m = printed_m_o ? dot(E, E) : dot(D, D);
  const double n = 2 * dot(D, E);
  const double o = printed_m_o ? 2 * dot(D, E) : dot(E, E);
  const double p = 2 * dot(D, F), q = 2 * dot(E, F), r = dot(F, F);
  const double slr = std::sqrt(l * r);
  std::array<double, 6> T;
  T[5] = (8 * a * l * l * r * r - 4 * d * j * l * r * r - 4 * d * l * l * p * r -
          4 * f * g * l * r * r - 4 * f * l * l * m * r + 3 * f * j * j * r * r +
          3 * f * l * l * p * p + 2 * f * j * l * p * r) /
         (8 * l * l * r * r * slr);
  T[4] = (4 * b * l * l * r * r - 2 * d * k * l * r * r - 2 * d * l * l * q * r -
          2 * e * j * l * r * r - 2 * e * l * l * p * r - 2 * f * h * l * r * r -
          2 * f * l * l * n * r + 3 * f * j * k * r * r + 3 * f * l * l * p * q +
          f * j * l * q * r + f * k * l * p * r) /
         (4 * l * l * r * r * slr);
  T[3] = (8 * c * l * l * r * r - 4 * e * k * l * r * r - 4 * f * i * l * r * r +
          3 * f * k * k * r * r - 4 * e * l * l * q * r + 2 * f * k * l * q * r -
          4 * f * l * l * o * r + 3 * f * l * l * q * q) /
         (8 * l * l * r * r * slr);
  T[2] = (2 * d * l * r - f * j * r - f * l * p) / (2 * l * r * slr);
  T[1] = (2 * e * l * r - f * k * r - f * l * q) / (2 * l * r * slr);
  T[0] = f / slr;
  return T;
}

// Coefficient k has total order 0, 1, 1, 2, 2, 2 and scales like rate^order.
constexpr int kOrder[6] = {0, 1, 1, 2, 2, 2};

void expect_matches_closed(const Quadratic& q, const std::array<double, 6>& T, double rate) {
  for (int k = 0; k < 6; ++k) {
    // Both sides are a few dozen flops on O(1) data: 1e-11 relative to the natural scale.
    const double tol = 1e-11 * std::pow(rate, kOrder[k]);
    EXPECT_NEAR(q.t[k], T[k], tol) << "T" << k;
  }
}

TEST(TaylorClosedForm, DiffuseMatchesCorrectedBishopWeimer) {
  Rng rng;
  for (int trial = 0; trial < 300; ++trial) {
    const double rate = rng.uniform(0.002, 0.3);
    const FieldCase fc = random_field(rng, normalize(rng.vec(1)) * rng.uniform(0.5, 2.0), rate);
    const Vec3 L = normalize(rng.vec(1));
    const Quadratic q = taylor_diffuse(fc.abs, L, fc.xc, fc.yc);
    EXPECT_EQ(q.xc, fc.xc);
    EXPECT_EQ(q.yc, fc.yc);
    expect_matches_closed(q, closed_diffuse(fc.A, fc.B, fc.C, L), fc.rate);
  }
}

TEST(TaylorClosedForm, InfiniteSpecularIsDiffuseFormWithHalfVector) {
  Rng rng;
  for (int trial = 0; trial < 100; ++trial) {
    const FieldCase fc = random_field(rng, normalize(rng.vec(1)), rng.uniform(0.002, 0.3));
    const Vec3 H = half_vector(normalize(rng.vec(1)), normalize(rng.vec(1)));
    const Quadratic q = taylor_specular_infinite(fc.abs, H, fc.xc, fc.yc);
    expect_matches_closed(q, closed_diffuse(fc.A, fc.B, fc.C, H), fc.rate);
  }
}

TEST(TaylorClosedForm, PrintedDiffuseT5IsWrong) {
  // C' not unit and far from L (c = L.C = 0.5, i = C.C = 1.1), with the normal swinging along x
  // (g = 2 A.C large), so 3ig^2 and 3cg^2 differ.
  const Vec3 A{0.02, 0.004, -0.01}, B{-0.002, 0.012, 0.001}, C{0.9, -0.2, 0.5};
  const Vec3 L{0, 0, 1};
  const AffineField N{A, B, C};
  const Quadratic q = taylor_diffuse(N, L, 0.0, 0.0);
  const auto corrected = closed_diffuse(A, B, C, L);
  const auto printed = closed_diffuse(A, B, C, L, /*printed_t5=*/true);
  EXPECT_NEAR(q.t[5], corrected[5], 1e-15);
  EXPECT_GT(std::fabs(q.t[5] - printed[5]), 1e-7)
      << "AD " << q.t[5] << " printed " << printed[5] << " corrected " << corrected[5];
  // And the size of the erratum relative to the coefficient itself is not a rounding effect.
  EXPECT_GT(std::fabs(q.t[5] - printed[5]), 0.5 * std::fabs(q.t[5]));
}

TEST(TaylorClosedForm, FiniteEyeMatchesCorrectedBishopWeimer) {
  Rng rng;
  for (int trial = 0; trial < 300; ++trial) {
    const double rate = rng.uniform(0.002, 0.2);
    const FieldCase n = random_field(rng, normalize(rng.vec(1)) * rng.uniform(0.5, 2.0), rate);
    const Vec3 L = normalize(rng.vec(1));
    // E field with its own centre value; H = E + L must stay away from zero.
    Vec3 e_centre = normalize(rng.vec(1));
    if (length(e_centre + L) < 0.3) e_centre = L;
    AffineField E;
    const Vec3 D = normalize(rng.vec(1)) * (rate / 2), Ey = normalize(rng.vec(1)) * (rate / 2);
    E.a = D;
    E.b = Ey;
    E.c = e_centre - D * n.xc - Ey * n.yc;
    const Quadratic q = taylor_specular_finite(n.abs, E, L, n.xc, n.yc);
    const Vec3 F = e_centre + L;  // H at the centre
    const double scale = n.rate + (length(D) + length(Ey)) / length(F);
    expect_matches_closed(q, closed_finite(n.A, n.B, n.C, D, Ey, F), scale);
  }
}

TEST(TaylorClosedForm, PrintedFiniteEyeMAndOAreWrong) {
  const Vec3 A{0.01, 0.004, -0.003}, B{-0.002, 0.012, 0.001}, C{0.3, -0.2, 1.4};
  const Vec3 D{0.02, -0.01, 0.005}, Ey{0.001, 0.003, -0.015}, F{0.2, 0.4, 1.6};
  const AffineField N{A, B, C};
  const AffineField E{D, Ey, F - Vec3{0, 0, 1}};
  const Quadratic q = taylor_specular_finite(N, E, Vec3{0, 0, 1}, 0.0, 0.0);
  const auto corrected = closed_finite(A, B, C, D, Ey, F);
  const auto printed = closed_finite(A, B, C, D, Ey, F, /*printed_m_o=*/true);
  EXPECT_NEAR(q.t[5], corrected[5], 1e-15);
  EXPECT_NEAR(q.t[3], corrected[3], 1e-15);
  EXPECT_GT(std::fabs(q.t[5] - printed[5]), 0.05 * std::fabs(q.t[5]));
  EXPECT_GT(std::fabs(q.t[3] - printed[3]), 0.05 * std::fabs(q.t[3]));
}

// Central differences with step h. For f analytic with |f| <= M on a complex disc of radius rho
// around the centre, Cauchy gives |f^(j)| <= j! M / rho^j. Our fields keep rho >= 1 / (2 rate) and
// M <= 2, so the truncation terms h^2/6 f''' (first derivatives), h^2/12 f'''' (second) and the
// mixed stencil's h^2/6 (f_xxxy + f_xyyy) are below 256 (h rate)^2 rate^k; rounding adds
// 4 eps M / (h^k). Tolerances are that bound, nothing tuned.
template <class F>
void expect_matches_finite_differences(const Quadratic& q, F f, double rate) {
  const double h = 1e-3 / rate;
  const double hr = h * rate;
  const double x = q.xc, y = q.yc;
  const double f0 = f(x, y);
  const double fx = (f(x + h, y) - f(x - h, y)) / (2 * h);
  const double fy = (f(x, y + h) - f(x, y - h)) / (2 * h);
  const double fxx = (f(x + h, y) - 2 * f0 + f(x - h, y)) / (h * h);
  const double fyy = (f(x, y + h) - 2 * f0 + f(x, y - h)) / (h * h);
  const double fxy =
      (f(x + h, y + h) - f(x + h, y - h) - f(x - h, y + h) + f(x - h, y - h)) / (4 * h * h);
  auto tol = [&](int order) {
    return 256 * hr * hr * std::pow(rate, order) + 8 * kEps * 2 / std::pow(h, order);
  };
  EXPECT_NEAR(q.t[0], f0, 4 * kEps);
  EXPECT_NEAR(q.t[1], fy, tol(1));
  EXPECT_NEAR(q.t[2], fx, tol(1));
  EXPECT_NEAR(q.t[3], fyy / 2, tol(2) / 2);
  EXPECT_NEAR(q.t[4], fxy, tol(2));
  EXPECT_NEAR(q.t[5], fxx / 2, tol(2) / 2);
}

TEST(TaylorFiniteDifferences, Diffuse) {
  Rng rng;
  for (int trial = 0; trial < 200; ++trial) {
    const FieldCase fc = random_field(rng, normalize(rng.vec(1)), rng.uniform(0.002, 0.2));
    const Vec3 L = normalize(rng.vec(1));
    const Quadratic q = taylor_diffuse(fc.abs, L, fc.xc, fc.yc);
    expect_matches_finite_differences(
        q, [&](double x, double y) { return diffuse_exact(fc.abs, L, x, y); }, fc.rate);
  }
}

TEST(TaylorFiniteDifferences, SpecularInfinite) {
  Rng rng;
  for (int trial = 0; trial < 200; ++trial) {
    const FieldCase fc = random_field(rng, normalize(rng.vec(1)), rng.uniform(0.002, 0.2));
    const Vec3 H = half_vector(normalize(rng.vec(1)), normalize(Vec3{0, 0, 1}));
    const Quadratic q = taylor_specular_infinite(fc.abs, H, fc.xc, fc.yc);
    expect_matches_finite_differences(
        q, [&](double x, double y) { return specular_exact_infinite(fc.abs, H, x, y); }, fc.rate);
  }
}

TEST(TaylorFiniteDifferences, SpecularFinite) {
  Rng rng;
  for (int trial = 0; trial < 200; ++trial) {
    const double rate = rng.uniform(0.002, 0.1);
    const FieldCase fc = random_field(rng, normalize(rng.vec(1)), rate);
    const Vec3 L = normalize(rng.vec(1));
    const Vec3 e_centre = normalize(L + normalize(rng.vec(1)) * 0.8);  // |E + L| >= ~1
    const Vec3 D = normalize(rng.vec(1)) * (rate / 4), Ey = normalize(rng.vec(1)) * (rate / 4);
    const AffineField E{D, Ey, e_centre - D * fc.xc - Ey * fc.yc};
    const Quadratic q = taylor_specular_finite(fc.abs, E, L, fc.xc, fc.yc);
    expect_matches_finite_differences(
        q, [&](double x, double y) { return specular_exact_finite(fc.abs, E, L, x, y); },
        fc.rate + rate);
  }
}

// Phong's R.V. Closed form at a point: with V unit, R.V = 2 (N.L)(N.V) / |N|^2 - L.V, which the
// exact functions (computed through the reflected vector R) must give at every sample point.
double phong_closed_form(Vec3 n, Vec3 L, Vec3 V) {
  return 2 * dot(n, L) * dot(n, V) / dot(n, n) - dot(L, V);
}

TEST(PhongClosedForm, ExactFunctionsMatchTwoNlNvOverNnMinusLvAtSamplePoints) {
  Rng rng;
  for (int trial = 0; trial < 200; ++trial) {
    const FieldCase fc =
        random_field(rng, normalize(rng.vec(1)) * rng.uniform(0.5, 2.0), rng.uniform(0.002, 0.2));
    const Vec3 L = normalize(rng.vec(1)), V = normalize(rng.vec(1));
    const AffineField E{rng.vec(0.01), rng.vec(0.01), rng.vec(2) + Vec3{0, 0, 3}};
    for (int k = 0; k < 10; ++k) {
      const double x = fc.xc + rng.uniform(-5, 5), y = fc.yc + rng.uniform(-5, 5);
      const Vec3 n = fc.abs.at(x, y), e = E.at(x, y);
      EXPECT_NEAR(phong_exact_infinite(fc.abs, L, V, x, y), phong_closed_form(n, L, V), 1e-14);
      EXPECT_NEAR(phong_exact_finite(fc.abs, E, L, x, y), phong_closed_form(n, L, e / length(e)),
                  1e-14);
    }
  }
  // Known directions: the mirror direction gives 1; looking back along a light 45 degrees off the
  // normal, R is perpendicular to V; light along the normal and eye opposite it give -1.
  const Vec3 n{0, 0, 2}, L = normalize(Vec3{1, 0, 1});
  EXPECT_NEAR(phong_cosine(n, L, normalize(Vec3{-1, 0, 1})), 1.0, 1e-15);
  EXPECT_NEAR(phong_cosine(n, L, -L), 0.0, 1e-15);
  EXPECT_NEAR(phong_cosine(n, Vec3{0, 0, 1}, Vec3{0, 0, -3}), -1.0, 1e-15);
  EXPECT_EQ(phong_cosine(Vec3{}, L, L), 0.0);
  EXPECT_EQ(phong_cosine(n, L, Vec3{}), 0.0);
}

// Independent closed form of the infinite-eye Phong quadratic: with N = A x' + B y' + C about the
// centre, P = (N.L)(N.V) and Q = N.N are quadratics with coefficients read off by hand, and the
// second-order series of P / Q is the power-series quotient r = (p - r q) / q0 term by term.
std::array<double, 6> closed_phong_infinite(Vec3 A, Vec3 B, Vec3 C, Vec3 L, Vec3 V) {
  const double a = dot(A, L), b = dot(B, L), c = dot(C, L);     // N.L = a x + b y + c
  const double a2 = dot(A, V), b2 = dot(B, V), c2 = dot(C, V);  // N.V
  const double p0 = c * c2, px = a * c2 + a2 * c, py = b * c2 + b2 * c;
  const double pxx = a * a2, pxy = a * b2 + a2 * b, pyy = b * b2;
  const double q0 = dot(C, C), qx = 2 * dot(A, C), qy = 2 * dot(B, C);
  const double qxx = dot(A, A), qxy = 2 * dot(A, B), qyy = dot(B, B);
  const double r0 = p0 / q0;
  const double rx = (px - r0 * qx) / q0, ry = (py - r0 * qy) / q0;
  const double rxx = (pxx - r0 * qxx - rx * qx) / q0;
  const double rxy = (pxy - r0 * qxy - rx * qy - ry * qx) / q0;
  const double ryy = (pyy - r0 * qyy - ry * qy) / q0;
  // Bishop order: T0, y, x, y^2, xy, x^2.
  return {2 * r0 - dot(L, V), 2 * ry, 2 * rx, 2 * ryy, 2 * rxy, 2 * rxx};
}

TEST(PhongClosedForm, InfiniteEyeQuadraticMatchesPowerSeriesQuotient) {
  Rng rng;
  for (int trial = 0; trial < 300; ++trial) {
    const double rate = rng.uniform(0.002, 0.3);
    const FieldCase fc = random_field(rng, normalize(rng.vec(1)) * rng.uniform(0.5, 2.0), rate);
    const Vec3 L = normalize(rng.vec(1)), V = normalize(rng.vec(1));
    const Quadratic q = taylor_phong_infinite(fc.abs, L, V, fc.xc, fc.yc);
    EXPECT_EQ(q.xc, fc.xc);
    EXPECT_EQ(q.yc, fc.yc);
    expect_matches_closed(q, closed_phong_infinite(fc.A, fc.B, fc.C, L, V), fc.rate);
  }
}

TEST(PhongClosedForm, ConstantNormalAndEyeGiveAConstantSeries) {
  // A flat face seen from infinity: R.V is the same at every pixel, and equals the closed form.
  const AffineField N{{0, 0, 0}, {0, 0, 0}, {0.2, 0.1, 1.3}};
  const Vec3 L = normalize(Vec3{0.4, 0.5, 1}), V{0, 0, 1};
  const Quadratic q = taylor_phong_infinite(N, L, V, 40, 70);
  EXPECT_NEAR(q.t[0], phong_closed_form(N.c, L, V), 1e-15);
  for (int k = 1; k < 6; ++k) EXPECT_EQ(q.t[k], 0.0) << "T" << k;
}

TEST(PhongFiniteDifferences, EyeAtInfinity) {
  Rng rng;
  for (int trial = 0; trial < 200; ++trial) {
    const FieldCase fc = random_field(rng, normalize(rng.vec(1)), rng.uniform(0.002, 0.2));
    const Vec3 L = normalize(rng.vec(1)), V = normalize(rng.vec(1));
    const Quadratic q = taylor_phong_infinite(fc.abs, L, V, fc.xc, fc.yc);
    // R.V = 2 (N^.L)(N^.V) - L.V has the same singularities as N^.L, with |f| <= 2 * 2 * 2 + 1
    // where the diffuse bound has 2: the same bound with the rate doubled multiplies every
    // truncation term by at least 2^3, which covers it.
    expect_matches_finite_differences(
        q, [&](double x, double y) { return phong_exact_infinite(fc.abs, L, V, x, y); },
        2 * fc.rate);
  }
}

TEST(PhongFiniteDifferences, FiniteEye) {
  Rng rng;
  for (int trial = 0; trial < 200; ++trial) {
    const double rate = rng.uniform(0.002, 0.1);
    const FieldCase fc = random_field(rng, normalize(rng.vec(1)), rate);
    const Vec3 L = normalize(rng.vec(1));
    const Vec3 D = normalize(rng.vec(1)) * (rate / 4), Ey = normalize(rng.vec(1)) * (rate / 4);
    const AffineField E{D, Ey, normalize(rng.vec(1)) - D * fc.xc - Ey * fc.yc};
    const Quadratic q = taylor_phong_finite(fc.abs, E, L, fc.xc, fc.yc);
    expect_matches_finite_differences(
        q, [&](double x, double y) { return phong_exact_finite(fc.abs, E, L, x, y); },
        2 * (fc.rate + rate));
  }
}

TEST(Quadratic, RecentredIsTheSamePolynomial) {
  Rng rng;
  for (int trial = 0; trial < 100; ++trial) {
    Quadratic q;
    q.xc = rng.uniform(0, 1000);
    q.yc = rng.uniform(0, 1000);
    for (double& t : q.t) t = rng.uniform(-1, 1) * 1e-2;
    const double x0 = std::floor(rng.uniform(0, 1000)), y0 = std::floor(rng.uniform(0, 1000));
    const Quadratic r = q.recentred(x0, y0);
    EXPECT_EQ(r.xc, x0);
    EXPECT_EQ(r.yc, y0);
    for (int k = 0; k < 20; ++k) {
      const double x = rng.uniform(0, 1000), y = rng.uniform(0, 1000);
      const double expect = q.eval(x, y);
      // Terms reach ~1e-2 * 1000^2 = 1e4; 1e4 * a few eps.
      EXPECT_NEAR(r.eval(x, y), expect, 1e4 * 16 * kEps);
    }
  }
}

TEST(Quadratic, EvalUsesBishopOrder) {
  Quadratic q;
  q.xc = 10;
  q.yc = 20;
  const double t[6] = {1, 2, 3, 4, 5, 6};
  for (int k = 0; k < 6; ++k) q.t[k] = t[k];
  // u = 2, v = -1: 1 + 2(-1) + 3(2) + 4(1) + 5(2)(-1) + 6(4) = 23
  EXPECT_DOUBLE_EQ(q.eval(12, 19), 23.0);
}

TEST(AffineField, InterpolatesVerticesAndRejectsDegenerate) {
  std::array<ScreenVertex, 3> v;
  v[0].x = 10;
  v[0].y = 5;
  v[0].normal = {0, 0, 1};
  v[1].x = 40;
  v[1].y = 9;
  v[1].normal = {0.5, 0, 1};
  v[2].x = 22;
  v[2].y = 37;
  v[2].normal = {0, -0.25, 2};
  const auto f = affine_field(v, &ScreenVertex::normal);
  ASSERT_TRUE(f.has_value());
  for (const auto& vx : v) {
    const Vec3 got = f->at(vx.x, vx.y);
    EXPECT_NEAR(got.x, vx.normal.x, 1e-14);
    EXPECT_NEAR(got.y, vx.normal.y, 1e-14);
    EXPECT_NEAR(got.z, vx.normal.z, 1e-14);
  }
  v[2].x = 70;
  v[2].y = 13;  // on the line through v0 and v1
  EXPECT_FALSE(affine_field(v, &ScreenVertex::normal).has_value());
  v[2].x = std::nan("");
  EXPECT_FALSE(affine_field(v, &ScreenVertex::normal).has_value());
}

}  // namespace
}  // namespace shadesim
