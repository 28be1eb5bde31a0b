// The exponent equivalence between Phong's (R.V)^n and Blinn's (N.H)^m, measured: for a light L
// and an eye V at angle 2b, the Blinn exponent m that best matches a Phong lobe of exponent n in
// least squares over the normals around H (solid-angle measure). Prints the table
// (`ctest --test-dir build -R PhongBlinn -V`).
//
// Small-angle expectation the assertions use: with N at angle a from H, R.V = cos 2a exactly when
// N tilts in the plane of L and V, and R.V = 1 - 2 cos^2 b sin^2 a when it tilts across it, while
// N.H = cos a. So (R.V)^n ~ exp(-2 n a^2) in the plane, exp(-2 n cos^2 b a^2) across it, and
// (N.H)^m ~ exp(-m a^2 / 2): m = 4 n for L = V (b = 0), and m between 4 n cos^2 b and 4 n
// otherwise, each up to O(1/n) from the fourth-order terms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "host/vec3.h"

namespace shadesim {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Lobes {
  std::vector<double> weight, phong, cos_h;  // per sample normal
};

// Normals N = cos a H + sin a (cos p P1 + sin p P2), P1 in the plane of L and V, on a midpoint
// grid in a in [0, a_max] and p in [0, 2 pi), weight sin a (the solid angle). a_max = 12 / sqrt(n)
// (at most pi / 2): there both lobes are below e^-18 for every b <= 60 degrees and m >= n / 2.
Lobes sample(double n, double half_angle) {
  const Vec3 H{0, 0, 1}, P1{1, 0, 0}, P2{0, 1, 0};
  const Vec3 L{std::sin(half_angle), 0, std::cos(half_angle)};
  const Vec3 V{-std::sin(half_angle), 0, std::cos(half_angle)};
  const double a_max = std::min(kPi / 2, 12 / std::sqrt(n));
  constexpr int kA = 400, kP = 64;
  Lobes s;
  for (int i = 0; i < kA; ++i) {
    const double a = (i + 0.5) * a_max / kA;
    for (int j = 0; j < kP; ++j) {
      const double p = (j + 0.5) * 2 * kPi / kP;
      const Vec3 N = H * std::cos(a) + (P1 * std::cos(p) + P2 * std::sin(p)) * std::sin(a);
      const double r_dot_v = 2 * dot(N, L) * dot(N, V) - dot(L, V);  // closed form, |N| = 1
      s.weight.push_back(std::sin(a));
      s.phong.push_back(std::pow(std::max(0.0, r_dot_v), n));
      s.cos_h.push_back(dot(N, H));
    }
  }
  return s;
}

double squared_error(const Lobes& s, double m) {
  double e = 0;
  for (size_t k = 0; k < s.weight.size(); ++k) {
    const double d = s.phong[k] - std::pow(std::max(0.0, s.cos_h[k]), m);
    e += s.weight[k] * d * d;
  }
  return e;
}

double max_difference(const Lobes& s, double m) {
  double e = 0;
  for (size_t k = 0; k < s.weight.size(); ++k)
    e = std::max(e, std::fabs(s.phong[k] - std::pow(std::max(0.0, s.cos_h[k]), m)));
  return e;
}

// Golden-section search for the least-squares m in [n / 2, 8 n], on log m.
double fit_blinn_exponent(const Lobes& s, double n) {
  double lo = std::log(n / 2), hi = std::log(8 * n);
  const double g = (std::sqrt(5.0) - 1) / 2;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = squared_error(s, std::exp(x1)), f2 = squared_error(s, std::exp(x2));
  while (hi - lo > 1e-7) {
    if (f1 < f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = squared_error(s, std::exp(x1));
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = squared_error(s, std::exp(x2));
    }
  }
  return std::exp((lo + hi) / 2);
}

TEST(PhongBlinnExponent, MeasuredRatioIsFourForLEqualsVAndBetweenFourCos2bAndFourOtherwise) {
  const double exponents[] = {2, 5, 10, 20, 60, 250};
  const double angles_deg[] = {0, 30, 60, 90, 120};  // between L and V: 2b
  std::printf(
      "Blinn exponent m best matching a Phong lobe of exponent n (least squares over the\n"
      "normals around H, solid-angle weight); m/n, and the largest lobe difference at that\n"
      "m in 8-bit LSBs of a full-scale highlight\n");
  std::printf("%8s", "n \\ L.V");
  for (double a : angles_deg) std::printf("  %9.0f deg       ", a);
  std::printf("\n");
  for (double n : exponents) {
    std::printf("%8g", n);
    for (double angle : angles_deg) {
      const double b = angle * kPi / 360;
      const Lobes s = sample(n, b);
      const double m = fit_blinn_exponent(s, n);
      const double ratio = m / n;
      std::printf("  m/n %5.3f (%5.1f LSB)", ratio, max_difference(s, m) * 255);
      // The fit is interior to the search range, so it is a minimum, not a clamp.
      EXPECT_GT(m, n / 2 * 1.01);
      EXPECT_LT(m, 8 * n * 0.99);
      if (n >= 60) {
        const double cos2b = std::cos(b) * std::cos(b);
        if (angle == 0) {
          EXPECT_NEAR(ratio, 4.0, 0.05) << "n " << n;
        } else {
          EXPECT_GT(ratio, 4 * cos2b * 0.98) << "n " << n << ", L.V angle " << angle;
          EXPECT_LT(ratio, 4 * 1.02) << "n " << n << ", L.V angle " << angle;
        }
      }
    }
    std::printf("\n");
  }
}

}  // namespace
}  // namespace shadesim
