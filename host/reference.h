// The float reference: double-precision shading per pixel with per-pixel normalisation and exact
// pow, over the same triangles and visibility the model shades. Ground truth for error figures.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "host/scene.h"
#include "host/screen.h"
#include "host/triangle_setup.h"

namespace shadesim {

struct ReferenceImage {
  int width = 0, height = 0, channels = 0;
  std::vector<double> values;  // row-major, channels interleaved: ((y * width) + x) * channels + c

  double at(int x, int y, int c) const {
    return values[(static_cast<std::size_t>(y) * width + x) * channels + c];
  }
};

// Per owned pixel, at its centre (px + 0.5, py + 0.5), with N and the to-eye vector E interpolated
// affinely in screen space from the owner's vertices (the same fields the Taylor series expand):
//   colour = clamp01(ambient_mat * ambient_light
//                    + sum_l kd * Lc * max(0, N.L / |N|) + [N.L > 0] ks * Lc * max(0, N.H / |N|)^n)
// with L = normalize(light.direction), H = normalize(L + V) (eye at infinity, V toward the eye
// from the camera) or normalize(E + L) (finite eye). A material whose specular_model is phong
// uses R.V in place of N.H: R = 2 (N^.L) N^ - L with N^ = N / |N|, and V as above (eye at
// infinity) or E / |E| (finite eye). Specular is gated by N.L > 0 ([N.L > 0] is 1 there, else
// 0), as the hardware gates it (model/pixel_combine.h). A zero |N| or |H| gives a zero term.
// Pixels with owner -1 are 0. channels 1 uses the first (x, red) component of every colour.
// Throws std::invalid_argument when channels is not 1 or 3, owner.size() != width * height, an
// owner index is out of range, or a material index is not in scene.materials.
ReferenceImage render_reference(const std::vector<ScreenTriangle>& triangles,
                                const std::vector<int32_t>& owner, int width, int height,
                                const Scene& scene, int channels);

inline ReferenceImage render_reference(const std::vector<ScreenTriangle>& triangles,
                                       const Visibility& vis, const Scene& scene, int channels) {
  return render_reference(triangles, vis.owner, vis.width, vis.height, scene, channels);
}

// The same double-precision shading with one or both of its ingredients swapped, so an error can
// be split by source (explore's error budget): the cosines from the owner's Taylor quadratics
// instead of the exact per-pixel ones, and the specular function of a hardware unit instead of pow.
struct ShadingVariant {
  // Parallel to the triangles: their quadratics (host/triangle_setup.h). nullptr: exact cosines.
  // With quadratics, diffuse is max(0, q_d) per light, the specular gate q_d > 0 and the specular
  // argument q_s, unclamped.
  const std::vector<TriangleSeries>* quadratics = nullptr;
  // Per material index, f(t) replacing max(0, t)^n (it must clamp t itself). Empty: pow.
  std::vector<std::function<double(double)>> specular;
  // Parallel to the triangles: the specular gate from these quadratics' N.L (q_d > 0), as the
  // unit gates it, with every cosine otherwise as set above. nullptr: the gate from the cosine
  // the shading uses. What a miss at the terminator owes to the gate alone (derive/miss_causes).
  const std::vector<TriangleSeries>* gate_quadratics = nullptr;
};

// render_reference with `variant`; the default variant gives render_reference's image exactly.
// Throws std::invalid_argument as render_reference does, and when variant.quadratics or
// variant.specular do not match the triangles or the materials in size.
ReferenceImage render_variant(const std::vector<ScreenTriangle>& triangles, const Visibility& vis,
                              const Scene& scene, int channels, const ShadingVariant& variant);

}  // namespace shadesim
