#include "kdtree_test_util.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

namespace kdrt::test {
namespace {

float Uniform(std::mt19937& rng, float lo, float hi) {
  return std::uniform_real_distribution<float>(lo, hi)(rng);
}

glm::vec3 RandomPoint(std::mt19937& rng, float lo, float hi) {
  const float x = Uniform(rng, lo, hi);
  const float y = Uniform(rng, lo, hi);
  const float z = Uniform(rng, lo, hi);
  return {x, y, z};
}

struct Cell {
  double lo[3];
  double hi[3];
};

double Area(const Cell& c) {
  const double dx = c.hi[0] - c.lo[0], dy = c.hi[1] - c.lo[1], dz = c.hi[2] - c.lo[2];
  return 2.0 * (dx * dy + dy * dz + dz * dx);
}

struct Recount {
  uint32_t nodes = 0, inner = 0, leaves = 0, empty = 0, max_depth = 0, max_prims = 0;
  uint64_t depth_sum = 0, refs = 0;
  uint32_t non_empty = 0;
  double sah = 0;
};

class StructureChecker {
 public:
  StructureChecker(const Scene& scene, const BuildOptions& options, const KdTree& tree,
                   int max_depth)
      : scene_(scene), options_(options), tree_(tree), max_depth_(max_depth) {}

  // Returns the index just after the subtree rooted at i (depth-first layout).
  uint32_t Walk(uint32_t i, int depth, const Cell& cell) {
    if (failed_) return i;
    if (i >= tree_.nodes.size()) {
      Fail() << "node index " << i << " out of range " << tree_.nodes.size();
      return i;
    }
    const img::Node& node = tree_.nodes[i];
    ++count_.nodes;
    count_.max_depth = std::max<uint32_t>(count_.max_depth, depth);
    if (depth > max_depth_) Fail() << "node " << i << " at depth " << depth << " > max";
    const double ratio = root_area_ > 0 ? Area(cell) / root_area_ : 1.0;
    if (node.IsLeaf()) {
      CheckLeaf(i, depth, cell);
      count_.sah += static_cast<double>(options_.isect_cost) * node.Count() * ratio;
      return i + 1;
    }
    ++count_.inner;
    count_.sah += static_cast<double>(options_.traversal_cost) * ratio;
    const int axis = node.Axis();
    const double s = node.Split();
    if (!(s > cell.lo[axis] && s < cell.hi[axis])) {
      Fail() << "node " << i << " split " << s << " not strictly inside its cell on axis "
             << axis;
    }
    const uint32_t above = node.AboveChild();
    if (above <= i + 1) {
      Fail() << "node " << i << " above child " << above << " not after the below child";
      return i + 1;
    }
    Cell below_cell = cell;
    below_cell.hi[axis] = s;
    Cell above_cell = cell;
    above_cell.lo[axis] = s;
    const uint32_t below_end = Walk(i + 1, depth + 1, below_cell);
    if (!failed_ && below_end != above) {
      Fail() << "node " << i << ": above child " << above << " but below subtree ends at "
             << below_end;
    }
    return Walk(above, depth + 1, above_cell);
  }

  void Run() {
    Cell root;
    for (int a = 0; a < 3; ++a) {
      root.lo[a] = tree_.bounds_min[a];
      root.hi[a] = tree_.bounds_max[a];
    }
    root_area_ = Area(root);
    ASSERT_FALSE(tree_.nodes.empty());
    const uint32_t end = Walk(0, 0, root);
    ASSERT_FALSE(failed_) << message_.str();
    EXPECT_EQ(end, tree_.nodes.size()) << "nodes unreachable from the root";
    EXPECT_EQ(count_.refs, tree_.lists.size()) << "leaf lists not compact";
    CheckStats();
  }

 private:
  std::ostringstream& Fail() {
    failed_ = true;
    message_ << "\n";
    return message_;
  }

  void CheckLeaf(uint32_t i, int depth, const Cell& cell) {
    const img::Node& node = tree_.nodes[i];
    const uint32_t count = node.Count();
    const uint32_t first = node.FirstEntry();
    ++count_.leaves;
    count_.depth_sum += depth;
    count_.refs += count;
    count_.max_prims = std::max(count_.max_prims, count);
    if (count == 0) {
      ++count_.empty;
      if (first != 0) Fail() << "empty leaf " << i << " has first = " << first;
      return;
    }
    ++count_.non_empty;
    if (static_cast<uint64_t>(first) + count > tree_.lists.size()) {
      Fail() << "leaf " << i << " list [" << first << ", +" << count << ") out of range";
      return;
    }
    for (uint32_t k = 0; k < count; ++k) {
      const uint32_t id = tree_.lists[first + k];
      if (id >= scene_.triangles.size()) {
        Fail() << "leaf " << i << " lists triangle " << id << " out of range";
        return;
      }
      if (ZeroAreaTriangle(scene_.triangles[id])) {
        Fail() << "leaf " << i << " lists degenerate triangle " << id;
      }
      if (k > 0 && tree_.lists[first + k - 1] >= id) {
        Fail() << "leaf " << i << " ids not strictly ascending";
      }
      CheckReachesIntoCell(i, id, cell);
    }
    // Median and midpoint stop early only at max depth or when a split would
    // not separate anything; for midpoint that is checkable here.
    if (options_.method == SplitMethod::kMidpoint &&
        count > static_cast<uint32_t>(options_.max_leaf_prims) && depth < max_depth_) {
      int axis = 0;
      for (int a = 1; a < 3; ++a) {
        if (cell.hi[a] - cell.lo[a] > cell.hi[axis] - cell.lo[axis]) axis = a;
      }
      const float s = static_cast<float>(0.5 * (cell.lo[axis] + cell.hi[axis]));
      if (s > cell.lo[axis] && s < cell.hi[axis]) {
        for (uint32_t k = 0; k < count; ++k) {
          const Triangle& t = scene_.triangles[tree_.lists[first + k]];
          const float lo = std::min({t.v0[axis], t.v1[axis], t.v2[axis]});
          const float hi = std::max({t.v0[axis], t.v1[axis], t.v2[axis]});
          if (lo >= s || hi <= s) {
            Fail() << "midpoint leaf " << i << " with " << count
                   << " triangles could have been split at " << s;
            break;
          }
        }
      }
    }
  }

  // The classification rule seen from a leaf: on every axis the triangle's
  // box extends strictly into the cell, or the triangle lies in a plane
  // within the closed cell. A triangle that only touches a face of the cell
  // from outside does not belong to it.
  void CheckReachesIntoCell(uint32_t leaf, uint32_t id, const Cell& cell) {
    const Triangle& t = scene_.triangles[id];
    for (int a = 0; a < 3; ++a) {
      const double lo = std::min({t.v0[a], t.v1[a], t.v2[a]});
      const double hi = std::max({t.v0[a], t.v1[a], t.v2[a]});
      const bool reaches = lo == hi ? (lo >= cell.lo[a] && lo <= cell.hi[a])
                                    : (lo < cell.hi[a] && hi > cell.lo[a]);
      if (!reaches) {
        Fail() << "leaf " << leaf << " lists triangle " << id << " [" << lo << ", " << hi
               << "] that does not reach into its cell [" << cell.lo[a] << ", " << cell.hi[a]
               << "] on axis " << a;
        return;
      }
    }
  }

  void CheckStats() {
    const TreeStats& st = tree_.stats;
    size_t non_degenerate = 0;
    uint32_t degenerate = 0;
    float lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::numeric_limits<float>::infinity();
      hi[a] = -lo[a];
    }
    for (const Triangle& t : scene_.triangles) {
      if (ZeroAreaTriangle(t)) {
        ++degenerate;
        continue;
      }
      ++non_degenerate;
      for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
        for (int a = 0; a < 3; ++a) {
          lo[a] = std::min(lo[a], v[a]);
          hi[a] = std::max(hi[a], v[a]);
        }
      }
    }
    if (non_degenerate > 0) {
      for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(tree_.bounds_min[a], lo[a]) << "axis " << a;
        EXPECT_EQ(tree_.bounds_max[a], hi[a]) << "axis " << a;
      }
    }
    EXPECT_EQ(st.degenerate_triangles, degenerate);
    EXPECT_EQ(st.nodes, count_.nodes);
    EXPECT_EQ(st.nodes, tree_.nodes.size());
    EXPECT_EQ(st.inner_nodes, count_.inner);
    EXPECT_EQ(st.leaves, count_.leaves);
    EXPECT_EQ(st.empty_leaves, count_.empty);
    EXPECT_EQ(st.max_depth, count_.max_depth);
    EXPECT_DOUBLE_EQ(st.avg_leaf_depth, static_cast<double>(count_.depth_sum) / count_.leaves);
    EXPECT_EQ(st.max_leaf_prims, count_.max_prims);
    EXPECT_DOUBLE_EQ(st.avg_leaf_prims,
                     count_.non_empty ? static_cast<double>(count_.refs) / count_.non_empty : 0);
    EXPECT_EQ(st.references, count_.refs);
    EXPECT_DOUBLE_EQ(st.refs_per_triangle,
                     non_degenerate ? static_cast<double>(count_.refs) / non_degenerate : 0);
    EXPECT_NEAR(st.sah_cost, count_.sah, 1e-9 * std::max(1.0, count_.sah));
    EXPECT_GE(st.build_seconds, 0.0);
  }

  const Scene& scene_;
  const BuildOptions& options_;
  const KdTree& tree_;
  const int max_depth_;
  double root_area_ = 0;
  Recount count_;
  bool failed_ = false;
  std::ostringstream message_;
};

// Descends with the coverage rule: strictly below/above the split follows
// one child, on the split follows both, and at least one leaf reached must
// list the triangle (a triangle touching the plane from one side, or lying
// in it, is only in one child). A point strictly inside a cell reaches one
// leaf, which must list it.
bool Reaches(const KdTree& tree, uint32_t i, const double p[3], uint32_t tri) {
  const img::Node& node = tree.nodes[i];
  if (node.IsLeaf()) {
    const auto first = tree.lists.begin() + node.FirstEntry();
    return std::binary_search(first, first + node.Count(), tri);
  }
  const int axis = node.Axis();
  const float s = node.Split();
  if (p[axis] < s) return Reaches(tree, i + 1, p, tri);
  if (p[axis] > s) return Reaches(tree, node.AboveChild(), p, tri);
  return Reaches(tree, i + 1, p, tri) || Reaches(tree, node.AboveChild(), p, tri);
}

}  // namespace

bool ZeroAreaTriangle(const Triangle& t) {
  const glm::vec3 e1 = t.v1 - t.v0;
  const glm::vec3 e2 = t.v2 - t.v0;
  const float cx = e1.y * e2.z - e1.z * e2.y;
  const float cy = e1.z * e2.x - e1.x * e2.z;
  const float cz = e1.x * e2.y - e1.y * e2.x;
  return cx == 0.0f && cy == 0.0f && cz == 0.0f;
}

Scene MakeScene(std::vector<Triangle> tris, const std::string& name) {
  Scene s;
  s.triangles = std::move(tris);
  s.material.assign(s.triangles.size(), 0);
  s.colors.push_back(glm::vec3(1.0f));
  s.source = name;
  return s;
}

std::vector<Triangle> RandomSmallTriangles(uint32_t seed, int count, float size) {
  std::mt19937 rng(seed);
  std::vector<Triangle> out;
  for (int i = 0; i < count; ++i) {
    const glm::vec3 c = RandomPoint(rng, 0.0f, 1.0f);
    Triangle t;
    t.v0 = c + RandomPoint(rng, -size, size);
    t.v1 = c + RandomPoint(rng, -size, size);
    t.v2 = c + RandomPoint(rng, -size, size);
    out.push_back(t);
  }
  return out;
}

std::vector<Triangle> GridSnappedTriangles(uint32_t seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> base(0, 6), offset(0, 2), axis_pick(0, 5);
  auto grid_point = [&](const glm::ivec3& b) {
    return glm::vec3((b.x + offset(rng)) / 8.0f, (b.y + offset(rng)) / 8.0f,
                     (b.z + offset(rng)) / 8.0f);
  };
  std::vector<Triangle> out;
  while (static_cast<int>(out.size()) < count) {
    const glm::ivec3 b(base(rng), base(rng), base(rng));
    Triangle t{grid_point(b), grid_point(b), grid_point(b)};
    const int axis = axis_pick(rng);
    if (axis < 3) {  // half of them flat on a grid plane
      t.v1[axis] = t.v0[axis];
      t.v2[axis] = t.v0[axis];
    }
    if (ZeroAreaTriangle(t)) continue;
    out.push_back(t);
  }
  return out;
}

std::vector<Triangle> ThinLongTriangles(uint32_t seed, int count) {
  std::mt19937 rng(seed);
  std::vector<Triangle> out;
  for (int i = 0; i < count; ++i) {
    Triangle t;
    if (i % 2 == 0) {  // diagonal
      t.v0 = RandomPoint(rng, 0.0f, 0.2f);
      t.v1 = RandomPoint(rng, 0.8f, 1.0f);
    } else {  // along one axis
      const int axis = i % 3;
      t.v0 = RandomPoint(rng, 0.0f, 1.0f);
      t.v1 = t.v0;
      t.v0[axis] = 0.0f;
      t.v1[axis] = 1.0f;
    }
    t.v2 = t.v0 + RandomPoint(rng, -0.002f, 0.002f);
    out.push_back(t);
  }
  return out;
}

std::vector<Triangle> DegenerateTriangles(uint32_t seed, int count, float offset) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> q(0, 16);
  std::vector<Triangle> out;
  for (int i = 0; i < count; ++i) {
    const glm::vec3 p(q(rng) / 4.0f + offset, q(rng) / 4.0f + offset, q(rng) / 4.0f + offset);
    const glm::vec3 d(q(rng) / 8.0f, q(rng) / 8.0f, 0.5f);
    switch (i % 3) {
      case 0: out.push_back({p, p, p + d}); break;           // repeated vertex
      case 1: out.push_back({p, p + d, p + 2.0f * d}); break;  // collinear, exact
      default: out.push_back({p, p, p}); break;              // a point
    }
  }
  return out;
}

Scene MixedScene(uint32_t seed, int count) {
  std::mt19937 rng(seed);
  std::vector<Triangle> tris = RandomSmallTriangles(seed + 1, count / 3, 0.05f);
  for (const auto& part : {GridSnappedTriangles(seed + 2, count / 3),
                           ThinLongTriangles(seed + 3, count / 6),
                           DegenerateTriangles(seed + 4, std::max(3, count / 50), 0.0f)}) {
    tris.insert(tris.end(), part.begin(), part.end());
  }
  const size_t n = tris.size();
  for (size_t i = 0; i < n / 20 + 1; ++i) {  // exact duplicates
    tris.push_back(tris[std::uniform_int_distribution<size_t>(0, n - 1)(rng)]);
  }
  std::shuffle(tris.begin(), tris.end(), rng);
  return MakeScene(std::move(tris), "mixed-" + std::to_string(seed));
}

Scene ClusteredScene(uint32_t seed, int clusters, int per_cluster, float box) {
  std::mt19937 rng(seed);
  std::vector<Triangle> tris;
  // Two small triangles stretch the box to [0, box]^3.
  tris.push_back({{0, 0, 0}, {0.1f, 0, 0}, {0, 0.1f, 0}});
  tris.push_back({{box, box, box}, {box - 0.1f, box, box}, {box, box - 0.1f, box}});
  for (int c = 0; c < clusters; ++c) {
    const glm::vec3 centre = RandomPoint(rng, 0.1f * box + 2.0f, 0.9f * box - 2.0f);
    for (int i = 0; i < per_cluster; ++i) {
      const glm::vec3 p = centre + RandomPoint(rng, -2.0f, 2.0f);
      tris.push_back({p, p + RandomPoint(rng, -0.3f, 0.3f), p + RandomPoint(rng, -0.3f, 0.3f)});
    }
  }
  return MakeScene(std::move(tris), "clustered-" + std::to_string(seed));
}

Scene SphereScene(int count) {
  const int stacks = std::max(3, static_cast<int>(std::sqrt(count / 4.0)) + 1);
  const int slices = std::max(3, count / (2 * (stacks - 1)));
  const double pi = std::acos(-1.0);
  auto vertex = [&](int i, int j) {  // i: stack 0..stacks, j: slice
    const double theta = pi * i / stacks, phi = 2.0 * pi * j / slices;
    return glm::vec3(static_cast<float>(std::sin(theta) * std::cos(phi)),
                     static_cast<float>(std::sin(theta) * std::sin(phi)),
                     static_cast<float>(std::cos(theta)));
  };
  std::vector<Triangle> tris;
  for (int i = 0; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      const glm::vec3 a = vertex(i, j), b = vertex(i, j + 1);
      const glm::vec3 c = vertex(i + 1, j), d = vertex(i + 1, j + 1);
      if (i > 0) tris.push_back({a, c, b});
      if (i < stacks - 1) tris.push_back({b, c, d});
    }
  }
  return MakeScene(std::move(tris), "sphere-" + std::to_string(tris.size()));
}

void CheckTreeStructure(const Scene& scene, const BuildOptions& options, const KdTree& tree) {
  size_t n = 0;
  for (const Triangle& t : scene.triangles) n += ZeroAreaTriangle(t) ? 0 : 1;
  int max_depth = options.max_depth;
  if (max_depth < 0) {
    max_depth = n == 0 ? 0 : static_cast<int>(std::lround(8.0 + 1.3 * std::log2(double(n))));
  }
  StructureChecker(scene, options, tree, max_depth).Run();
}

int CheckCoverage(const Scene& scene, const BuildOptions& options, const KdTree& tree,
                  uint32_t seed, int random_points_per_triangle) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked = 0, failures = 0;
  for (uint32_t id = 0; id < scene.triangles.size(); ++id) {
    const Triangle& t = scene.triangles[id];
    if (ZeroAreaTriangle(t)) continue;
    // Vertices, edge midpoints, centroid, then random barycentric points.
    std::vector<std::array<double, 3>> weights = {{1, 0, 0},     {0, 1, 0},     {0, 0, 1},
                                                  {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5},
                                                  {1.0 / 3, 1.0 / 3, 1.0 / 3}};
    for (int k = 0; k < random_points_per_triangle; ++k) {
      double u = unit(rng), v = unit(rng);
      if (u + v > 1) {
        u = 1 - u;
        v = 1 - v;
      }
      weights.push_back({1 - u - v, u, v});
    }
    for (const auto& w : weights) {
      double p[3];
      for (int a = 0; a < 3; ++a) {
        const double x = w[0] * t.v0[a] + w[1] * t.v1[a] + w[2] * t.v2[a];
        // The exact point lies within the vertex range; clamping removes the
        // rounding that could carry it past a plane the triangle only touches.
        const double lo = std::min({t.v0[a], t.v1[a], t.v2[a]});
        const double hi = std::max({t.v0[a], t.v1[a], t.v2[a]});
        p[a] = std::min(hi, std::max(lo, x));
      }
      ++checked;
      if (!Reaches(tree, 0, p, id)) {
        if (++failures <= 5) {
          ADD_FAILURE() << scene.source << " method " << SplitMethodName(options.method)
                        << (options.perfect_splits ? "+perfect" : "") << ": triangle " << id
                        << " point (" << p[0] << ", " << p[1] << ", " << p[2]
                        << ") reaches a leaf that does not list it";
        }
      }
    }
  }
  EXPECT_EQ(failures, 0);
  return checked;
}

}  // namespace kdrt::test
