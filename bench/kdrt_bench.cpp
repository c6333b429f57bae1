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
#include <cstring>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include "accel/kdtree.h"
#include "oracle/embree_scene.h"
#include "scene/camera.h"
#include "scene/text_fields.h"
#include "scenes/gen/generators.h"
#include "trace/memory_image.h"
#include "trace/ray_pool.h"
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

constexpr int kWidths[] = {4, 8, 16};

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool SameBits(const std::vector<kdrt::Hit>& a, const std::vector<kdrt::Hit>& b) {
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].prim != b[i].prim || std::memcmp(&a[i].t, &b[i].t, sizeof(float)) != 0 ||
        std::memcmp(&a[i].u, &b[i].u, sizeof(float)) != 0 || std::memcmp(&a[i].v, &b[i].v, sizeof(float)) != 0) {
      return false;
    }
  }
  return true;
}

// One ray set (primary or shadow) traced by the kd-tree one ray at a time and
// in packets of each width, and by Embree one ray at a time and in packets of
// each width; single-threaded, then the fastest width of each on every core.
// Mrays/s, each the fastest of `repeat` runs.
struct RaySetFigures {
  double kd1 = 0, emb1 = 0;
  double kd[3] = {}, emb[3] = {};
  std::string isa[3];
  uint64_t kd_alone[3] = {};  // rays that left their packet
  double lanes[3] = {};        // active lanes per packet node fetch
  bool same_bits = true;      // kd packets == kd scalar, every ray
  int threads = 1;
  double kd_mt = 0, emb_mt = 0;  // fastest width, all threads
  int kd_mt_width = 0, emb_mt_width = 0;
};

RaySetFigures MeasureRaySet(const kdrt::ImageView& image, const kdrt::EmbreeScene& embree,
                            const std::vector<kdrt::Ray>& rays, int row_width, kdrt::Query query, int repeat,
                            const std::vector<kdrt::Hit>& kd_scalar_hits, double kd_scalar_seconds) {
  using namespace kdrt;
  RaySetFigures f;
  const double n = static_cast<double>(rays.size());
  const auto mrays = [n](double s) { return n / s * 1e-6; };
  const bool shadow = query == Query::kAny;
  std::vector<Hit> theirs(rays.size());
  std::unique_ptr<bool[]> occluded(new bool[rays.size()]);
  // Embree over rays [begin, end) at `width` (1: single rays).
  const auto embree_range = [&](size_t begin, size_t end, int width) {
    if (width == 1) {
      for (size_t i = begin; i < end; ++i) {
        if (shadow) {
          occluded[i] = embree.Occluded(rays[i]);
        } else {
          theirs[i] = embree.Intersect(rays[i]);
        }
      }
      return;
    }
    for (size_t i = begin; i < end; i += width) {
      const int k = static_cast<int>(std::min<size_t>(width, end - i));
      if (shadow) {
        embree.OccludedPacket(&rays[i], k, width, &occluded[i]);
      } else {
        embree.IntersectPacket(&rays[i], k, width, &theirs[i]);
      }
    }
  };
  // Primary rays in packets: the tiles the kd-tree's packets take
  // (TraceOptions::row_width), gathered and put back the same way.
  const auto embree_tiles = [&](size_t begin, size_t end, int width) {
    const int tw = width == 4 ? 2 : 4, th = width / tw;
    const size_t row = row_width, rows = rays.size() / row, tiles_x = (row + tw - 1) / tw;
    Ray tile[16];
    Hit tile_hits[16];
    size_t index[16];
    for (size_t t = begin; t < end; ++t) {
      const size_t x0 = t % tiles_x * tw, y0 = t / tiles_x * th;
      int k = 0;
      for (size_t y = y0; y < y0 + th && y < rows; ++y) {
        for (size_t x = x0; x < x0 + tw && x < row; ++x) {
          index[k] = y * row + x;
          tile[k] = rays[index[k]];
          ++k;
        }
      }
      embree.IntersectPacket(tile, k, width, tile_hits);
      for (int i = 0; i < k; ++i) theirs[index[i]] = tile_hits[i];
    }
  };
  const auto time_embree = [&](int width, int threads) {
    const bool tiles = !shadow && width > 1 && row_width > 0 && rays.size() % row_width == 0;
    size_t units = rays.size();
    if (tiles) {
      const int tw = width == 4 ? 2 : 4, th = width / tw;
      units = ((row_width + tw - 1) / tw) * ((rays.size() / row_width + th - 1) / th);
    }
    double best = 0;
    for (int run = 0; run < repeat; ++run) {
      const auto start = std::chrono::steady_clock::now();
      RunRayThreads(units, threads, false, [&](const NextChunk& next) {
        size_t b, e;
        while (next(&b, &e)) {
          if (tiles) {
            embree_tiles(b, e, width);
          } else {
            embree_range(b, e, width);
          }
        }
      });
      const double s = Seconds(start);
      best = run == 0 ? s : std::min(best, s);
    }
    return best;
  };
  const auto time_kd = [&](int width, int threads, TraceStats* ts, std::vector<Hit>* hits) {
    TraceOptions to;
    to.threads = threads;
    to.query = query;
    to.packets = width;
    to.row_width = shadow ? 0 : row_width;
    double best = 0;
    for (int run = 0; run < repeat; ++run) {
      *hits = TraceRays(image, rays, to, ts);
      best = run == 0 ? ts->seconds : std::min(best, ts->seconds);
    }
    return best;
  };
  f.kd1 = mrays(kd_scalar_seconds);
  f.emb1 = mrays(time_embree(1, 1));
  for (int w = 0; w < 3; ++w) {
    TraceStats ts;
    std::vector<Hit> hits;
    f.kd[w] = mrays(time_kd(kWidths[w], 1, &ts, &hits));
    f.isa[w] = ts.packets.width > 0 ? ts.packets.isa : "scalar";
    f.kd_alone[w] = ts.packet_counts.scalar_rays;
    f.lanes[w] = ts.packet_counts.node_fetches > 0
                     ? static_cast<double>(ts.totals.nodes) / static_cast<double>(ts.packet_counts.node_fetches)
                     : 0.0;
    f.same_bits = f.same_bits && SameBits(hits, kd_scalar_hits);
    f.emb[w] = mrays(time_embree(kWidths[w], 1));
  }
  const int kd_best = static_cast<int>(std::max_element(f.kd, f.kd + 3) - f.kd);
  const int emb_best = static_cast<int>(std::max_element(f.emb, f.emb + 3) - f.emb);
  f.kd_mt_width = kWidths[kd_best];
  f.emb_mt_width = kWidths[emb_best];
  f.threads = static_cast<int>(std::thread::hardware_concurrency());
  TraceStats ts;
  std::vector<Hit> hits;
  f.kd_mt = mrays(time_kd(f.kd_mt_width, 0, &ts, &hits));
  f.same_bits = f.same_bits && SameBits(hits, kd_scalar_hits);
  f.emb_mt = mrays(time_embree(f.emb_mt_width, 0));
  return f;
}

void PrintPacketRow(const std::string& name, size_t tris, const char* rays, const RaySetFigures& f) {
  std::printf("%-8s %9zu %-7s | %7.2f %7.2f %7.2f %7.2f | %7.2f %7.2f %7.2f %7.2f | %5.2f %5.2f %5.2f %5.2f | %7.2f "
              "%5.2f %7.2f %5.2f | %4.1f | %s\n",
              name.c_str(), tris, rays, f.kd1, f.kd[0], f.kd[1], f.kd[2], f.emb1, f.emb[0], f.emb[1], f.emb[2],
              *std::max_element(f.kd, f.kd + 3) / f.emb1, f.kd[0] / f.emb[0], f.kd[1] / f.emb[1], f.kd[2] / f.emb[2],
              f.kd_mt, f.kd_mt / *std::max_element(f.kd, f.kd + 3), f.emb_mt,
              f.emb_mt / *std::max_element(f.emb, f.emb + 3), f.lanes[1], f.same_bits ? "yes" : "NO");
}

nlohmann::json PacketJson(const RaySetFigures& f) {
  nlohmann::json widths = nlohmann::json::array();
  for (int w = 0; w < 3; ++w) {
    widths.push_back({{"width", kWidths[w]},
                      {"isa", f.isa[w]},
                      {"kd_mrays_per_second", f.kd[w]},
                      {"kd_rays_alone", f.kd_alone[w]},
                      {"kd_active_lanes_per_node_fetch", f.lanes[w]},
                      {"embree_mrays_per_second", f.emb[w]},
                      {"kd_vs_embree_same_width", f.kd[w] / f.emb[w]}});
  }
  return {{"kd_scalar_mrays_per_second", f.kd1},
          {"embree_single_mrays_per_second", f.emb1},
          {"packets", widths},
          {"kd_best_vs_embree_single", *std::max_element(f.kd, f.kd + 3) / f.emb1},
          {"same_bits_as_scalar", f.same_bits},
          {"threads", f.threads},
          {"kd_threads_mrays_per_second", f.kd_mt},
          {"kd_threads_width", f.kd_mt_width},
          {"kd_thread_speedup", f.kd_mt / *std::max_element(f.kd, f.kd + 3)},
          {"embree_threads_mrays_per_second", f.emb_mt},
          {"embree_threads_width", f.emb_mt_width},
          {"embree_thread_speedup", f.emb_mt / *std::max_element(f.emb, f.emb + 3)}};
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
  app.add_option("--max-depth", build.max_depth, "Maximum kd-tree depth (-1: round(8 + 1.3 log2 N))")
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
  LoadOptions tessellation;
  app.add_option("--cone-aspect", tessellation.cone_aspect,
                 "gen:hoops' cylinders in bands of cells at most A times longer than wide (kdrt render --help)")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  const bool cap_gears = scenes == default_scenes && build.min_split_gain < kGearsFullGain;

  nlohmann::json rows = nlohmann::json::array();
  struct PacketRow {
    std::string name;
    size_t tris;
    const char* rays;
    RaySetFigures f;
  };
  std::vector<PacketRow> packet_rows;
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
    const Scene scene = GenerateScene(name, size, tessellation);
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
    to.packets = 0;
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
    for (size_t i = 0; i < per_ray.size(); ++i) leaves[i] = per_ray[i].leaves + per_ray[i].empty_skipped;
    const bench::WalkFloor floor = bench::MeasureWalkFloor(image, rays, leaves, repeat);
    const double floor_mrays = floor.ns_per_ray > 0 ? 1e3 / floor.ns_per_ray : 0.0;
    std::printf("%-8s %9zu | %8.2f %6u %8.2f | %8.3fs %8.3fs %6.2f | %9.2f %9.2f %6.2f | %6.2f %6.2f | %5.2f%%\n",
                name.c_str(), scene.triangles.size(), tree.stats.refs_per_triangle, tree.stats.max_leaf_prims,
                ts.totals.tri_tests / n, tree.stats.build_seconds, embree.build_seconds(),
                tree.stats.build_seconds / embree.build_seconds(), kd_mrays, emb_mrays, kd_mrays / emb_mrays,
                ts.totals.nodes / n, floor_mrays / emb_mrays, 100.0 * agree / n);
    std::fflush(stdout);
    // Shadow rays: from each primary hit towards the scene's first light (a
    // point above the scene without one), any hit.
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const Triangle& t : scene.triangles) {
      for (const glm::vec3& v : {t.v0, t.v1, t.v2}) lo = glm::min(lo, v), hi = glm::max(hi, v);
    }
    const glm::vec3 light = scene.lights.empty() ? glm::vec3(0.5f * (lo.x + hi.x), hi.y + (hi.y - lo.y), hi.z)
                                                 : scene.lights[0].position;
    std::vector<Ray> shadow;
    for (size_t i = 0; i < rays.size(); ++i) {
      if (!ours[i].IsHit()) continue;
      const glm::vec3 p = rays[i].o + ours[i].t * rays[i].d;
      shadow.push_back(Ray{p, light - p, 1e-4f, 1.0f});
    }
    TraceOptions so = to;
    so.query = Query::kAny;
    std::vector<Hit> shadow_hits;
    double shadow_seconds = 0;
    for (int run = 0; run < repeat; ++run) {
      shadow_hits = TraceRays(image, shadow, so, &ts);
      shadow_seconds = run == 0 ? ts.seconds : std::min(shadow_seconds, ts.seconds);
    }
    packet_rows.push_back({name, scene.triangles.size(), "primary",
                           MeasureRaySet(image, embree, rays, res, Query::kClosest, repeat, ours, kd_seconds)});
    packet_rows.push_back({name, scene.triangles.size(), "shadow",
                           MeasureRaySet(image, embree, shadow, 0, Query::kAny, repeat, shadow_hits, shadow_seconds)});
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
                      {"vs_embree", floor_mrays / emb_mrays}}},
                    {"primary", PacketJson(packet_rows[packet_rows.size() - 2].f)},
                    {"shadow", PacketJson(packet_rows.back().f)}});
  }
  std::printf("build ratio = kd / Embree (aim <= 2); throughput ratio = kd / Embree (aim >= 0.7)\n");
  std::printf("floor = the walk floor against Embree: a bare walk of about the tracer's nodes, with no triangle\n"
              "        tests, ending each ray after the tracer's leaves (bench/walk_floor.h)\n");
  std::printf("\nPackets (Mrays/s; kd: the reference tracer, emb: Embree 3; 1: one ray at a time, 4/8/16: rays per "
              "packet, single thread; thr: the fastest width on every core)\n");
  std::printf("%-8s %9s %-7s | %7s %7s %7s %7s | %7s %7s %7s %7s | %5s %5s %5s %5s | %7s %5s %7s %5s | %4s | %s\n",
              "scene", "tris", "rays", "kd 1", "kd 4", "kd 8", "kd 16", "emb 1", "emb 4", "emb 8", "emb 16", "kd/e1",
              "4/4", "8/8", "16/16", "kd thr", "x", "emb thr", "x", "act8", "same");
  std::printf("%s\n", std::string(157, '-').c_str());
  for (const PacketRow& r : packet_rows) PrintPacketRow(r.name, r.tris, r.rays, r.f);
  if (!packet_rows.empty()) {
    const RaySetFigures& f = packet_rows.front().f;
    std::printf("kd packets ran on: 4 %s, 8 %s, 16 %s (packed formats: %s; the others trace one ray at a time)\n",
                f.isa[0].c_str(), f.isa[1].c_str(), f.isa[2].c_str(), PacketFormats());
  }
  std::printf("kd/e1 = the fastest kd width / Embree one ray at a time (aim >= 1); W/W = kd / Embree at width W (aim "
              ">= 0.5);\nx = all threads / the same width on one; act8 = active rays per node a kd packet of 8 fetches;\n"
              "same = kd packets give the scalar bits on every ray\n");
  if (!json_path.empty()) std::ofstream(json_path) << rows.dump(2) << "\n";
  return 0;
}
