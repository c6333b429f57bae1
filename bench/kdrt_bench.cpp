// make bench: tracing and build speed of the reference tracer against Embree 3.
// Both trace the same primary rays single-threaded (our TraceRays with one
// thread, Embree's rtcIntersect1 in a loop); only tracing is timed, no file
// I/O, and each side's time is the fastest of --repeat runs (this machine's
// timings of one run vary by 5-20 %). Build times: our SAH kd-tree against
// Embree's high-quality BVH build, both single-threaded.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "accel/kdtree.h"
#include "oracle/embree_scene.h"
#include "scene/camera.h"
#include "scene/text_fields.h"
#include "scenes/gen/generators.h"
#include "trace/memory_image.h"
#include "trace/tracer.h"
#include "walk_floor.h"

namespace {

std::vector<std::string> Split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(item);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace kdrt;
  CLI::App app{"kdrt_bench: reference tracer vs Embree 3 (single thread, primary rays)"};
  // Every generator at every size. Without the minimum split gain gears' SAH
  // tree references each triangle ~460 times at 200k, and 800k would need
  // several GB of leaf lists: below kGearsFullGain the default list leaves
  // out gears above 200k (and says so).
  const std::string default_scenes = "balls,rings,tetra,tree,strips,hoops,gears";
  constexpr float kGearsFullGain = 0.05f;
  std::string scenes = default_scenes;
  std::string sizes = "1000,30000,200000,800000";
  int res = 512;
  int repeat = 3;
  std::string json_path;
  BuildOptions build;  // one build thread, as Embree's
  app.add_flag("--perfect-splits", build.perfect_splits, "Build the kd-trees with perfect splits (clipped boxes)");
  app.add_flag("--no-auto-clip{false}", build.auto_clip,
               "Build the kd-trees without clipping where the boxes give no good split (kdrt info --help)");
  app.add_option("--min-split-gain", build.min_split_gain,
                 "SAH: the gain below which a split counts as a bad refinement (kdrt info --help)")
      ->capture_default_str();
  app.add_option("--isect-cost", build.isect_cost, "SAH cost of a triangle test (kdrt info --help)")
      ->capture_default_str();
  app.add_option("--trav-cost", build.traversal_cost, "SAH cost of a traversal step")->capture_default_str();
  app.add_option("--empty-bonus", build.empty_bonus, "SAH bonus for empty children")->capture_default_str();
  app.add_option("--scenes", scenes,
                 "Comma-separated generator names, each at every --sizes, or name:size for one size")
      ->capture_default_str();
  app.add_option("--sizes", sizes, "Comma-separated triangle counts")->capture_default_str();
  app.add_option("--res", res, "Image width = height")->capture_default_str();
  app.add_option("--repeat", repeat, "Trace the rays this many times on each side and keep the fastest")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  app.add_option("--json", json_path, "Also write the table as JSON");
  CLI11_PARSE(app, argc, argv);
  const bool cap_gears = scenes == default_scenes && build.min_split_gain < kGearsFullGain;

  nlohmann::json rows = nlohmann::json::array();
  // Every (generator, size) to run, checked before the first one runs.
  std::vector<std::pair<std::string, int>> runs;
  for (const std::string& item : Split(scenes)) {
    const size_t colon = item.find(':');
    const std::string name = item.substr(0, colon);
    try {
      GeneratorDescription(name);  // InputError on an unknown generator
    } catch (const std::exception& e) {
      std::fprintf(stderr, "kdrt_bench: --scenes: %s\n", e.what());
      return 1;
    }
    for (const std::string& size_text : colon == std::string::npos ? Split(sizes) : Split(item.substr(colon + 1))) {
      long long size = 0;
      if (!ParseInteger(size_text, &size) || size < 1 || size > kMaxGeneratorSize) {
        std::fprintf(stderr, "kdrt_bench: --scenes/--sizes: '%s': a triangle count must be an integer in 1..%d\n",
                     item.c_str(), kMaxGeneratorSize);
        return 1;
      }
      if (cap_gears && name == "gears" && size > 200000) {
        std::fprintf(stderr,
                     "kdrt_bench: note: gears %lld left out: with --min-split-gain below %.2g its tree would need "
                     "several GB of leaf lists (name it in --scenes to run it anyway)\n",
                     size, kGearsFullGain);
        continue;
      }
      runs.emplace_back(name, static_cast<int>(size));
    }
  }
  std::printf("%-8s %9s | %8s %6s %8s | %9s %9s %6s | %9s %9s %6s | %6s %6s | %6s\n", "scene", "tris", "refs/tri",
              "max", "tests/r", "kd build", "emb build", "ratio", "kd Mray/s", "emb Mray/s", "ratio", "nodes/r",
              "floor", "agree");
  std::printf("%s\n", std::string(139, '-').c_str());
  for (const auto& [name, size] : runs) {
    const Scene scene = GenerateScene(name, size);
    const FramedImage framed = BuildFramedImage(scene, build);
    const KdTree& tree = framed.tree;
    const std::vector<uint8_t>& bytes = framed.bytes;
    const ImageView image(bytes);
    const EmbreeScene embree(scene, 1, /*robust=*/false);

    Camera cam = scene.camera ? *scene.camera : AutoCamera(scene, res, res);
    cam.width = cam.height = res;
    std::vector<Ray> rays;
    rays.reserve(static_cast<size_t>(res) * res);
    for (int y = 0; y < res; ++y) {
      for (int x = 0; x < res; ++x) {
        const CameraRay cr = PrimaryRay(cam, x, y);
        rays.push_back(Ray{cr.o, cr.d, cr.tmin, INFINITY});
      }
    }
    TraceOptions to;
    to.threads = 1;
    TraceStats ts;
    std::vector<Hit> ours;
    std::vector<RayCounters> per_ray;
    std::vector<Hit> theirs(rays.size());
    double kd_seconds = 0.0, embree_seconds = 0.0;
    for (int run = 0; run < repeat; ++run) {
      ours = TraceRays(image, rays, to, &ts, &per_ray);
      kd_seconds = run == 0 ? ts.seconds : std::min(kd_seconds, ts.seconds);
      const auto start = std::chrono::steady_clock::now();
      for (size_t i = 0; i < rays.size(); ++i) theirs[i] = embree.Intersect(rays[i]);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      embree_seconds = run == 0 ? s : std::min(embree_seconds, s);
    }
    size_t agree = 0;
    for (size_t i = 0; i < rays.size(); ++i) agree += ours[i].IsHit() == theirs[i].IsHit();

    const double n = static_cast<double>(rays.size());
    const double kd_mrays = n / kd_seconds * 1e-6, emb_mrays = n / embree_seconds * 1e-6;
    // The walk floor (walk_floor.h): a bare walk of about the tracer's nodes,
    // each ray ending after the leaves the tracer fetched on it.
    std::vector<uint32_t> leaves(per_ray.size());
    for (size_t i = 0; i < per_ray.size(); ++i) leaves[i] = per_ray[i].leaves;
    const bench::WalkFloor floor = bench::MeasureWalkFloor(image, rays, leaves, repeat);
    const double floor_mrays = floor.ns_per_ray > 0 ? 1e3 / floor.ns_per_ray : 0.0;
    std::printf("%-8s %9zu | %8.2f %6u %8.2f | %8.3fs %8.3fs %6.2f | %9.2f %9.2f %6.2f | %6.2f %6.2f | %5.2f%%\n",
                name.c_str(), scene.triangles.size(), tree.stats.refs_per_triangle, tree.stats.max_leaf_prims,
                ts.totals.tri_tests / n, tree.stats.build_seconds, embree.build_seconds(),
                tree.stats.build_seconds / embree.build_seconds(), kd_mrays, emb_mrays, kd_mrays / emb_mrays,
                ts.totals.nodes / n, floor_mrays / emb_mrays, 100.0 * agree / n);
    std::fflush(stdout);
    rows.push_back({{"scene", name},
                    {"triangles", scene.triangles.size()},
                    {"perfect_splits", build.perfect_splits},
                    {"auto_clip", build.auto_clip},
                    {"min_split_gain", build.min_split_gain},
                    {"refs_per_triangle", tree.stats.refs_per_triangle},
                    {"max_leaf_prims", tree.stats.max_leaf_prims},
                    {"avg_leaf_prims", tree.stats.avg_leaf_prims},
                    {"per_ray_leaves", ts.totals.leaves / n},
                    {"kd_build_seconds", tree.stats.build_seconds},
                    {"embree_build_seconds", embree.build_seconds()},
                    {"kd_mrays_per_second", kd_mrays},
                    {"embree_mrays_per_second", emb_mrays},
                    {"hit_miss_agreement", agree / n},
                    {"per_ray_nodes", ts.totals.nodes / n},
                    {"per_ray_tri_tests", ts.totals.tri_tests / n},
                    {"walk_floor",
                     {{"ns_per_ray", floor.ns_per_ray},
                      {"setup_ns_per_ray", floor.setup_ns_per_ray},
                      {"nodes_per_ray", floor.nodes_per_ray},
                      {"mrays_per_second", floor_mrays},
                      {"vs_embree", floor_mrays / emb_mrays}}}});
  }
  std::printf("build ratio = kd / Embree (aim <= 2); throughput ratio = kd / Embree (aim >= 0.7)\n");
  std::printf("floor = the walk floor against Embree: a bare walk of about the tracer's nodes, with no triangle\n"
              "        tests, ending each ray after the tracer's leaves (bench/walk_floor.h)\n");
  if (!json_path.empty()) std::ofstream(json_path) << rows.dump(2) << "\n";
  return 0;
}
