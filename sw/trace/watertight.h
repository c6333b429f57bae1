// Closed meshes and ray sets for measuring watertightness: every ray below is
// aimed at a vertex or an edge midpoint of a closed, convex mesh from outside
// it, so it passes through the mesh's interior and must hit some triangle. A
// ray that hits nothing slipped through a crack between triangles.
#pragma once

#include <cstdint>
#include <vector>

#include "common/ray.h"
#include "scene/scene.h"

namespace kdrt {

// A unit sphere around the origin: `rings` latitude bands (>= 2) between the
// poles, `segments` longitudes (>= 3). Each vertex is computed once and every
// triangle touching it uses the same float values, so the mesh is closed:
// 2 * segments * (rings - 1) triangles, wound counter-clockwise seen from
// outside. Throws InputError on bad sizes (rings or segments above 4096).
Scene ClosedSphereMesh(int rings, int segments);

// The cube [-1, 1]^3, each face an n x n grid of quads (n in 1..1024), each
// quad split into two triangles: 12 * n * n triangles. Vertices are computed
// from their integer lattice coordinates, so faces sharing a cube edge share
// bit-identical vertices.
Scene ClosedCubeMesh(int n);

// For every triangle, six rays: aimed at each of its three vertices and at
// each of its three edge midpoints, from origin = 3 * target + a jitter of up
// to 0.05 per axis, direction = target - origin (not normalised), t in
// [0, inf). Requires a mesh around the origin (both meshes above are), so the
// origin lies outside. Deterministic for a seed on every platform.
std::vector<Ray> WatertightRays(const Scene& scene, uint32_t seed);

}  // namespace kdrt
