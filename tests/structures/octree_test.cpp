// The octree (structures/octree.cpp): the build rule (leaf sizes, depth
// limit, the blow-up guards), complete binning, the separating-axis test,
// the edge cases of the build (empty scene, one triangle, a flat scene), the
// work it saves, and the rays that stress the traversal's slack (in the mid
// planes, from the box faces), which must find brute force's closest hit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

#include "common/error.h"
#include "fp/ftz.h"
#include "structures/octree_tree.h"
#include "structures/structure.h"
#include "structures/structure_tracer.h"
#include "tests/structures/structures_test_util.h"

namespace kdrt {
namespace {

using testing::BruteForceHits;
using testing::FromTriangles;
using testing::InsideRays;

using octree::Cell;
using octree::Node;
using testing::Prepared;

// A prepared scene, its structure input and its octree, kept together so the
// pointers between them stay valid.
struct OctreeScene {
  Prepared p;
  StructureInput input;
  std::unique_ptr<Structure> structure;
  explicit OctreeScene(Scene scene, StructureOptions options = {})
      : p(std::move(scene)), input(MakeStructureInput(p.view())), structure(BuildOctree(input, options)) {}
  ImageView image() const { return p.view(); }
  const Octree& tree() const { return dynamic_cast<const Octree&>(*structure); }
};

// Calls fn(node, cell, depth) for every stored node, parents first.
void Walk(const Octree& t, const std::function<void(const Node&, const Cell&, int)>& fn) {
  const std::function<void(uint32_t, const Cell&, int)> visit = [&](uint32_t index, const Cell& cell, int depth) {
    const Node& n = t.nodes()[index];
    fn(n, cell, depth);
    if (n.IsLeaf()) return;
    float mid[3];
    octree::CellCentre(cell, mid);
    for (int c = 0; c < 8; ++c) {
      if (n.HasChild(c)) visit(n.Child(c), octree::ChildCell(cell, mid, c), depth + 1);
    }
  };
  visit(0, t.root_cell(), 0);
}

void Widened(const Cell& cell, double margin, double lo[3], double hi[3]) {
  for (int k = 0; k < 3; ++k) {
    lo[k] = double(cell.lo[k]) - margin;
    hi[k] = double(cell.hi[k]) + margin;
  }
}

// References the build would give the children of `cell` if it split this
// list there: the overlap test on every candidate child (the build skips it
// where the triangle's box reaches into one child only).
size_t ChildReferences(const OctreeScene& s, const std::vector<uint32_t>& ids, const Cell& cell) {
  float mid[3];
  octree::CellCentre(cell, mid);
  size_t sum = 0;
  for (uint32_t id : ids) {
    for (int c = 0; c < 8; ++c) {
      bool skip = false;  // the upper half of an axis too thin to split is empty
      for (int k = 0; k < 3; ++k) skip = skip || (((c >> k) & 1) && mid[k] == cell.hi[k]);
      double lo[3], hi[3];
      Widened(octree::ChildCell(cell, mid, c), s.tree().margin(), lo, hi);
      if (!skip && octree::TriangleOverlapsBox(s.input.triangles[id], lo, hi)) ++sum;
    }
  }
  return sum;
}

// The distinct triangles under a node: the list the build had there.
std::vector<uint32_t> SubtreeIds(const Octree& t, uint32_t index) {
  const Node& n = t.nodes()[index];
  if (n.IsLeaf()) {
    const auto begin = t.refs().begin() + n.FirstRef();
    return std::vector<uint32_t>(begin, begin + n.Count());
  }
  std::vector<uint32_t> ids;
  for (int c = 0; c < 8; ++c) {
    if (!n.HasChild(c)) continue;
    const std::vector<uint32_t> child = SubtreeIds(t, n.Child(c));
    ids.insert(ids.end(), child.begin(), child.end());
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

// Why leaves hold more than max_prims triangles.
struct OversizedLeaves {
  size_t at_depth_limit = 0, no_gain = 0, over_budget = 0, unsplittable = 0;
  size_t total() const { return at_depth_limit + no_gain + over_budget + unsplittable; }
};

// Checks the build rule (octree_tree.h) at every node below `index`, which
// holds `ids` and got `budget` references.
void CheckBuildRule(const OctreeScene& s, uint32_t index, const Cell& cell, int depth, double budget,
                    const std::vector<uint32_t>& ids, OversizedLeaves* over) {
  const Octree& t = s.tree();
  const Node& n = t.nodes()[index];
  const size_t max_prims = static_cast<size_t>(t.max_prims());
  float mid[3];
  const bool splittable = octree::CellCentre(cell, mid);
  if (n.IsLeaf()) {
    if (ids.size() <= max_prims) return;
    if (depth == t.depth_limit()) {
      ++over->at_depth_limit;
    } else if (!splittable) {
      ++over->unsplittable;
    } else {
      const size_t sum = ChildReferences(s, ids, cell);
      if (!octree::SplitPays(ids.size(), sum)) {
        ++over->no_gain;
      } else {
        EXPECT_GT(double(sum), budget) << "a leaf of " << ids.size() << " at depth " << depth
                                       << " that the rule would split (" << sum << " references)";
        ++over->over_budget;
      }
    }
    return;
  }
  EXPECT_GT(ids.size(), max_prims);
  EXPECT_LT(depth, t.depth_limit());
  EXPECT_TRUE(splittable);
  std::vector<uint32_t> child_ids[8];
  size_t sum = 0;
  for (int c = 0; c < 8; ++c) {
    if (n.HasChild(c)) child_ids[c] = SubtreeIds(t, n.Child(c));
    sum += child_ids[c].size();
  }
  EXPECT_TRUE(octree::SplitPays(ids.size(), sum)) << ids.size() << " -> " << sum;
  EXPECT_LE(double(sum), budget);
  for (int c = 0; c < 8; ++c) {
    if (!n.HasChild(c)) continue;
    CheckBuildRule(s, n.Child(c), octree::ChildCell(cell, mid, c), depth + 1,
                   budget * double(child_ids[c].size()) / double(sum), child_ids[c], over);
  }
}

struct Work {
  double nodes = 0, tests = 0, mailbox_hits = 0;
};

Work CameraWork(const OctreeScene& s, int res) {
  const std::vector<Ray> rays = testing::CameraRays(s.p.scene, res);
  AccelTotals totals;
  TraceStructureRays(*s.structure, s.image().frame(), rays, TraceOptions{}, &totals);
  const double n = double(rays.size());
  return Work{totals.nodes / n, totals.tri_tests / n, totals.mailbox_hits / n};
}

// The octree's hit must be brute force's (both take the smallest t, then the
// smallest id, over every triangle hit), bit for bit, but for ties
// (IsTie: two triangles hit within a few ulps, where the stop rule may end
// the ray after the cell of the farther one); they must stay rare. Where the
// kd-tree's hit is brute force's, the octree thus gives the kd-tree's hit
// buffer. The kd-tree's own differences are only counted: on rays lying in
// its split planes it stops after the near child although the far child
// covers the same t range and may hold a triangle that only touches the
// plane (a closer hit at a vertex or an edge), and near planes it shows the
// IsTie case far more often than the octree.
void ExpectExactHits(const OctreeScene& s, const std::vector<Ray>& rays, const std::string& what,
                     size_t min_hits = 1) {
  for (const char* format : {"fp32", "fp64"}) {
    TraceOptions o;
    o.format = fp::ParseFormat(format);
    const std::vector<Hit> kd = TraceRays(s.image(), rays, o);
    const std::vector<Hit> ours = TraceStructureRays(*s.structure, s.image().frame(), rays, o);
    const std::vector<Hit> exact = BruteForceHits(s.image(), rays, o.format);
    size_t wrong = 0, ties = 0, kd_differs = 0, kd_ties = 0, kd_mismatches = 0, hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      hits += ours[i].IsHit();
      kd_differs += !testing::SameBits(kd[i], exact[i]);
      if (!testing::SameBits(kd[i], ours[i])) ++(IsTie(kd[i], ours[i]) ? kd_ties : kd_mismatches);
      if (testing::SameBits(ours[i], exact[i])) continue;
      if (IsTie(ours[i], exact[i])) {
        ++ties;
        continue;
      }
      if (++wrong <= 3) {
        ADD_FAILURE() << what << " " << format << " ray " << i << " (o " << rays[i].o.x << " " << rays[i].o.y << " "
                      << rays[i].o.z << ", d " << rays[i].d.x << " " << rays[i].d.y << " " << rays[i].d.z
                      << "): brute force " << HitText(exact[i]) << ", octree " << HitText(ours[i]) << ", kd-tree "
                      << HitText(kd[i]);
      }
    }
    std::printf("[ octree   ] %s %s: %zu rays, %zu hits; octree vs brute force: %zu mismatches, %zu ties; vs the "
                "kd-tree: %zu mismatches, %zu ties (kd-tree vs brute force: %zu differ)\n",
                what.c_str(), format, rays.size(), hits, wrong, ties, kd_mismatches, kd_ties, kd_differs);
    EXPECT_EQ(wrong, 0u) << what << " " << format;
    EXPECT_LE(ties, hits / 50 + 2) << what << " " << format;
    EXPECT_GE(hits, min_hits) << what << " " << format;
  }
}

// No leaf holds more than max_prims triangles unless it is at the depth
// limit or splitting it fails a guard (no gain, over its budget); every inner
// node passed the guards.
TEST(OctreeTest, BuildRule) {
  for (const char* g : {"balls", "tree", "room", "gears"}) {
    StructureOptions options;
    options.octree_max_prims = 4;
    const OctreeScene s(GenerateScene(g, 4000), options);
    const Octree& t = s.tree();
    OversizedLeaves over;
    CheckBuildRule(s, 0, t.root_cell(), 0, octree::kDuplicationBudget * double(s.input.ids.size()), s.input.ids,
                   &over);
    size_t leaves = 0, max_leaf = 0;
    uint32_t max_depth = 0;
    Walk(t, [&](const Node& n, const Cell&, int depth) {
      if (!n.IsLeaf()) {
        EXPECT_NE(n.ChildMask(), 0u) << g;
        return;
      }
      max_depth = std::max<uint32_t>(max_depth, depth);
      leaves += n.Count() > 0;
      max_leaf = std::max<size_t>(max_leaf, n.Count());
    });
    std::printf("[ octree   ] %s:4000 max_prims 4: %zu leaves, %zu larger: %zu at the depth limit %d, %zu where a "
                "split would not pay, %zu over their budget, %zu too thin to split; %.2f references per triangle\n",
                g, leaves, over.total(), over.at_depth_limit, t.depth_limit(), over.no_gain, over.over_budget,
                over.unsplittable, double(t.refs().size()) / s.input.ids.size());
    EXPECT_EQ(leaves, s.structure->stats().leaves) << g;
    EXPECT_EQ(max_leaf, s.structure->stats().max_leaf_prims) << g;
    EXPECT_EQ(max_depth, s.structure->stats().max_depth) << g;
    EXPECT_EQ(s.structure->stats().extra["oversized_leaves"].get<size_t>(), over.total()) << g;
    EXPECT_LE(double(t.refs().size()), octree::kDuplicationBudget * double(s.input.ids.size())) << g;
  }
}

TEST(OctreeTest, EveryTriangleListedInEveryLeafItOverlaps) {
  for (const char* g : {"room", "balls", "rings", "tetra", "tree", "gears"}) {
    const OctreeScene s(GenerateScene(g, 3000));
    const Octree& t = s.tree();
    size_t listed = 0;
    std::vector<uint32_t> seen(s.input.triangles.size(), 0);
    Walk(t, [&](const Node& n, const Cell& cell, int) {
      if (!n.IsLeaf()) return;
      listed += n.Count();
      double lo[3], hi[3];
      Widened(cell, t.margin(), lo, hi);
      for (uint32_t i = 0; i < n.Count(); ++i) {
        const uint32_t id = t.refs()[n.FirstRef() + i];
        if (i > 0) {
          EXPECT_LT(t.refs()[n.FirstRef() + i - 1], id) << g << ": leaf list not ascending";
        }
        ++seen[id];
        EXPECT_TRUE(octree::TriangleOverlapsBox(s.input.triangles[id], lo, hi)) << g << ": " << id;
      }
    });
    EXPECT_EQ(listed, t.refs().size()) << g;
    EXPECT_EQ(listed, s.structure->stats().references) << g;
    for (uint32_t id : s.input.ids) EXPECT_GT(seen[id], 0u) << g << ": triangle " << id << " not referenced";

    // The other direction, per triangle: descend into every cell the
    // triangle overlaps (unwidened); each such leaf must list it.
    size_t missing = 0;
    for (size_t k = 0; k < s.input.ids.size(); k += 3) {
      const uint32_t id = s.input.ids[k];
      const std::function<void(uint32_t, const Cell&)> descend = [&](uint32_t index, const Cell& cell) {
        double lo[3], hi[3];
        Widened(cell, 0.0, lo, hi);
        if (!octree::TriangleOverlapsBox(s.input.triangles[id], lo, hi)) return;
        const Node& n = t.nodes()[index];
        if (n.IsLeaf()) {
          const uint32_t* begin = t.refs().data() + n.FirstRef();
          missing += !std::binary_search(begin, begin + n.Count(), id);
          return;
        }
        float mid[3];
        octree::CellCentre(cell, mid);
        for (int c = 0; c < 8; ++c) {
          const Cell child = octree::ChildCell(cell, mid, c);
          if (n.HasChild(c)) {
            descend(n.Child(c), child);
            continue;
          }
          Widened(child, 0.0, lo, hi);
          missing += octree::TriangleOverlapsBox(s.input.triangles[id], lo, hi);  // an empty child
        }
      };
      descend(0, t.root_cell());
    }
    EXPECT_EQ(missing, 0u) << g;
  }
}

TEST(OctreeTest, SeparatingAxisTest) {
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  auto tri = [](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    img::TriangleRecord t;
    for (int k = 0; k < 3; ++k) {
      t.v0[k] = a[k];
      t.v1[k] = b[k];
      t.v2[k] = c[k];
    }
    return t;
  };
  // Boxes overlap, the plane x + y + z = 3.5 passes beyond the far corner.
  EXPECT_FALSE(octree::TriangleOverlapsBox(tri({3.5f, 0, 0}, {0, 3.5f, 0}, {0, 0, 3.5f}), lo, hi));
  // The plane x + y + z = 3 touches the far corner: touching overlaps.
  EXPECT_TRUE(octree::TriangleOverlapsBox(tri({3, 0, 0}, {0, 3, 0}, {0, 0, 3}), lo, hi));
  EXPECT_TRUE(octree::TriangleOverlapsBox(tri({2.9f, 0, 0}, {0, 2.9f, 0}, {0, 0, 2.9f}), lo, hi));
  // In the plane z = 0.5, beyond the edge line x + y = 2: only an edge
  // cross axis separates it.
  EXPECT_FALSE(octree::TriangleOverlapsBox(tri({2.2f, 0, 0.5f}, {0, 2.2f, 0.5f}, {3, 3, 0.5f}), lo, hi));
  EXPECT_TRUE(octree::TriangleOverlapsBox(tri({1.8f, 0, 0.5f}, {0, 1.8f, 0.5f}, {3, 3, 0.5f}), lo, hi));
  // Far away on one axis; and a big triangle containing the whole box.
  EXPECT_FALSE(octree::TriangleOverlapsBox(tri({0, 0, 5}, {1, 0, 5}, {0, 1, 5}), lo, hi));
  EXPECT_TRUE(octree::TriangleOverlapsBox(tri({-10, -10, 0.5f}, {30, -10, 0.5f}, {-10, 30, 0.5f}), lo, hi));
}

TEST(OctreeTest, DeeperLimitTestsFewerTrianglesOnAClusteredScene) {
  const Scene scene = GenerateScene("tree", 10000);
  double previous = INFINITY;
  for (int depth : {1, 3, 5, -1}) {
    StructureOptions options;
    options.octree_max_depth = depth;
    const OctreeScene s(scene, options);
    const Work w = CameraWork(s, 48);
    std::printf("[ octree   ] tree:10000 depth limit %d (max depth %u): %.2f nodes, %.2f tests per ray\n", depth,
                s.structure->stats().max_depth, w.nodes, w.tests);
    EXPECT_LT(w.tests, 0.8 * previous) << "depth " << depth;
    previous = w.tests;
  }
}

TEST(OctreeTest, MailboxSavesTestsOnLargeTriangles) {
  const OctreeScene s(GenerateScene("room", 3000));
  const Work w = CameraWork(s, 48);
  EXPECT_GT(w.mailbox_hits, 0.5);
  EXPECT_TRUE(s.structure->uses_mailbox());
}

TEST(OctreeTest, EmptySceneBuildsAndMisses) {
  const Scene empty = FromTriangles({});
  Prepared p(empty);
  const StructureInput input = MakeStructureInput(p.view());
  const std::unique_ptr<Structure> s = BuildOctree(input, StructureOptions{});
  EXPECT_EQ(s->stats().nodes, 1u);
  EXPECT_EQ(s->stats().leaves, 0u);
  EXPECT_EQ(s->stats().references, 0u);
  std::vector<Ray> rays;
  for (int i = 0; i < 50; ++i) {
    const float a = 0.3f * i;
    rays.push_back(Ray{glm::vec3(std::cos(a), std::sin(a), 0.5f) * 3.0f, glm::vec3(-std::cos(a), -std::sin(a), -0.2f),
                       0.0f, INFINITY});
  }
  rays.push_back(Ray{glm::vec3(0.0f), glm::vec3(1, 0, 0), 0.0f, INFINITY});  // through the zero box
  for (const char* format : {"fp32", "fp64"}) {
    TraceOptions o;
    o.format = fp::ParseFormat(format);
    for (const Hit& h : TraceStructureRays(*s, p.view().frame(), rays, o)) EXPECT_FALSE(h.IsHit()) << format;
  }
}

TEST(OctreeTest, OneTriangle) {
  const OctreeScene s(FromTriangles({Triangle{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}}));
  EXPECT_EQ(s.structure->stats().nodes, 1u);
  EXPECT_EQ(s.structure->stats().references, 1u);
  std::vector<Ray> rays;
  for (float x = -1.0f; x <= 5.0f; x += 0.25f) {
    for (float y = -1.0f; y <= 5.0f; y += 0.25f) rays.push_back(Ray{{x, y, 3.0f}, {0, 0, -1}, 0.0f, INFINITY});
  }
  TraceScratch scratch(1);
  const Hit inside = TraceStructureOne(*s.structure, s.image().frame(), Ray{{1, 1, 3}, {0, 0, -1}, 0, INFINITY},
                                       TraceOptions{}, scratch);
  ASSERT_TRUE(inside.IsHit());
  EXPECT_EQ(inside.prim, 0u);
  EXPECT_EQ(inside.t, 3.0f);
  const Hit beside = TraceStructureOne(*s.structure, s.image().frame(), Ray{{3, 3, 3}, {0, 0, -1}, 0, INFINITY},
                                       TraceOptions{}, scratch);
  EXPECT_FALSE(beside.IsHit());
  ExpectExactHits(s, rays, "one triangle", 100);
}

// All triangles in the plane z = 0: the frame's z extent is zero, so the
// octree splits x and y only (the upper z children stay empty).
TEST(OctreeTest, FlatSceneSplitsItsTwoWideAxes) {
  std::vector<Triangle> tris;
  const int n = 40;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const glm::vec3 a(i, j, 0), b(i + 1, j, 0), c(i, j + 1, 0), d(i + 1, j + 1, 0);
      tris.push_back(Triangle{a, b, d});
      tris.push_back(Triangle{a, d, c});
    }
  }
  const OctreeScene s(FromTriangles(tris));
  EXPECT_EQ(s.tree().root_cell().lo[2], s.tree().root_cell().hi[2]);
  EXPECT_GT(s.structure->stats().max_depth, 3u);
  EXPECT_LT(s.structure->stats().references, 8 * tris.size());
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-2.0f, 42.0f);
  std::vector<Ray> rays;
  for (int i = 0; i < 3000; ++i) {
    const glm::vec3 o(u(rng), u(rng), 10.0f), target(u(rng), u(rng), 0.0f);
    rays.push_back(Ray{o, target - o, 0.0f, INFINITY});
  }
  for (int i = 0; i <= n; ++i) {  // straight down onto the grid lines and vertices
    rays.push_back(Ray{{float(i), 17.5f, 5.0f}, {0, 0, -1}, 0.0f, INFINITY});
    rays.push_back(Ray{{float(i), float(i), 5.0f}, {0, 0, -1}, 0.0f, INFINITY});
  }
  ExpectExactHits(s, rays, "flat grid", 1000);
}

// Rays lying in the octree's mid planes (of the cells down to depth 2 and a
// sample of deeper ones),
// along the lines where two of them meet, and rays starting exactly on the
// scene box's faces: the cases the slack must cover.
TEST(OctreeTest, RaysOnMidPlanesAndFromBoxFacesFindTheClosestHit) {
  for (const char* g : {"room", "balls", "tetra", "gears"}) {
    const OctreeScene s(GenerateScene(g, 2000));
    const Octree& t = s.tree();
    const Frame frame = s.image().frame();
    std::vector<Ray> plane_rays, face_rays;
    size_t inexact = 0;
    auto add = [&](std::vector<Ray>& set, const glm::vec3& framed_o, const glm::vec3& d) {
      Ray r;
      if (testing::RayAtFramedPoint(frame, framed_o, d, &r)) {
        set.push_back(r);
      } else {
        ++inexact;
      }
    };
    size_t inner = 0;
    Walk(t, [&](const Node& n, const Cell& cell, int depth) {
      if (n.IsLeaf()) return;
      if (depth > 2 && ++inner % 16 != 0) return;  // all planes down to depth 2, a sample below
      float mid[3];
      octree::CellCentre(cell, mid);
      for (int k = 0; k < 3; ++k) {
        const int u = (k + 1) % 3, v = (k + 2) % 3;
        for (int i = 1; i < 4; ++i) {
          glm::vec3 o;
          o[k] = mid[k];
          o[u] = cell.lo[u] + (cell.hi[u] - cell.lo[u]) * 0.25f * i;
          o[v] = cell.lo[v] - 1.0f;  // from outside the cell, in the plane
          glm::vec3 along(0.0f), diagonal(0.0f);
          along[v] = 1.0f;
          diagonal[u] = 0.5f;
          diagonal[v] = 1.0f;
          add(plane_rays, o, along);
          add(plane_rays, o, diagonal);
          o[v] = mid[v];  // on the line where two mid planes meet, and through the centre
          glm::vec3 line(0.0f);
          line[u] = -1.0f;
          add(plane_rays, o, line);
          o[u] = mid[u];
          add(plane_rays, o, glm::vec3(1.0f, 1.0f, 1.0f));
          add(plane_rays, o, -along);
        }
      }
    });
    const Cell& box = t.root_cell();
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    std::normal_distribution<float> gauss;
    for (int i = 0; i < 600; ++i) {
      const int k = i % 3;
      glm::vec3 o;
      for (int j = 0; j < 3; ++j) o[j] = box.lo[j] + (box.hi[j] - box.lo[j]) * u01(rng);
      o[k] = (i / 3) % 2 ? box.hi[k] : box.lo[k];
      glm::vec3 d(gauss(rng), gauss(rng), gauss(rng));
      if (i % 7 == 0) d[k] = 0.0f;  // along the face
      add(face_rays, o, d);
    }
    std::printf("[ octree   ] %s: %zu rays skipped (no world origin maps exactly onto the plane)\n", g, inexact);
    EXPECT_GE(plane_rays.size(), 400u) << g;
    EXPECT_GE(face_rays.size(), 300u) << g;
    ExpectExactHits(s, plane_rays, std::string(g) + " mid-plane rays", 20);
    ExpectExactHits(s, face_rays, std::string(g) + " box-face rays", 20);
  }
}

TEST(OctreeTest, Deterministic) {
  const Scene scene = GenerateScene("gears", 3000);
  const OctreeScene a(scene), b(scene);
  EXPECT_EQ(a.structure->stats().nodes, b.structure->stats().nodes);
  EXPECT_EQ(a.structure->stats().references, b.structure->stats().references);
  EXPECT_EQ(a.structure->stats().memory_bytes, b.structure->stats().memory_bytes);
  EXPECT_EQ(a.structure->stats().extra, b.structure->stats().extra);
  EXPECT_EQ(a.tree().refs(), b.tree().refs());
  ASSERT_EQ(a.tree().nodes().size(), b.tree().nodes().size());
  for (size_t i = 0; i < a.tree().nodes().size(); ++i) {
    EXPECT_EQ(a.tree().nodes()[i].first, b.tree().nodes()[i].first);
    EXPECT_EQ(a.tree().nodes()[i].meta, b.tree().nodes()[i].meta);
  }
  const std::vector<Ray> rays = testing::CameraRays(scene, 32);
  const std::vector<Hit> ha = TraceStructureRays(*a.structure, a.image().frame(), rays, TraceOptions{});
  const std::vector<Hit> hb = TraceStructureRays(*b.structure, b.image().frame(), rays, TraceOptions{});
  for (size_t i = 0; i < rays.size(); ++i) EXPECT_TRUE(testing::SameBits(ha[i], hb[i])) << i;
}

TEST(OctreeTest, StatsAndOptions) {
  StructureOptions options;
  options.octree_max_prims = 3;
  options.octree_max_depth = 4;
  const OctreeScene s(GenerateScene("balls", 3000), options);
  const StructureStats& st = s.structure->stats();
  EXPECT_EQ(st.extra["max_prims"], 3);
  EXPECT_EQ(st.extra["depth_limit"], 4);
  EXPECT_LE(st.max_depth, 4u);
  EXPECT_EQ(st.nodes, s.tree().nodes().size());
  EXPECT_EQ(st.memory_bytes, st.nodes * sizeof(Node) + st.references * sizeof(uint32_t));
  EXPECT_GT(st.build_seconds, 0.0);
  EXPECT_EQ(s.structure->kind(), AccelKind::kOctree);
  EXPECT_EQ(octree::DefaultMaxDepth(0), 0);
  EXPECT_LE(octree::DefaultMaxDepth(size_t{1} << 40), octree::kMaxDepth);

  options.octree_max_prims = 0;
  EXPECT_THROW(BuildOctree(s.input, options), InputError);
  options.octree_max_prims = 8;
  options.octree_max_depth = 33;
  EXPECT_THROW(BuildOctree(s.input, options), InputError);
}

}  // namespace
}  // namespace kdrt
