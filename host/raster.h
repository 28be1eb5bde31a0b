// Projection of a scene to screen triangles, and exact rasterization / visibility into spans.
#pragma once

#include <cstdint>
#include <vector>

#include "host/scene.h"
#include "host/screen.h"

namespace shadesim {

// What became of the mesh triangles. A triangle wholly in front of the near plane, and each piece
// of a clipped one, is a candidate that ends as exactly one of culled_back_face,
// dropped_out_of_range or emitted:
//   triangles_in - culled_near - clipped_near + clipped_pieces
//     == culled_back_face + dropped_out_of_range + emitted.
struct ProjectStats {
  int64_t triangles_in = 0;          // mesh triangles of all objects
  int64_t culled_near = 0;           // every vertex nearer than the near plane: nothing to draw
  int64_t clipped_near = 0;          // crossing the near plane: clipped to it and the guard band
  int64_t clipped_pieces = 0;        // triangles the clipping made (0 to 6 per clipped triangle)
  int64_t culled_back_face = 0;      // clockwise-from-outside on screen, or zero screen area
  int64_t dropped_out_of_range = 0;  // a vertex beyond kMaxScreenCoordinate
  int64_t emitted = 0;
};

// Screen coordinates must stay within +-kMaxScreenCoordinate pixels so edge functions are exact.
constexpr double kMaxScreenCoordinate = double(1 << 28);
// A triangle crossing the near plane is also clipped to a guard band this many pixels beyond every
// image edge: its clip points can land thousands of pixels off-screen, where the screen-affine
// fields of a triangle whose vertices lie at very different depths vary fast and far from the
// true ones, and the Taylor subdivision would spend its depth on pixels nobody sees. Triangles
// wholly in front of the near plane are not clipped (they keep the unclipped affine fields).
constexpr double kGuardBandPixels = 256;
// Rasterization works on integers in units of 2^-kRasterFractionBits pixels: kSubpixelBits of the
// snapped vertices plus up to 16 halvings by subdivision midpoints.
constexpr int kRasterFractionBits = 24;

// World -> camera -> screen (y down, pixel centres at +0.5). A triangle crossing the near plane
// is clipped in view space to it and to the guard band (up to 6 triangles; at the new vertices
// the normal is interpolated along the edge and renormalised, the to-eye vector taken at the
// interpolated point); one wholly nearer than the near plane is culled.
// Perspective: z = far(d - near) / (d (far - near)), affine in screen space, 0 at the near plane;
// orthographic: z = view depth d.
// x and y are rounded to the 2^-kSubpixelBits grid before back-face culling, so the cull decision
// is the exact sign of the snapped triangle's area. Emitted triangles keep the mesh winding
// (counter-clockwise from outside, which is clockwise on the y-down screen). `stats` may be null.
std::vector<ScreenTriangle> project_scene(const Scene& scene, ProjectStats* stats);

// Pixel rows covered by one triangle: pixel centres inside it by the top-left fill rule
// (a centre on an edge belongs to the triangle if the edge is a top edge — horizontal, interior
// below — or a left edge — interior to its right). Either winding is accepted. Only pixels within
// [0, width) x [0, height) are reported. Throws std::logic_error if a vertex x or y is not on the
// 2^-kRasterFractionBits grid or exceeds kMaxScreenCoordinate.
struct CoveredRow {
  int y = 0;
  int x_begin = 0;  // first covered pixel
  int x_end = 0;    // one past the last
};
std::vector<CoveredRow> covered_rows(const ScreenTriangle& triangle, int width, int height);

// Z-buffer at pixel centres over the triangles in index order: the nearest triangle owns the
// pixel; on equal depth the lower index wins. Then runs of equal owner along each row become
// spans, grouped by triangle ascending, within a triangle by y then x0; the span of each row that
// comes last in that order has last_in_row set.
Visibility resolve_visibility(const std::vector<ScreenTriangle>& triangles, int width, int height);

}  // namespace shadesim
