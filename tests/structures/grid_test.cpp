// The uniform and hierarchical grids (structures/grid.cpp, hgrid.cpp): the
// resolution rule, complete binning, sub-grids where triangles cluster, the
// mailbox, edge cases (no triangles, one triangle, rays on cell planes and
// box faces) and exactness against brute force and the kd-tree.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "common/error.h"
#include "fp/ftz.h"
#include "structures/grid_level.h"
#include "structures/structure.h"
#include "structures/structure_tracer.h"
#include "tests/structures/structures_test_util.h"

namespace kdrt {
namespace {

using testing::BruteForceHits;
using testing::FromTriangles;
using testing::InsideRays;

constexpr AccelKind kGridKinds[] = {AccelKind::kGrid, AccelKind::kHgrid};

const grid::Cells& CellsOf(const Structure& s) {
  const auto* view = dynamic_cast<const grid::CellsView*>(&s);
  if (view == nullptr) throw std::logic_error("not a grid");
  return view->cells();
}

TraceOptions Options(const char* format, Query query = Query::kClosest) {
  TraceOptions o;
  o.format = fp::ParseFormat(format);
  o.query = query;
  return o;
}

size_t CountDiffering(const std::vector<Hit>& expected, const std::vector<Hit>& got, const std::vector<Ray>& rays,
                      const std::string& what) {
  size_t differ = 0;
  for (size_t i = 0; i < expected.size(); ++i) {
    if (SameBits(expected[i], got[i])) continue;
    if (++differ <= 3) {
      ADD_FAILURE() << what << " ray " << i << " (o " << rays[i].o.x << " " << rays[i].o.y << " " << rays[i].o.z
                    << ", d " << rays[i].d.x << " " << rays[i].d.y << " " << rays[i].d.z << ", tmax " << rays[i].tmax
                    << "): expected " << HitText(expected[i]) << ", got " << HitText(got[i]);
    }
  }
  return differ;
}

AccelTotals Work(const Structure& s, const ImageView& image, const std::vector<Ray>& rays) {
  AccelTotals totals;
  TraceStructureRays(s, image.frame(), rays, Options("fp32"), &totals);
  return totals;
}

Scene HandScene(std::vector<Triangle> tris) {
  Scene s;
  s.triangles = std::move(tris);
  s.material.assign(s.triangles.size(), 0);
  s.colors = {glm::vec3(1)};
  s.finishes = {Finish{}};
  s.source = "hand-made";
  return s;
}

// ---------------------------------------------------------------------------

TEST(GridResolution, FollowsTheDensityRule) {
  const double cube[3] = {2, 2, 2};
  const grid::Resolution r1 = grid::ChooseResolution(cube, 1000, 1.0, grid::kMaxCellsPerLevel);
  EXPECT_EQ(r1.n[0], 10);
  EXPECT_EQ(r1.n[1], 10);
  EXPECT_EQ(r1.n[2], 10);
  EXPECT_FALSE(r1.clamped);
  const grid::Resolution r8 = grid::ChooseResolution(cube, 1000, 8.0, grid::kMaxCellsPerLevel);
  EXPECT_EQ(r8.cells(), 8 * r1.cells());

  // Cells as close to cubes as possible in a 4:2:1 box.
  const double slab[3] = {4, 2, 1};
  const grid::Resolution rs = grid::ChooseResolution(slab, 512, 1.0, grid::kMaxCellsPerLevel);
  EXPECT_EQ(rs.n[0], 16);
  EXPECT_EQ(rs.n[1], 8);
  EXPECT_EQ(rs.n[2], 4);
}

TEST(GridResolution, FlatBoxesGetOneCellAcross) {
  const double flat[3] = {3, 0, 3};
  const grid::Resolution f = grid::ChooseResolution(flat, 100, 4.0, grid::kMaxCellsPerLevel);
  EXPECT_EQ(f.n[1], 1);
  EXPECT_EQ(f.n[0], 20);
  EXPECT_EQ(f.n[2], 20);
  // Nearly flat: the thin axis would get far less than a cell; the budget
  // goes to the other two instead of exploding them.
  const double thin[3] = {3, 1e-7, 3};
  const grid::Resolution t = grid::ChooseResolution(thin, 100, 4.0, grid::kMaxCellsPerLevel);
  EXPECT_EQ(t.n[1], 1);
  EXPECT_EQ(t.cells(), f.cells());
  const double line[3] = {0, 5, 0};
  EXPECT_EQ(grid::ChooseResolution(line, 100, 2.0, grid::kMaxCellsPerLevel).n[1], 200);
  const double point[3] = {0, 0, 0};
  EXPECT_EQ(grid::ChooseResolution(point, 100, 2.0, grid::kMaxCellsPerLevel).cells(), 1u);
  const double box[3] = {1, 2, 3};
  EXPECT_EQ(grid::ChooseResolution(box, 0, 2.0, grid::kMaxCellsPerLevel).cells(), 1u);
}

TEST(GridResolution, ClampsTheCellCount) {
  const double cube[3] = {1, 1, 1};
  const grid::Resolution r = grid::ChooseResolution(cube, 1000000, 100.0, 4096);
  EXPECT_TRUE(r.clamped);
  EXPECT_LE(r.cells(), 4096u);
  EXPECT_GE(r.cells(), 3000u);
  EXPECT_EQ(r.n[0], r.n[1]);
  EXPECT_EQ(r.n[1], r.n[2]);
}

// Every list ascending without repeats, every non-degenerate triangle in at
// least one list and no degenerate one in any, a cell with a sub-grid holds
// no list, and the statistics count what is there.
void ExpectCompleteLists(const Structure& s, const StructureInput& in, const std::string& what) {
  const grid::Cells& c = CellsOf(s);
  std::vector<uint32_t> times(in.triangles.size(), 0);
  uint64_t sum = 0;
  uint32_t longest = 0;
  for (uint32_t cell = 0; cell < c.cell_count(); ++cell) {
    const uint32_t b = c.begin[cell], e = c.begin[cell + 1];
    if (!c.child.empty() && c.child[cell] != 0) {
      EXPECT_EQ(b, e) << what << " cell " << cell;
    }
    for (uint32_t k = b; k < e; ++k) {
      ++times[c.refs[k]];
      if (k > b) {
        EXPECT_LT(c.refs[k - 1], c.refs[k]) << what << " cell " << cell;
      }
    }
    sum += e - b;
    longest = std::max(longest, e - b);
  }
  EXPECT_EQ(sum, c.refs.size()) << what;
  EXPECT_EQ(s.stats().references, sum) << what;
  EXPECT_EQ(s.stats().max_leaf_prims, longest) << what;
  EXPECT_EQ(s.stats().nodes, c.cell_count()) << what;
  EXPECT_GE(s.stats().memory_bytes, sizeof(uint32_t) * (c.cell_count() + sum)) << what;
  std::vector<bool> usable(in.triangles.size(), false);
  for (uint32_t id : in.ids) usable[id] = true;
  size_t unlisted = 0, degenerate_listed = 0;
  for (uint32_t id = 0; id < in.triangles.size(); ++id) {
    if (usable[id]) {
      unlisted += times[id] == 0;
    } else {
      degenerate_listed += times[id] != 0;
    }
  }
  EXPECT_EQ(unlisted, 0u) << what;
  EXPECT_EQ(degenerate_listed, 0u) << what;
}

// Every triangle that meets a cell (not widened) is in its list: the
// binning misses nothing, on every level.
void ExpectListsHoldOverlaps(const Structure& s, const StructureInput& in, const std::string& what) {
  const grid::Cells& c = CellsOf(s);
  std::vector<TriangleBoxTest> tests;
  for (uint32_t id : in.ids) tests.emplace_back(in.triangles[id]);
  size_t missing = 0, checked = 0;
  for (const grid::Level& g : c.levels) {
    const float* p[3] = {&c.planes[g.plane_offset[0]], &c.planes[g.plane_offset[1]], &c.planes[g.plane_offset[2]]};
    for (int z = 0; z < g.n[2]; ++z) {
      for (int y = 0; y < g.n[1]; ++y) {
        for (int x = 0; x < g.n[0]; ++x) {
          const uint32_t cell = g.first_cell + uint32_t(x) + uint32_t(y) * g.stride[1] + uint32_t(z) * g.stride[2];
          if (!c.child.empty() && c.child[cell] != 0) continue;
          const double lo[3] = {p[0][x], p[1][y], p[2][z]};
          const double hi[3] = {p[0][x + 1], p[1][y + 1], p[2][z + 1]};
          const uint32_t* b = c.refs.data() + c.begin[cell];
          const uint32_t* e = c.refs.data() + c.begin[cell + 1];
          for (size_t i = 0; i < in.ids.size(); ++i) {
            const accel::Box& box = in.boxes[in.ids[i]];
            bool apart = false;
            for (int a = 0; a < 3; ++a) apart = apart || box.lo[a] > hi[a] || box.hi[a] < lo[a];
            if (apart || !tests[i].Overlaps(lo, hi)) continue;
            ++checked;
            missing += !std::binary_search(b, e, in.ids[i]);
          }
        }
      }
    }
  }
  EXPECT_GT(checked, in.ids.size()) << what;
  EXPECT_EQ(missing, 0u) << what;
}

struct Built {
  std::string name;
  std::unique_ptr<Structure> s;
};

std::vector<Built> BuildVariants(const StructureInput& input) {
  std::vector<Built> v;
  StructureOptions o;
  v.push_back({"grid", BuildGrid(input, o)});
  o.grid_density = 0.5;
  v.push_back({"grid d=0.5", BuildGrid(input, o)});
  o.grid_density = 16;
  v.push_back({"grid d=16", BuildGrid(input, o)});
  v.push_back({"hgrid", BuildHgrid(input, StructureOptions{})});
  o = StructureOptions{};
  o.hgrid_density = 4;
  v.push_back({"hgrid d=4", BuildHgrid(input, o)});
  o.hgrid_max_prims = 2;
  o.hgrid_max_levels = 4;
  v.push_back({"hgrid deep", BuildHgrid(input, o)});
  return v;
}

// Each structure returns the brute-force hit on every ray, and the
// kd-tree's wherever the kd-tree returns the brute-force hit. (The kd-tree's
// early stop may keep a hit a few ulps behind the closest one when the two
// lie on either side of one of its splits within the traversal slack: that
// deviation is its own, counted and printed.) Any-hit answers hit or miss as
// the closest hit does.
void ExpectExact(const std::vector<Built>& structures, const ImageView& image, const std::vector<Ray>& rays,
                 const std::string& what) {
  for (const char* format : {"fp32", "fp64"}) {
    const std::vector<Hit> brute = BruteForceHits(image, rays, format);
    const std::vector<Hit> kd = TraceRays(image, rays, Options(format));
    size_t kd_deviates = 0;
    for (size_t i = 0; i < rays.size(); ++i) kd_deviates += !SameBits(kd[i], brute[i]);
    if (kd_deviates > 0) {
      std::printf("[ note     ] %s %s: the kd-tree differs from brute force on %zu of %zu rays\n", what.c_str(),
                  format, kd_deviates, rays.size());
    }
    for (const Built& b : structures) {
      const std::string label = what + " " + b.name + " " + format;
      const std::vector<Hit> ours = TraceStructureRays(*b.s, image.frame(), rays, Options(format));
      EXPECT_EQ(CountDiffering(brute, ours, rays, label + " vs brute force"), 0u) << label;
      size_t differ = 0;
      for (size_t i = 0; i < rays.size(); ++i) differ += SameBits(kd[i], brute[i]) && !SameBits(kd[i], ours[i]);
      EXPECT_EQ(differ, 0u) << label << " vs kd-tree";
      const std::vector<Hit> any = TraceStructureRays(*b.s, image.frame(), rays, Options(format, Query::kAny));
      size_t hitmiss = 0;
      for (size_t i = 0; i < rays.size(); ++i) hitmiss += any[i].IsHit() != brute[i].IsHit();
      EXPECT_EQ(hitmiss, 0u) << label << " any-hit";
    }
  }
}

TEST(GridStructure, CellCountFollowsTheDensity) {
  testing::Prepared p(GenerateScene("balls", 3000));
  const StructureInput input = MakeStructureInput(p.view());
  StructureOptions o1, o8;
  o1.grid_density = 1;
  o8.grid_density = 8;
  const auto g1 = BuildGrid(input, o1);
  const auto g8 = BuildGrid(input, o8);
  const double ratio = double(g8->stats().nodes) / double(g1->stats().nodes);
  EXPECT_GT(ratio, 6.5);
  EXPECT_LT(ratio, 9.5);
  EXPECT_NEAR(double(g1->stats().nodes) / double(input.ids.size()), 1.0, 0.35);
  for (const Structure* g : {g1.get(), g8.get()}) {
    const nlohmann::json& extra = g->stats().extra;
    ASSERT_TRUE(extra.contains("resolution"));
    const nlohmann::json& n = extra["resolution"];
    const uint64_t product = n[0].get<uint64_t>() * n[1].get<uint64_t>() * n[2].get<uint64_t>();
    EXPECT_EQ(product, g->stats().nodes);
    EXPECT_FALSE(extra.contains("clamped"));
    EXPECT_EQ(g->stats().max_depth, 0u);
  }
  EXPECT_EQ(g8->stats().extra["density"].get<double>(), 8.0);
}

TEST(GridStructure, ListsAreCompleteAndCounted) {
  for (const char* g : {"room", "tetra", "tree", "gears"}) {
    testing::Prepared p(GenerateScene(g, 3000));
    const StructureInput input = MakeStructureInput(p.view());
    for (const Built& b : BuildVariants(input)) ExpectCompleteLists(*b.s, input, std::string(g) + " " + b.name);
  }
}

TEST(GridStructure, ListsHoldEveryOverlappingTriangle) {
  for (const char* g : {"tetra", "tree", "rings"}) {
    testing::Prepared p(GenerateScene(g, 300));
    const StructureInput input = MakeStructureInput(p.view());
    for (const Built& b : BuildVariants(input)) ExpectListsHoldOverlaps(*b.s, input, std::string(g) + " " + b.name);
  }
}

TEST(GridStructure, HgridRefinesAClusteredScene) {
  testing::Prepared p(GenerateScene("tree", 20000));
  const ImageView image = p.view();
  const StructureInput input = MakeStructureInput(image);
  const auto g = BuildGrid(input, StructureOptions{});
  StructureOptions same_top;  // the grid's density, so the top levels are alike
  same_top.hgrid_density = same_top.grid_density;
  const auto h = BuildHgrid(input, same_top);
  EXPECT_GT(h->stats().extra["subgrids"].get<uint64_t>(), 0u);
  EXPECT_GE(h->stats().max_depth, 1u);
  EXPECT_LT(h->stats().max_depth, uint32_t(StructureOptions{}.hgrid_max_levels));
  EXPECT_EQ(h->stats().extra["resolution"], g->stats().extra["resolution"]);
  const std::vector<Ray> rays = testing::CameraRays(p.scene, 64);
  const AccelTotals gw = Work(*g, image, rays);
  const AccelTotals hw = Work(*h, image, rays);
  std::printf("[ work     ] tree:20000 tests per ray: grid %.2f, hgrid %.2f\n", double(gw.tri_tests) / rays.size(),
              double(hw.tri_tests) / rays.size());
  EXPECT_LT(double(hw.tri_tests), 0.8 * double(gw.tri_tests));

  // One level is the uniform grid.
  StructureOptions one = same_top;
  one.hgrid_max_levels = 1;
  const auto flat = BuildHgrid(input, one);
  EXPECT_EQ(flat->stats().extra["subgrids"].get<uint64_t>(), 0u);
  EXPECT_EQ(flat->stats().nodes, g->stats().nodes);
  EXPECT_EQ(flat->stats().references, g->stats().references);
  EXPECT_EQ(Work(*flat, image, rays).tri_tests, gw.tri_tests);
}

TEST(GridStructure, MailboxSavesTestsOnLargeTriangles) {
  testing::Prepared p(GenerateScene("room", 3000));
  const ImageView image = p.view();
  const StructureInput input = MakeStructureInput(image);
  const std::vector<Ray> rays = testing::CameraRays(p.scene, 48);
  for (AccelKind kind : kGridKinds) {
    const auto s = BuildStructure(kind, input, StructureOptions{});
    EXPECT_TRUE(s->uses_mailbox());
    EXPECT_GT(s->stats().references, input.ids.size());
    const AccelTotals w = Work(*s, image, rays);
    EXPECT_GT(w.mailbox_hits, rays.size() / 4) << AccelKindName(kind);
    EXPECT_GT(w.nodes, w.leaves) << AccelKindName(kind);
  }
}

// Rays through a region, for the hand-made scenes.
std::vector<Ray> RaysThrough(float extent, size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-extent, extent);
  std::vector<Ray> rays;
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3 from(u(rng) * 3, u(rng) * 3, u(rng) * 3);
    const glm::vec3 to(u(rng), u(rng), u(rng));
    rays.push_back(Ray{from, to - from});
  }
  return rays;
}

TEST(GridStructure, SceneWithoutTrianglesMisses) {
  const Triangle degenerate{{1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
  for (const std::vector<Triangle>& tris : {std::vector<Triangle>{}, std::vector<Triangle>{degenerate}}) {
    testing::Prepared p(HandScene(tris));
    const ImageView image = p.view();
    const StructureInput input = MakeStructureInput(image);
    const std::vector<Ray> rays = RaysThrough(4, 200, 3);
    for (AccelKind kind : kGridKinds) {
      const auto s = BuildStructure(kind, input, StructureOptions{});
      EXPECT_EQ(s->stats().references, 0u);
      EXPECT_GE(s->stats().nodes, 1u);
      for (const char* format : {"fp32", "fp64"}) {
        for (Query q : {Query::kClosest, Query::kAny}) {
          size_t hits = 0;
          for (const Hit& h : TraceStructureRays(*s, image.frame(), rays, Options(format, q))) hits += h.IsHit();
          EXPECT_EQ(hits, 0u) << AccelKindName(kind) << " " << format << " " << tris.size();
        }
      }
    }
  }
}

TEST(GridStructure, OneTriangle) {
  // Id 0 is degenerate, so the hit must name id 1.
  testing::Prepared p(HandScene({{{0, 0, 0}, {0, 0, 0}, {1, 1, 1}}, {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}}));
  const ImageView image = p.view();
  const StructureInput input = MakeStructureInput(image);
  std::vector<Ray> rays = RaysThrough(1.2f, 300, 5);
  for (int i = -6; i <= 6; ++i) {
    for (int j = -6; j <= 6; ++j) {
      rays.push_back(Ray{{i * 0.2f, j * 0.2f, 3}, {0, 0, -1}});    // down onto it
      rays.push_back(Ray{{i * 0.2f, j * 0.2f, 3}, {0, 0, 1}});     // away from it
      rays.push_back(Ray{{i * 0.2f, j * 0.2f, 0}, {0.3f, 0, 1}});  // from its plane
    }
  }
  std::vector<Built> structures;
  for (AccelKind kind : kGridKinds) structures.push_back({AccelKindName(kind), BuildStructure(kind, input, {})});
  ExpectExact(structures, image, rays, "one triangle");
  size_t hits = 0, wrong = 0;
  for (const Hit& h : TraceStructureRays(*structures[0].s, image.frame(), rays, Options("fp32"))) {
    hits += h.IsHit();
    wrong += h.IsHit() && h.prim != 1;
  }
  EXPECT_GT(hits, 50u);
  EXPECT_EQ(wrong, 0u);
}

// A scene whose frame is the identity (box [-8, 8]^3 centred on the origin)
// and whose uniform grid is 8 x 8 x 8 (1024 triangles, density 0.5), so the
// cell planes are the even integers and rays can be put exactly on them.
// Several triangles lie in cell planes or on the box faces, or have their
// vertices on cell corners; clusters of small ones give the hierarchical
// grid sub-grids.
Scene PlaneScene() {
  std::vector<Triangle> t;
  t.push_back({{-8, -8, -8}, {-7, -8, -8}, {-8, -7, -8}});
  t.push_back({{8, 8, 8}, {7, 8, 8}, {8, 7, 8}});
  // Quads (two triangles) in the cell planes x = -2, y = 0, z = 6 and on the
  // box faces x = 8, y = -8.
  auto quad = [&](int axis, float at, float lo, float hi) {
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    glm::vec3 v[4];
    for (int k = 0; k < 4; ++k) {
      v[k][axis] = at;
      v[k][b] = k == 1 || k == 2 ? hi : lo;
      v[k][c] = k >= 2 ? hi : lo;
    }
    t.push_back({v[0], v[1], v[2]});
    t.push_back({v[0], v[2], v[3]});
  };
  quad(0, -2, -4, 4);
  quad(1, 0, -6, 6);
  quad(2, 6, -4, 4);
  quad(0, 8, -6, 6);
  quad(1, -8, -6, 2);
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> node(-4, 4);
  while (t.size() < 64) {  // corners on cell corners
    const Triangle tri{glm::vec3(node(rng), node(rng), node(rng)) * 2.0f,
                       glm::vec3(node(rng), node(rng), node(rng)) * 2.0f,
                       glm::vec3(node(rng), node(rng), node(rng)) * 2.0f};
    if (!IsDegenerate(tri)) t.push_back(tri);
  }
  std::uniform_real_distribution<float> u(-6.5f, 6.5f), small(-1.0f, 1.0f);
  while (t.size() < 128) {
    const glm::vec3 c(u(rng), u(rng), u(rng));
    const Triangle tri{c + glm::vec3(small(rng), small(rng), small(rng)),
                       c + glm::vec3(small(rng), small(rng), small(rng)),
                       c + glm::vec3(small(rng), small(rng), small(rng))};
    if (!IsDegenerate(tri)) t.push_back(tri);
  }
  // One loose cluster across cell planes, one dense one inside a cell.
  std::uniform_real_distribution<float> loose(-1.0f, 3.0f), dense(-5.5f, -4.5f), tiny(-0.1f, 0.1f);
  while (t.size() < 1024) {
    const bool odd = t.size() % 2;
    const glm::vec3 c =
        odd ? glm::vec3(loose(rng), loose(rng), loose(rng)) : glm::vec3(dense(rng), dense(rng), dense(rng));
    const float scale = odd ? 2.0f : 0.5f;
    const Triangle tri{c + scale * glm::vec3(tiny(rng), tiny(rng), tiny(rng)),
                       c + scale * glm::vec3(tiny(rng), tiny(rng), tiny(rng)),
                       c + scale * glm::vec3(tiny(rng), tiny(rng), tiny(rng))};
    if (!IsDegenerate(tri)) t.push_back(tri);
  }
  return HandScene(t);
}

// Rays lying in the given planes of each axis: along cell edges (two
// coordinates on planes), inside a plane in other directions, and ending
// exactly on a plane.
void AddPlaneRays(const std::vector<float> planes[3], std::mt19937& rng, std::vector<Ray>* rays) {
  std::uniform_real_distribution<float> u(-9.0f, 9.0f);
  std::normal_distribution<float> gauss;
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (float pa : planes[a]) {
      for (float pb : planes[b]) {
        for (float dir : {1.0f, -1.0f}) {
          Ray r;
          r.o[a] = pa;
          r.o[b] = pb;
          r.o[c] = -20 * dir;
          r.d = glm::vec3(0);
          r.d[c] = dir;
          rays->push_back(r);
          r.o[c] = u(rng);  // from inside, to a plane
          r.tmax = std::fabs(planes[c][planes[c].size() / 2] - r.o[c]);
          rays->push_back(r);
        }
      }
      for (int k = 0; k < 4; ++k) {
        Ray r;
        r.o[a] = pa;
        r.o[b] = u(rng);
        r.o[c] = u(rng);
        r.d = glm::vec3(gauss(rng), gauss(rng), gauss(rng));
        r.d[a] = 0;
        rays->push_back(r);
      }
    }
  }
}

TEST(GridStructure, RaysOnCellPlanesAndBoxFaces) {
  testing::Prepared p(PlaneScene());
  const ImageView image = p.view();
  ASSERT_EQ(image.frame().scale_log2, 0);
  for (int a = 0; a < 3; ++a) ASSERT_EQ(image.frame().origin[a], 0.0f);
  const StructureInput input = MakeStructureInput(image);
  ASSERT_EQ(input.ids.size(), 1024u);
  std::vector<Built> structures;
  StructureOptions o;
  o.grid_density = 0.5;
  structures.push_back({"grid", BuildGrid(input, o)});
  StructureOptions deep = o;
  deep.hgrid_density = o.grid_density;
  deep.hgrid_max_prims = 4;
  deep.hgrid_max_levels = 4;
  structures.push_back({"hgrid deep", BuildHgrid(input, deep)});
  const grid::Cells& top = CellsOf(*structures[0].s);
  for (int a = 0; a < 3; ++a) ASSERT_EQ(top.levels[0].n[a], 8) << a;
  ASSERT_EQ(top.planes[2], -4.0f);
  const grid::Cells& nested = CellsOf(*structures[1].s);
  ASSERT_GT(nested.levels.size(), 4u);
  ASSERT_GE(structures[1].s->stats().max_depth, 2u);

  std::mt19937 rng(21);
  std::vector<Ray> rays;
  std::vector<float> even[3];
  for (int a = 0; a < 3; ++a) {
    for (int k = -4; k <= 4; ++k) even[a].push_back(2.0f * k);
  }
  AddPlaneRays(even, rng, &rays);
  // The sub-grids' planes, a few levels' worth.
  for (size_t l = 1; l < nested.levels.size(); l += std::max<size_t>(1, nested.levels.size() / 6)) {
    std::vector<float> sub[3];
    for (int a = 0; a < 3; ++a) {
      const float* first = &nested.planes[nested.levels[l].plane_offset[a]];
      sub[a].assign(first, first + nested.levels[l].n[a] + 1);
    }
    AddPlaneRays(sub, rng, &rays);
  }
  // From the box faces (and from cell corners on them): inwards, outwards,
  // and along the face.
  std::uniform_real_distribution<float> u(-8.0f, 8.0f);
  std::uniform_int_distribution<int> node(-4, 4);
  std::normal_distribution<float> gauss;
  for (int i = 0; i < 600; ++i) {
    const int a = i % 3;
    Ray r;
    r.o = i % 2 ? glm::vec3(u(rng), u(rng), u(rng)) : glm::vec3(node(rng), node(rng), node(rng)) * 2.0f;
    r.o[a] = i % 6 < 3 ? 8.0f : -8.0f;
    r.d = glm::vec3(gauss(rng), gauss(rng), gauss(rng));
    if (i % 5 == 0) r.d[a] = 0;
    rays.push_back(r);
  }
  // From cell corners inside, and aimed at cell corners.
  for (int i = 0; i < 300; ++i) {
    const glm::vec3 from = glm::vec3(node(rng), node(rng), node(rng)) * 2.0f;
    const glm::vec3 to = glm::vec3(node(rng), node(rng), node(rng)) * 2.0f;
    if (from != to) rays.push_back(Ray{from, to - from});
    rays.push_back(Ray{from * 2.0f, to - from * 2.0f});
  }
  ExpectExact(structures, image, rays, "plane scene");
}

TEST(GridStructure, BuildIsDeterministic) {
  testing::Prepared p(GenerateScene("gears", 3000));
  const ImageView image = p.view();
  const StructureInput input = MakeStructureInput(image);
  const std::vector<Ray> rays = InsideRays(p.scene, 2000, 9);
  for (AccelKind kind : kGridKinds) {
    const auto s1 = BuildStructure(kind, input, StructureOptions{});
    const auto s2 = BuildStructure(kind, input, StructureOptions{});
    nlohmann::json j1 = StructureStatsJson(s1->stats()), j2 = StructureStatsJson(s2->stats());
    j1.erase("build_seconds");
    j2.erase("build_seconds");
    EXPECT_EQ(j1, j2) << AccelKindName(kind);
    EXPECT_EQ(CellsOf(*s1).refs, CellsOf(*s2).refs);
    EXPECT_EQ(CellsOf(*s1).begin, CellsOf(*s2).begin);
    const std::vector<Hit> h1 = TraceStructureRays(*s1, image.frame(), rays, Options("fp32"));
    const std::vector<Hit> h2 = TraceStructureRays(*s2, image.frame(), rays, Options("fp32"));
    size_t differ = 0;
    for (size_t i = 0; i < rays.size(); ++i) differ += !SameBits(h1[i], h2[i]);
    EXPECT_EQ(differ, 0u);
  }
}

TEST(GridStructure, RejectsBadOptions) {
  testing::Prepared p(GenerateScene("tetra", 100));
  const StructureInput input = MakeStructureInput(p.view());
  StructureOptions o;
  o.grid_density = 0;
  EXPECT_THROW(BuildGrid(input, o), InputError);
  o = StructureOptions{};
  o.hgrid_max_levels = 0;
  EXPECT_THROW(BuildHgrid(input, o), InputError);
}

// Every generator, several densities and a deep hierarchy, camera rays and
// rays starting and ending inside the scene.
class GridExactness : public ::testing::TestWithParam<const char*> {};

TEST_P(GridExactness, SameHitsAsBruteForce) {
  testing::Prepared p(GenerateScene(GetParam(), 1000));
  const ImageView image = p.view();
  const StructureInput input = MakeStructureInput(image);
  std::vector<Ray> rays = testing::CameraRays(p.scene, 40);
  const std::vector<Ray> inside = InsideRays(p.scene, 1000, 17);
  rays.insert(rays.end(), inside.begin(), inside.end());
  ExpectExact(BuildVariants(input), image, rays, GetParam());
}

INSTANTIATE_TEST_SUITE_P(Generators, GridExactness,
                         ::testing::Values("room", "balls", "rings", "tetra", "tree", "gears"),
                         [](const auto& info) { return std::string(info.param); });

// Measurements for the structure comparison, not a check (run with
// --gtest_also_run_disabled_tests --gtest_filter='*GridMeasure*'):
// build time and memory, per-ray work and single-thread speed against the
// kd-tree on camera rays.
void Measure(const char* generator, int size, const std::vector<double>& densities) {
  const auto t0 = std::chrono::steady_clock::now();
  testing::Prepared p(GenerateScene(generator, size));
  const ImageView image = p.view();
  const StructureInput input = MakeStructureInput(image);
  const double prep = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::vector<Ray> rays = testing::CameraRays(p.scene, 256);
  TraceOptions one = Options("fp32");
  one.threads = 1;
  TraceStats kd;
  TraceRays(image, rays, one, &kd);
  std::printf("[ measure  ] %s:%zu (scene + kd-tree %.1f s): kd-tree %.2f Mrays/s, %.2f nodes, %.2f tests per ray\n",
              generator, input.ids.size(), prep, rays.size() / kd.seconds * 1e-6, double(kd.totals.nodes) / rays.size(),
              double(kd.totals.tri_tests) / rays.size());
  for (AccelKind kind : kGridKinds) {
    for (double d : densities) {
      StructureOptions o;
      o.grid_density = o.hgrid_density = d;
      const auto s = BuildStructure(kind, input, o);
      AccelTotals w;
      TraceStructureRays(*s, image.frame(), rays, one, &w);
      const StructureStats& st = s->stats();
      std::printf("[ measure  ] %s d=%g: build %.2f s, %.1f MB, %llu cells, %.2f refs/tri, levels %u; "
                  "%.2f Mrays/s, %.2f cells, %.2f tests, %.2f mailbox hits per ray %s\n",
                  AccelKindName(kind), d, st.build_seconds, st.memory_bytes / 1e6, (unsigned long long)st.nodes,
                  double(st.references) / input.ids.size(), st.max_depth + 1, rays.size() / w.seconds * 1e-6,
                  double(w.nodes) / rays.size(), double(w.tri_tests) / rays.size(),
                  double(w.mailbox_hits) / rays.size(), st.extra.dump().c_str());
    }
  }
}

TEST(GridMeasure, DISABLED_Million) {
  for (const char* g : {"balls", "tree"}) Measure(g, 1000000, {1, 4});
}

TEST(GridMeasure, DISABLED_DensitySweep) {
  for (const char* g : {"balls", "tree"}) Measure(g, 100000, {1, 2, 4, 8, 16});
}

}  // namespace
}  // namespace kdrt
