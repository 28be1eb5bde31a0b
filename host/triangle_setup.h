// Triangle setup: per-light Taylor quadratics of the shading cosines, the approximation error
// they cause in the output image (measured, not predicted), and subdivision until it fits a budget.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "host/scene.h"
#include "host/screen.h"
#include "host/taylor.h"

namespace shadesim {

// The t series of one triangle, one entry per scene light in scene order, all about the triangle
// centroid. Channel-independent cosines: colour scaling (and ambient) is left to the encoder.
struct TriangleSeries {
  std::vector<Quadratic> diffuse;  // N.L / |N|
  // Blinn: N.H / |N| (eye at infinity) or N.H / (|N||H|) (finite eye). Phong (the material's
  // specular_model): R.V, V constant (eye at infinity) or E / |E| (finite eye).
  std::vector<Quadratic> specular;
  // Collinear vertices: no field exists. Quadratics are all zero and the error is 0 (such a
  // triangle covers no pixel centre).
  bool degenerate = false;
};

struct SetupOptions {
  std::optional<double> budget_lsb;  // unset: scene.error_budget_lsb
  int max_depth = 12;                // splits per input triangle along one path (grid: 2^-(8+12))
  int output_bits = 8;               // 1 LSB = 2^-output_bits of full scale
  // true: colour uses max(0, q_d) per light, as the reference does. false: the diffuse quadratics
  // are summed unclamped (what a model that rolls all lights and ambient into one series computes),
  // so errors at the terminator are measured, not hidden.
  bool diffuse_clamped_per_light = true;
};

struct SetupStats {
  std::size_t triangles_in = 0;
  std::size_t triangles_out = 0;
  std::size_t splits = 0;        // split operations; each turns one triangle into two
  std::size_t inputs_split = 0;  // input triangles split at least once
  std::size_t over_budget = 0;   // output triangles still over budget (at max depth)
  std::size_t degenerate = 0;    // output triangles with no field
  int max_depth_reached = 0;
  double worst_error_lsb = 0.0;  // over output triangles; +inf if a series was not finite
};

struct SetupResult {
  // Output triangles grouped by input triangle in input order: those of input i are
  // [first_out[i], first_out[i + 1]). An unsplit triangle is copied unchanged; a child has
  // parent = input's parent if set, else the input index.
  std::vector<ScreenTriangle> triangles;
  std::vector<TriangleSeries> series;  // parallel to triangles
  std::vector<double> error_lsb;       // parallel to triangles: measured max error, output LSBs
  std::vector<std::size_t> first_out;  // size triangles_in + 1
  SetupStats stats;
};

// Quadratics of one triangle for every light of the scene. Throws std::invalid_argument when the
// triangle's material index is not in scene.materials.
TriangleSeries setup_triangle(const ScreenTriangle& tri, const Scene& scene);

// Max over the pixel centres the closed triangle covers inside the scene.width x scene.height
// image (a superset of what a half-open rasterizer gives it, so an upper bound), over channels,
// of |colour(quadratics) - colour(exact cosines)| * 2^output_bits, where
//   colour = clamp01(ambient_mat * ambient_light
//                    + sum_l kd * Lc * max(0, t_d) + [t_d > 0] ks * Lc * clamp01(t_s)^n),
// t_s the material's specular cosine (Blinn's N.H or Phong's R.V); the specular gate [t_d > 0]
// is taken from each side's own t_d (quadratic or exact), so a sign flip near the terminator
// counts as error.
// Returns 0 when no centre is covered, +inf when a value is not finite. Stops early, returning a
// value above stop_above, as soon as one pixel exceeds it.
double measure_error_lsb(const ScreenTriangle& tri, const TriangleSeries& series,
                         const Scene& scene, const SetupOptions& opt,
                         double stop_above = std::numeric_limits<double>::infinity());

// Sets up every triangle, splitting at the midpoint of the longest edge (the exact average of the
// endpoints' x, y, z, normal and to_eye, so the fields are unchanged) while the measured error
// exceeds the budget and depth < max_depth. Throws std::invalid_argument on bad options or a bad
// material index, naming the triangle.
SetupResult subdivide_and_setup(const std::vector<ScreenTriangle>& in, const Scene& scene,
                                const SetupOptions& opt = SetupOptions());

}  // namespace shadesim
