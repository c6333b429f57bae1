// Scene generators and tree checkers shared by the kd-tree tests. The
// checkers are written independently of the builder: they only read the
// memory-image encoding.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "accel/kdtree.h"
#include "scene/scene.h"

namespace kdrt::test {

// Exactly the contract of IsDegenerate: float cross product is the zero vector.
bool ZeroAreaTriangle(const Triangle& t);

Scene MakeScene(std::vector<Triangle> tris, const std::string& name);

// Small random triangles in the unit cube.
std::vector<Triangle> RandomSmallTriangles(uint32_t seed, int count, float size);
// Vertices on a 1/8 grid, a third of them axis-aligned (flat on a grid plane,
// so they lie exactly on candidate split planes).
std::vector<Triangle> GridSnappedTriangles(uint32_t seed, int count);
// Long thin triangles crossing most of the cube, some diagonal.
std::vector<Triangle> ThinLongTriangles(uint32_t seed, int count);
// Zero-area triangles: repeated vertices and exactly collinear points.
std::vector<Triangle> DegenerateTriangles(uint32_t seed, int count, float offset);
// A mix of all the above plus exact duplicates of some triangles.
Scene MixedScene(uint32_t seed, int count);
// Clusters (4 units wide) of small triangles in a mostly empty box [0, box]^3.
Scene ClusteredScene(uint32_t seed, int clusters, int per_cluster, float box);
// A UV sphere of radius 1 with about `count` triangles.
Scene SphereScene(int count);

// Checks layout, index ranges, sorted leaf lists, that every listed triangle
// reaches into its leaf's cell (strictly, unless it lies in a plane), depth
// limit, bounds and stats (against an independent recount). Reports
// failures via gtest.
void CheckTreeStructure(const Scene& scene, const BuildOptions& options, const KdTree& tree);

// Checks that every sample point of every non-degenerate triangle, descended
// with the float splits (on a split plane into both children), reaches at
// least one leaf listing the triangle (see the coverage rule in
// docs/kdtree.md). Returns the number of points checked.
int CheckCoverage(const Scene& scene, const BuildOptions& options, const KdTree& tree,
                  uint32_t seed, int random_points_per_triangle);

}  // namespace kdrt::test
