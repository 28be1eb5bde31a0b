// Triangles after projection, and the visibility result: who owns each pixel, as spans.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "host/vec3.h"

namespace shadesim {

// Pixel (px, py) has its centre at (px + 0.5, py + 0.5). Screen y grows downward.
struct ScreenVertex {
  double x = 0, y = 0;  // pixel coordinates, on the 2^-kSubpixelBits grid (midpoints add bits)
  double z = 0;         // depth, smaller is nearer; affine in screen space
  // Values of the screen-affine fields at this vertex. At mesh vertices these are unit vectors;
  // at subdivision midpoints they are the averages of their endpoints (not renormalised), so the
  // field a sub-triangle interpolates is exactly its parent's.
  Vec3 normal;  // interpolated surface normal N(x, y)
  Vec3 to_eye;  // unit vector toward the eye at mesh vertices (finite-eye specular)
};

constexpr int kSubpixelBits = 8;

struct ScreenTriangle {
  std::array<ScreenVertex, 3> v;
  int material = 0;
  int object = 0;
  int parent = -1;  // index of the projected triangle this one was subdivided from (-1: itself)
};

// A run of pixels on one row owned by one triangle.
struct Span {
  int y = 0;
  int x0 = 0;
  int length = 0;
  uint32_t triangle = 0;
  bool last_in_row = false;  // last span of row y in stream order
};

struct Visibility {
  int width = 0, height = 0;
  std::vector<int32_t> owner;  // width*height, triangle index or -1
  // Grouped by triangle in ascending index, within a triangle by y then x0. Every owned pixel is
  // in exactly one span.
  std::vector<Span> spans;
};

}  // namespace shadesim
