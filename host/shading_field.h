// Screen-affine vector fields over a triangle and the exact shading functions Bishop & Weimer
// approximate. Everything is in absolute screen coordinates (pixels, y down).
#pragma once

#include <array>
#include <optional>

#include "host/scene.h"
#include "host/screen.h"
#include "host/vec3.h"

namespace shadesim {

// F(x, y) = a x + b y + c: Bishop's N = A x + B y + C. Deliberately affine in screen space, not
// perspective-correct: it is the function the hardware approximates and the reference renders.
struct AffineField {
  Vec3 a, b, c;
  Vec3 at(double x, double y) const { return a * x + b * y + c; }
};

// The field taking the value v[i].*member at (v[i].x, v[i].y). Returns std::nullopt when the
// vertices are collinear or not finite: |twice the area| <= 1e-14 * (longest edge)^2, where no
// unique field exists (such a triangle covers no pixel centre). No exception: callers decide.
std::optional<AffineField> affine_field(const std::array<ScreenVertex, 3>& v,
                                        Vec3 ScreenVertex::*member);
inline std::optional<AffineField> normal_field(const ScreenTriangle& t) {
  return affine_field(t.v, &ScreenVertex::normal);
}
inline std::optional<AffineField> eye_field(const ScreenTriangle& t) {
  return affine_field(t.v, &ScreenVertex::to_eye);
}

// Exact shading cosines at (x, y). Not clamped (Taylor series and reference clamp later).
// Where |N| (or |H|) is zero the cosine is defined as 0 rather than NaN.
// Diffuse: N.L / |N|, L unit toward the light.
double diffuse_exact(const AffineField& N, Vec3 L, double x, double y);
// Blinn specular, eye at infinity: N.H / |N| with H the unit half vector (used as given).
double specular_exact_infinite(const AffineField& N, Vec3 H, double x, double y);
// Bishop's finite eye: N.H / (|N| |H|) with H(x, y) = E(x, y) + L, E the affine to-eye field.
double specular_exact_finite(const AffineField& N, const AffineField& E, Vec3 L, double x,
                             double y);

// Phong specular: R.V with R = 2 (N^.L) N^ - L the unit light direction reflected about the unit
// normal N^ = N / |N|, and V the unit vector toward the eye. Computed through R itself (the
// closed form 2 (N.L)(N.V) / |N|^2 - L.V is what the tests check it against).
// At a point: n the normal (any length), v toward the eye (any length). 0 where |n| or |v| is 0.
double phong_cosine(Vec3 n, Vec3 L, Vec3 v);
// Eye at infinity: V unit and constant.
double phong_exact_infinite(const AffineField& N, Vec3 L, Vec3 V, double x, double y);
// Finite eye: V = E / |E|, E the affine to-eye field.
double phong_exact_finite(const AffineField& N, const AffineField& E, Vec3 L, double x, double y);

// Unit vector toward an eye at infinity: minus the view direction (orthographic, or the usual
// infinite-viewer approximation for perspective).
Vec3 eye_direction_at_infinity(const Camera& camera);
// normalize(L + V); the zero vector when L = -V (then the specular cosine is 0 everywhere).
Vec3 half_vector(Vec3 L, Vec3 V);

}  // namespace shadesim
