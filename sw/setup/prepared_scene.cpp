#include "setup/prepared_scene.h"

#include <charconv>
#include <chrono>
#include <cstdio>
#include <string>

#include "common/error.h"
#include "scenes/gen/generators.h"
#include "trace/memory_image.h"

namespace kdrt {

Scene LoadOrGenerate(const SceneSpec& spec) {
  if (spec.scene.rfind("gen:", 0) == 0) {
    // gen:NAME or gen:NAME:SIZE, SIZE all digits: "1e3" or "10:extra" is an
    // error, never a size read up to the first non-digit.
    const std::string rest = spec.scene.substr(4);
    const size_t colon = rest.find(':');
    const std::string name = rest.substr(0, colon);
    int size = 1000;
    if (colon != std::string::npos) {
      const std::string digits = rest.substr(colon + 1);
      if (digits.find(':') != std::string::npos) {
        throw InputError(spec.scene, 0, "expected gen:NAME or gen:NAME:SIZE (one size, no more fields)");
      }
      long long value = 0;
      const char* end = digits.data() + digits.size();
      const auto [ptr, ec] = std::from_chars(digits.data(), end, value);
      if (digits.empty() || ec != std::errc() || ptr != end) {
        throw InputError(spec.scene, 0, "size " + QuoteBytes(digits) + " is not a whole number");
      }
      if (value < 1 || value > kMaxGeneratorSize) {
        throw InputError(spec.scene, 0,
                         "size " + digits + " is outside 1.." + std::to_string(kMaxGeneratorSize));
      }
      size = static_cast<int>(value);
    }
    try {
      LoadOptions tessellation;
      tessellation.cone_aspect = spec.cone_aspect;
      return GenerateScene(name, size, tessellation);
    } catch (const InputError& e) {
      throw InputError(spec.scene, 0, e.what());  // names the spec the user gave
    }
  }
  LoadOptions lo;
  if (spec.sphere_segments > 0) lo.sphere_segments = spec.sphere_segments;
  lo.cone_aspect = spec.cone_aspect;
  lo.strict = spec.strict;
  Scene scene = LoadScene(spec.scene, lo);
  for (const std::string& w : scene.warnings) std::fprintf(stderr, "kdrt: warning: %s\n", w.c_str());
  return scene;
}

PreparedScene PrepareScene(const SceneSpec& spec) {
  const auto start = std::chrono::steady_clock::now();
  Scene scene = LoadOrGenerate(spec);
  const double load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  PreparedScene p = PrepareScene(std::move(scene), spec);
  p.load_seconds = load_seconds;
  return p;
}

PreparedScene PrepareScene(Scene scene, const SceneSpec& spec) {
  if (IsKdTree(spec.accel)) {  // the split rule is spec.build.method
    PreparedScene p = PrepareScene(std::move(scene), spec.build);
    p.accel = AccelKindOf(spec.build.method);
    return p;
  }
  CheckStructureOptions(spec.structure);
  BuildOptions single_leaf = spec.build;
  single_leaf.method = SplitMethod::kMidpoint;
  single_leaf.max_depth = 0;
  PreparedScene p = PrepareScene(std::move(scene), single_leaf);
  p.accel = spec.accel;
  p.structure_input = std::make_unique<StructureInput>(MakeStructureInput(ImageView(p.image)));
  p.structure = BuildStructure(spec.accel, *p.structure_input, spec.structure);
  return p;
}

PreparedScene PrepareScene(Scene scene, const BuildOptions& build) {
  PreparedScene p;
  p.scene = std::move(scene);
  FramedImage framed = BuildFramedImage(p.scene, build);
  p.frame = framed.frame;
  p.tree = std::move(framed.tree);
  p.image = std::move(framed.bytes);
  return p;
}

namespace {

nlohmann::json LeafCausesJson(const LeafCauses& c) {
  if (!c.recorded) return nullptr;
  nlohmann::json j = {{"large_leaf_prims", kLargeLeafPrims}};
  for (int i = 0; i < kLeafCauseCount; ++i) {
    const LeafCauseCount& n = c.by_cause[i];
    j[LeafCauseName(static_cast<LeafCause>(i))] = {
        {"leaves", n.leaves}, {"references", n.references}, {"large", n.large}, {"largest", n.largest}};
  }
  return j;
}

// "0", "1", "2-3", ..., "1024+": the leaf size buckets of TreeStats.
std::string LeafSizeBucketName(int b) {
  if (b == 0) return "0";
  if (b == 1) return "1";
  const uint64_t lo = uint64_t{1} << (b - 1);
  if (b + 1 == kLeafSizeBuckets) return std::to_string(lo) + "+";
  return std::to_string(lo) + "-" + std::to_string(2 * lo - 1);
}

nlohmann::json LeafSizesJson(const TreeStats& s) {
  nlohmann::json j = nlohmann::json::object();
  for (int b = 0; b < kLeafSizeBuckets; ++b) j[LeafSizeBucketName(b)] = s.leaf_sizes[b];
  return j;
}

void PrintLeafSizes(const TreeStats& s) {
  std::string line;
  for (int b = 0; b < kLeafSizeBuckets; ++b) {
    if (s.leaf_sizes[b] == 0) continue;
    line += (line.empty() ? "" : ", ") + LeafSizeBucketName(b) + ": " + std::to_string(s.leaf_sizes[b]);
  }
  std::printf("leaf sizes     %s\n", line.c_str());
}

void PrintLeafCauses(const LeafCauses& c) {
  if (!c.recorded) return;
  std::string all, large;
  uint64_t large_total = 0, leaves = 0;
  for (int i = 0; i < kLeafCauseCount; ++i) {
    const LeafCauseCount& n = c.by_cause[i];
    leaves += n.leaves;
    if (n.leaves == 0) continue;
    const std::string text = LeafCauseText(static_cast<LeafCause>(i));
    all += (all.empty() ? "" : ", ") + text + " " + std::to_string(n.leaves);
    if (n.large == 0) continue;
    large_total += n.large;
    large += (large.empty() ? "" : ", ") + text + " " + std::to_string(n.large) +
             " (largest " + std::to_string(n.largest) + ")";
  }
  std::printf("leaf causes    %s\n", all.c_str());
  if (large_total > 0) {
    std::printf("large leaves   %llu over %u triangles: %s\n", static_cast<unsigned long long>(large_total),
                kLargeLeafPrims, large.c_str());
  }
  // Large leaves at the depth limit in numbers mean the levels ran out before
  // the triangles were apart; the SAH's bonus for empty cells is what spends
  // them (docs/kdtree.md, "Where the levels go").
  const uint64_t large_at_limit = c.by_cause[static_cast<int>(LeafCause::kDepth)].large;
  if (large_at_limit > 0 && large_at_limit * 100 >= leaves) {
    std::printf("               %.1f %% of the leaves are large at the depth limit: a smaller --empty-bonus "
                "(0.2) spends fewer levels on empty space, --max-depth D allows more\n",
                100.0 * static_cast<double>(large_at_limit) / static_cast<double>(leaves));
  }
}

}  // namespace

nlohmann::json BuildOptionsJson(const BuildOptions& o, const TreeStats& s) {
  return {{"method", SplitMethodName(o.method)},
          {"traversal_cost", o.traversal_cost},
          {"isect_cost", o.isect_cost},
          {"empty_bonus", o.empty_bonus},
          {"max_depth", s.depth_limit},
          {"max_leaf_prims", o.max_leaf_prims},
          {"perfect_splits", o.perfect_splits},
          {"auto_clip", o.auto_clip},
          {"min_split_gain", o.min_split_gain}};
}

nlohmann::json TreeStatsJson(const TreeStats& s) {
  return {{"nodes", s.nodes},
          {"inner_nodes", s.inner_nodes},
          {"leaves", s.leaves},
          {"empty_leaves", s.empty_leaves},
          {"max_depth", s.max_depth},
          {"avg_leaf_depth", s.avg_leaf_depth},
          {"max_leaf_prims", s.max_leaf_prims},
          {"avg_leaf_prims", s.avg_leaf_prims},
          {"references", s.references},
          {"refs_per_triangle", s.refs_per_triangle},
          {"sah_cost", s.sah_cost},
          {"degenerate_triangles", s.degenerate_triangles},
          {"build_seconds", s.build_seconds},
          {"leaf_causes", LeafCausesJson(s.leaf_causes)},
          {"leaf_sizes", LeafSizesJson(s)}};
}

void PrintTreeStats(const PreparedScene& p) {
  const TreeStats& s = p.tree.stats;
  if (p.structure) {
    const StructureStats& st = p.structure->stats();
    std::printf("scene          %s\n", p.scene.source.c_str());
    std::printf("triangles      %zu (%u degenerate, left out)\n", p.scene.triangles.size(), s.degenerate_triangles);
    std::printf("structure      %s: %llu cells/nodes, %llu holding triangles, depth %u\n", AccelKindName(p.accel),
                static_cast<unsigned long long>(st.nodes), static_cast<unsigned long long>(st.leaves), st.max_depth);
    std::printf("references     %llu (%.2f per triangle), longest list %u\n",
                static_cast<unsigned long long>(st.references),
                p.structure_input->ids.empty() ? 0.0 : double(st.references) / p.structure_input->ids.size(),
                st.max_leaf_prims);
    std::printf("memory         %.2f MB (without the triangles)\n", st.memory_bytes / 1e6);
    std::printf("build time     %.3f s\n", st.build_seconds);
    return;
  }
  std::printf("scene          %s\n", p.scene.source.c_str());
  std::printf("triangles      %zu (%u degenerate, left out of the tree)\n", p.scene.triangles.size(),
              s.degenerate_triangles);
  std::printf("kd-tree        %u nodes: %u inner, %u leaves (%u empty)\n", s.nodes, s.inner_nodes, s.leaves,
              s.empty_leaves);
  std::printf("depth          max %u, avg leaf %.2f\n", s.max_depth, s.avg_leaf_depth);
  std::printf("leaf triangles max %u, avg %.2f (non-empty leaves)\n", s.max_leaf_prims, s.avg_leaf_prims);
  PrintLeafSizes(s);
  PrintLeafCauses(s.leaf_causes);
  std::printf("references     %llu (%.2f per triangle)\n", static_cast<unsigned long long>(s.references),
              s.refs_per_triangle);
  std::printf("SAH cost       %.2f\n", s.sah_cost);
  std::printf("build time     %.3f s (load %.3f s)\n", s.build_seconds, p.load_seconds);
  std::printf("memory image   %zu bytes\n", p.image.size());
}

}  // namespace kdrt
