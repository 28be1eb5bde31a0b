// Triangle meshes: procedural shapes with analytic normals, and the object-to-world transform.
// Mesh files are read by host/mesh_import.h.
#pragma once

#include <string>

#include "host/scene.h"
#include "host/vec3.h"

namespace shadesim {

// Shapes are built in object space, centred on the origin, with unit vertex normals and triangles
// counter-clockwise seen from outside. `tessellation` must be at least kMinTessellation.
constexpr int kMinTessellation = 3;
constexpr int kMaxTessellation = 1024;

// `tessellation` latitude bands and 2*tessellation longitude segments; one vertex at each pole, so
// the mesh is closed (every edge shared by exactly two triangles).
Mesh make_sphere(double radius, int tessellation);
// Ring around the y axis in the xz plane: 2*tessellation segments around, tessellation around the
// tube.
Mesh make_torus(double major_radius, double minor_radius, int tessellation);
// Axis y, from -height/2 to +height/2, `tessellation` segments around, closed by flat caps. Cap
// vertices duplicate the rim positions because the cap normal (+-y) differs from the side normal.
Mesh make_cylinder(double radius, double height, int tessellation);
// Square of side `size` in the xz plane (y = 0), facing +y, tessellation x tessellation quads.
// Any tessellation >= 1 is accepted here.
Mesh make_plane(double size, int tessellation);

// Scale, then rotate about x, then y, then z (Euler XYZ, degrees), then translate.
struct Transform {
  Vec3 translate{0, 0, 0};
  Vec3 rotate_deg{0, 0, 0};
  Vec3 scale{1, 1, 1};  // every component non-zero
};

// Positions by the transform, normals by its inverse transpose (renormalised). A mirroring
// transform (negative determinant) reverses the winding so triangles stay counter-clockwise from
// outside.
Mesh transform_mesh(const Mesh& mesh, const Transform& transform);

}  // namespace shadesim
