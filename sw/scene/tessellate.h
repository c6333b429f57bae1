// Triangle meshes for the curved NFF primitives and the generators' shapes.
// Positions are computed in double and rounded once to float; seam vertices
// are computed once and reused, so neighbouring triangles share vertices
// bit-exactly (no cracks for a watertight intersector). Triangles face
// outward (counter-clockwise seen from outside). Callers validate sizes.
#pragma once

#include <glm/vec3.hpp>

#include "scene/scene_builder.h"

namespace kdrt {

// Poles on the +z/-z axis through `centre`; `segments` slices and
// max(2, segments / 2) stacks: 2 * segments * (stacks - 1) triangles, in
// order north cap, bands from north to south, south cap.
void AddSphere(SceneBuilder& b, const glm::dvec3& centre, double radius, int segments);
int SphereTriangleCount(int segments);

// Open cone frustum from `base` (radius rb) to `apex` (radius ra); needs
// base != apex and rb or ra non-zero. `segments` sides cut into `bands`
// equal rings along the axis; each cell two triangles (b_i, b_i+1, a_i+1),
// (b_i, a_i+1, a_i), or one triangle where a radius is 0:
// 2 * segments * bands triangles, fewer for a cone's point.
void AddCone(SceneBuilder& b, const glm::dvec3& base, double rb, const glm::dvec3& apex, double ra,
             int segments, int bands = 1);

// The bands that keep a cone's cells at most `max_aspect` times longer than
// the widest ring's side (1 for max_aspect <= 0: one band from end to end),
// at most kMaxConeBands. A long cell crosses every kd-tree cell along its
// length, so a tree cannot separate the sides of a thin cylinder of one band
// (docs/kdtree.md, "Long thin cylinders").
constexpr int kMaxConeBands = 4096;
// The cone aspects LoadOptions::cone_aspect may hold: 0 (one band) or 1..1e6.
inline bool IsValidConeAspect(double aspect) { return aspect == 0.0 || (aspect >= 1.0 && aspect <= 1e6); }
inline constexpr const char* kConeAspectRule = "cone aspect must be 0 (one band) or in 1..1e6";
int ConeBands(const glm::dvec3& base, double rb, const glm::dvec3& apex, double ra, int segments,
              double max_aspect);

// Torus around `axis` (unit), major radius R, tube radius r:
// 2 * major_segments * minor_segments triangles.
void AddTorus(SceneBuilder& b, const glm::dvec3& centre, const glm::dvec3& axis, double major_r,
              double minor_r, int major_segments, int minor_segments);

// Parallelogram corner + s*edge_u + t*edge_v, cut into nu x nv cells of two
// triangles each, facing along edge_u x edge_v; rows of cells along edge_u.
void AddGrid(SceneBuilder& b, const glm::dvec3& corner, const glm::dvec3& edge_u,
             const glm::dvec3& edge_v, int nu, int nv);

// Right-handed orthonormal frame (u, v, axis) for a unit axis: the same axis
// always gives the same frame.
void MakeFrame(const glm::dvec3& axis, glm::dvec3* u, glm::dvec3* v);

}  // namespace kdrt
