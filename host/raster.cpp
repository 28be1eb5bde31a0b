#include "host/raster.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace shadesim {
namespace {

using Int128 = __int128;

constexpr double kPi = 3.14159265358979323846;
constexpr int64_t kOne = int64_t{1} << kRasterFractionBits;  // one pixel in raster units
constexpr int64_t kHalf = kOne / 2;                          // offset of a pixel centre

// floor(a / b) and ceil(a / b) for b > 0.
Int128 floor_div(Int128 a, Int128 b) {
  Int128 q = a / b;
  if (a % b != 0 && a < 0) --q;
  return q;
}
Int128 ceil_div(Int128 a, Int128 b) { return -floor_div(-a, b); }

int64_t to_raster_units(double v, const char* axis, int vertex) {
  if (!std::isfinite(v) || std::fabs(v) > kMaxScreenCoordinate) {
    throw std::logic_error(std::string("rasterizer: vertex ") + std::to_string(vertex) + " " +
                           axis + " = " + std::to_string(v) +
                           " is not a finite screen coordinate within +-2^28");
  }
  const double scaled = std::ldexp(v, kRasterFractionBits);  // exact: a power-of-two scale
  if (scaled != std::floor(scaled)) {
    throw std::logic_error(std::string("rasterizer: vertex ") + std::to_string(vertex) + " " +
                           axis + " is not on the 2^-" + std::to_string(kRasterFractionBits) +
                           " pixel grid");
  }
  return static_cast<int64_t>(scaled);
}

// Calls row(y, x_begin, x_end, z_at_x_begin, dz_dx) for each non-empty covered row, top to bottom.
template <typename RowFn>
void rasterize(const ScreenTriangle& triangle, int width, int height, RowFn&& row) {
  int64_t x[3], y[3];
  double z[3];
  for (int i = 0; i < 3; ++i) {
    x[i] = to_raster_units(triangle.v[i].x, "x", i);
    y[i] = to_raster_units(triangle.v[i].y, "y", i);
    z[i] = triangle.v[i].z;
  }
  // Twice the signed area; the interior is where all three edge functions are positive.
  Int128 area = Int128(x[1] - x[0]) * (y[2] - y[0]) - Int128(y[1] - y[0]) * (x[2] - x[0]);
  if (area == 0) return;
  if (area < 0) {
    std::swap(x[1], x[2]);
    std::swap(y[1], y[2]);
    std::swap(z[1], z[2]);
    area = -area;
  }
  // Edge i runs from vertex i to vertex i+1: E_i(P) = dx (Py - ay) - dy (Px - ax), whose gradient
  // (-dy, dx) points inward. A centre exactly on the edge (E = 0) counts only for a left edge
  // (inward normal toward +x: dy < 0) or a top edge (horizontal, inward toward +y: dy == 0, dx >
  // 0).
  int64_t edge_dx[3], edge_dy[3], threshold[3];
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    edge_dx[i] = x[j] - x[i];
    edge_dy[i] = y[j] - y[i];
    const bool top_left = edge_dy[i] < 0 || (edge_dy[i] == 0 && edge_dx[i] > 0);
    threshold[i] = top_left ? 0 : 1;
  }
  // Vertex opposite edge i is i+2; its barycentric weight is E_i / area.
  const double inv_area = 1.0 / static_cast<double>(area);
  double dz_dx = 0;
  for (int i = 0; i < 3; ++i) dz_dx += z[(i + 2) % 3] * static_cast<double>(-edge_dy[i]) * kOne;
  dz_dx *= inv_area;

  const int64_t min_x = std::min({x[0], x[1], x[2]}), max_x = std::max({x[0], x[1], x[2]});
  const int64_t min_y = std::min({y[0], y[1], y[2]}), max_y = std::max({y[0], y[1], y[2]});
  // Pixels whose centre lies within the bounding box, clipped to the screen.
  const int64_t px_lo = std::max<int64_t>(0, static_cast<int64_t>(ceil_div(min_x - kHalf, kOne)));
  const int64_t px_hi =
      std::min<int64_t>(width - 1, static_cast<int64_t>(floor_div(max_x - kHalf, kOne)));
  const int64_t py_lo = std::max<int64_t>(0, static_cast<int64_t>(ceil_div(min_y - kHalf, kOne)));
  const int64_t py_hi =
      std::min<int64_t>(height - 1, static_cast<int64_t>(floor_div(max_y - kHalf, kOne)));
  if (px_lo > px_hi) return;

  const int64_t centre_x0 = px_lo * kOne + kHalf;
  for (int64_t py = py_lo; py <= py_hi; ++py) {
    const int64_t centre_y = py * kOne + kHalf;
    Int128 lo = px_lo, hi = px_hi;  // inclusive
    Int128 e_at_lo[3];
    bool empty = false;
    for (int i = 0; i < 3 && !empty; ++i) {
      const Int128 e0 =
          Int128(edge_dx[i]) * (centre_y - y[i]) - Int128(edge_dy[i]) * (centre_x0 - x[i]);
      e_at_lo[i] = e0;
      // E_i(px_lo + k) = e0 + k * step must reach threshold[i].
      const Int128 step = -Int128(edge_dy[i]) * kOne;
      const Int128 need = threshold[i] - e0;
      if (step > 0) {
        lo = std::max(lo, px_lo + ceil_div(need, step));
      } else if (step < 0) {
        hi = std::min(hi, px_lo + floor_div(-need, -step));
      } else if (need > 0) {
        empty = true;
      }
    }
    if (empty || lo > hi) continue;
    double z_lo = 0;
    for (int i = 0; i < 3; ++i) z_lo += z[(i + 2) % 3] * static_cast<double>(e_at_lo[i]);
    z_lo = z_lo * inv_area + dz_dx * static_cast<double>(lo - px_lo);
    row(static_cast<int>(py), static_cast<int>(lo), static_cast<int>(hi) + 1, z_lo, dz_dx);
  }
}

struct ViewBasis {
  Vec3 right, up, forward;
};

ViewBasis view_basis(const Camera& camera) {
  ViewBasis b;
  b.forward = normalize(camera.target - camera.position);
  b.right = normalize(cross(b.forward, camera.up));
  b.up = cross(b.right, b.forward);
  return b;
}

// A mesh vertex (or a near-plane clip point) before projection: view-space coordinates and the
// attributes the screen vertex carries.
struct ViewPoint {
  double right = 0, up = 0, depth = 0;  // view coordinates; depth along the view direction
  Vec3 world;                           // for the to-eye vector
  Vec3 normal;
};

struct ProjectedVertex {
  ScreenVertex screen;
  bool behind_near = false;
  bool out_of_range = false;
};

constexpr int kClipPlanes = 5;  // the near plane and the four sides of the guard band

double snap(double v) {
  constexpr double kGrid = double(1 << kSubpixelBits);
  return std::nearbyint(v * kGrid) / kGrid;
}

// A clipping plane in view space: a point is inside where r right + u up + d depth + c >= 0 (a
// NaN is outside). The near plane is depth - near >= 0; the guard-band planes pass through the
// eye (perspective) or are parallel to the view direction (orthographic).
struct ClipPlane {
  double r = 0, u = 0, d = 0, c = 0;
  bool is_near = false;
  double distance(const ViewPoint& p) const { return r * p.right + u * p.up + d * p.depth + c; }
  bool inside(const ViewPoint& p) const { return distance(p) >= 0; }
};

// Where the edge from `inside` to `outside` meets the plane. Always called with the inside end
// first, so the two triangles sharing an edge get bit-identical points and the clipped surface
// stays watertight. Attributes are interpolated along the 3D edge: the normal, renormalised like
// every mesh vertex normal; the to-eye vector follows from the interpolated position (normalising
// the interpolated unnormalised eye vectors gives the same).
ViewPoint plane_point(const ViewPoint& inside, const ViewPoint& outside, const ClipPlane& plane,
                      double near) {
  const double s_in = plane.distance(inside), s_out = plane.distance(outside);
  const double t = s_in / (s_in - s_out);
  auto lerp = [t](double a, double b) { return a + t * (b - a); };
  ViewPoint p;
  p.right = lerp(inside.right, outside.right);
  p.up = lerp(inside.up, outside.up);
  p.depth = plane.is_near ? near : lerp(inside.depth, outside.depth);  // exactly on the near plane
  p.world = inside.world + (outside.world - inside.world) * t;
  p.normal = normalize(inside.normal + (outside.normal - inside.normal) * t);
  return p;
}

// The camera's view of a scene: mesh vertices to view space and on to the screen, and the
// planes a triangle that crosses the near plane is clipped to.
class Projection {
 public:
  explicit Projection(const Scene& scene);
  ViewPoint view_point(const Vec3& position, const Vec3& normal) const;
  ProjectedVertex project(const ViewPoint& p) const;
  // Clips the convex polygon's `corners` points to each plane in turn (Sutherland-Hodgman),
  // keeping the vertex order (so the winding); returns the corners left.
  int clip(ViewPoint* polygon, int corners) const;

 private:
  const Scene& scene_;
  const Camera& camera_;
  const ViewBasis basis_;
  const bool perspective_;
  const double pixels_per_unit_;
  const double near_, far_;
  // The near plane, then the guard band, kGuardBandPixels beyond each image edge.
  ClipPlane planes_[kClipPlanes];
};

Projection::Projection(const Scene& scene)
    : scene_(scene),
      camera_(scene.camera),
      basis_(view_basis(camera_)),
      perspective_(camera_.kind == Camera::Kind::kPerspective),
      pixels_per_unit_(perspective_
                           ? (scene.height / 2.0) / std::tan(camera_.fov_y_deg * kPi / 360.0)
                           : scene.height / camera_.ortho_height),
      near_(camera_.near_plane),
      far_(camera_.far_plane) {
  const double gx = (scene.width / 2.0 + kGuardBandPixels) / pixels_per_unit_;
  const double gy = (scene.height / 2.0 + kGuardBandPixels) / pixels_per_unit_;
  const double gd = perspective_ ? 1.0 : 0.0, gc = perspective_ ? 0.0 : 1.0;
  const ClipPlane planes[kClipPlanes] = {
      {0, 0, 1, -near_, true},          {1, 0, gx * gd, gx * gc, false},  // right >= -gx (depth)
      {-1, 0, gx * gd, gx * gc, false},                                   // right <= gx (depth)
      {0, 1, gy * gd, gy * gc, false},                                    // up >= -gy (depth)
      {0, -1, gy * gd, gy * gc, false},                                   // up <= gy (depth)
  };
  std::copy(planes, planes + kClipPlanes, planes_);
}

ViewPoint Projection::view_point(const Vec3& position, const Vec3& normal) const {
  const Vec3 rel = position - camera_.position;
  ViewPoint p;
  p.right = dot(rel, basis_.right);
  p.up = dot(rel, basis_.up);
  p.depth = dot(rel, basis_.forward);
  p.world = position;
  p.normal = normal;
  return p;
}

ProjectedVertex Projection::project(const ViewPoint& p) const {
  ProjectedVertex pv;
  pv.behind_near = !(p.depth >= near_);
  if (pv.behind_near) return pv;
  const double scale = perspective_ ? pixels_per_unit_ / p.depth : pixels_per_unit_;
  pv.screen.x = snap(scene_.width / 2.0 + p.right * scale);
  pv.screen.y = snap(scene_.height / 2.0 - p.up * scale);
  pv.screen.z = perspective_ ? far_ * (p.depth - near_) / (p.depth * (far_ - near_)) : p.depth;
  pv.screen.normal = p.normal;
  pv.screen.to_eye = normalize(camera_.position - p.world);
  pv.out_of_range = !(std::fabs(pv.screen.x) <= kMaxScreenCoordinate &&
                      std::fabs(pv.screen.y) <= kMaxScreenCoordinate);
  return pv;
}

int Projection::clip(ViewPoint* polygon, int corners) const {
  ViewPoint next_polygon[3 + kClipPlanes];
  for (int q = 0; q < kClipPlanes && corners > 0; ++q) {
    const ClipPlane& plane = planes_[q];
    int kept = 0;
    for (int k = 0; k < corners; ++k) {
      const ViewPoint& cur = polygon[k];
      const ViewPoint& nxt = polygon[(k + 1) % corners];
      const bool cur_in = plane.inside(cur), nxt_in = plane.inside(nxt);
      if (cur_in) next_polygon[kept++] = cur;
      if (cur_in != nxt_in) {
        next_polygon[kept++] =
            cur_in ? plane_point(cur, nxt, plane, near_) : plane_point(nxt, cur, plane, near_);
      }
    }
    corners = kept;
    std::copy(next_polygon, next_polygon + kept, polygon);
  }
  return corners;
}

// The screen triangles of a scene, counted into ProjectStats as they are kept or dropped.
class TriangleSink {
 public:
  TriangleSink(ProjectStats& stats, std::vector<ScreenTriangle>& out) : s_(stats), out_(out) {}

  // One triangle wholly in front of the near plane: range check, back-face cull, emit.
  void emit(const ProjectedVertex& a, const ProjectedVertex& b, const ProjectedVertex& c,
            int material, int object) {
    if (a.out_of_range || b.out_of_range || c.out_of_range) {
      ++s_.dropped_out_of_range;
      return;
    }
    // Exact sign of the snapped area: counter-clockwise from outside is negative on a y-down
    // screen.
    constexpr double kGrid = double(1 << kSubpixelBits);
    auto grid = [](double v) { return static_cast<int64_t>(v * kGrid); };
    const int64_t ax = grid(a.screen.x), ay = grid(a.screen.y);
    const int64_t bx = grid(b.screen.x), by = grid(b.screen.y);
    const int64_t cx = grid(c.screen.x), cy = grid(c.screen.y);
    const Int128 area = Int128(bx - ax) * (cy - ay) - Int128(by - ay) * (cx - ax);
    if (area >= 0) {
      ++s_.culled_back_face;
      return;
    }
    ScreenTriangle st;
    st.v = {a.screen, b.screen, c.screen};
    st.material = material;
    st.object = object;
    st.parent = -1;
    out_.push_back(st);
    ++s_.emitted;
  }

 private:
  ProjectStats& s_;
  std::vector<ScreenTriangle>& out_;
};

// A triangle that crosses the near plane (or has a NaN depth, which counts as behind). Its clip
// points land up to (extent / near) pixels off-screen, so it is clipped to the guard band as
// well, then fanned into triangles.
void clip_and_emit(const Projection& projection, const ViewPoint (&corners)[3], int material,
                   int object, ProjectStats& s, TriangleSink& sink) {
  ++s.clipped_near;
  ViewPoint polygon[3 + kClipPlanes];
  std::copy(corners, corners + 3, polygon);
  const int n = projection.clip(polygon, 3);
  ProjectedVertex corner[3 + kClipPlanes];
  for (int k = 0; k < n; ++k) corner[k] = projection.project(polygon[k]);
  for (int k = 1; k + 1 < n; ++k) {
    ++s.clipped_pieces;
    sink.emit(corner[0], corner[k], corner[k + 1], material, object);
  }
}

void project_object(const Projection& projection, const Object& object, int object_id,
                    ProjectStats& s, TriangleSink& sink) {
  const Mesh& mesh = object.mesh;
  std::vector<ViewPoint> view(mesh.positions.size());
  std::vector<ProjectedVertex> projected(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    view[i] = projection.view_point(mesh.positions[i], mesh.normals[i]);
    projected[i] = projection.project(view[i]);
  }
  for (const auto& t : mesh.triangles) {
    ++s.triangles_in;
    const int behind = int(projected[t[0]].behind_near) + int(projected[t[1]].behind_near) +
                       int(projected[t[2]].behind_near);
    if (behind == 0) {
      sink.emit(projected[t[0]], projected[t[1]], projected[t[2]], object.material, object_id);
    } else if (behind == 3) {
      ++s.culled_near;
    } else {
      const ViewPoint corners[3] = {view[t[0]], view[t[1]], view[t[2]]};
      clip_and_emit(projection, corners, object.material, object_id, s, sink);
    }
  }
}

}  // namespace

std::vector<CoveredRow> covered_rows(const ScreenTriangle& triangle, int width, int height) {
  std::vector<CoveredRow> rows;
  rasterize(triangle, width, height, [&](int y, int x_begin, int x_end, double, double) {
    rows.push_back({y, x_begin, x_end});
  });
  return rows;
}

std::vector<ScreenTriangle> project_scene(const Scene& scene, ProjectStats* stats) {
  ProjectStats local;
  ProjectStats& s = stats ? *stats : local;
  s = ProjectStats{};
  const Projection projection(scene);
  std::vector<ScreenTriangle> out;
  TriangleSink sink(s, out);
  for (size_t object_index = 0; object_index < scene.objects.size(); ++object_index) {
    project_object(projection, scene.objects[object_index], static_cast<int>(object_index), s,
                   sink);
  }
  return out;
}

Visibility resolve_visibility(const std::vector<ScreenTriangle>& triangles, int width, int height) {
  if (width < 0 || height < 0)
    throw std::invalid_argument("resolve_visibility: negative image size");
  Visibility vis;
  vis.width = width;
  vis.height = height;
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
  vis.owner.assign(pixels, -1);
  std::vector<double> depth(pixels, std::numeric_limits<double>::infinity());
  for (size_t t = 0; t < triangles.size(); ++t) {
    const int32_t id = static_cast<int32_t>(t);
    rasterize(triangles[t], width, height,
              [&](int y, int x_begin, int x_end, double z, double dz_dx) {
                const size_t row = static_cast<size_t>(y) * width;
                for (int x = x_begin; x < x_end; ++x, z += dz_dx) {
                  // Strictly nearer only: on a tie the earlier (lower-index) triangle keeps the
                  // pixel.
                  if (z < depth[row + x]) {
                    depth[row + x] = z;
                    vis.owner[row + x] = id;
                  }
                }
              });
  }

  // Runs of equal owner, bucketed by triangle. Scanning rows top-down and left to right already
  // yields y-then-x0 order within each triangle, so a stable counting sort suffices.
  std::vector<size_t> first(triangles.size() + 1, 0);
  auto for_each_run = [&](auto&& emit) {
    for (int y = 0; y < height; ++y) {
      const int32_t* row = vis.owner.data() + static_cast<size_t>(y) * width;
      int x = 0;
      while (x < width) {
        const int32_t owner = row[x];
        int end = x + 1;
        while (end < width && row[end] == owner) ++end;
        if (owner >= 0) emit(y, x, end - x, owner);
        x = end;
      }
    }
  };
  for_each_run([&](int, int, int, int32_t owner) { ++first[owner + 1]; });
  for (size_t t = 0; t < triangles.size(); ++t) first[t + 1] += first[t];
  vis.spans.resize(first.back());
  std::vector<size_t> next(first.begin(), first.end() - 1);
  for_each_run([&](int y, int x0, int length, int32_t owner) {
    Span& span = vis.spans[next[owner]++];
    span.y = y;
    span.x0 = x0;
    span.length = length;
    span.triangle = static_cast<uint32_t>(owner);
  });
  std::vector<int64_t> last_of_row(height, -1);
  for (size_t i = 0; i < vis.spans.size(); ++i)
    last_of_row[vis.spans[i].y] = static_cast<int64_t>(i);
  for (int64_t i : last_of_row)
    if (i >= 0) vis.spans[i].last_in_row = true;
  return vis;
}

}  // namespace shadesim
