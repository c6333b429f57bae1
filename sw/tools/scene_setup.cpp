#include "tools/scene_setup.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "scene/camera.h"
#include "scenes/gen/generators.h"
#include "trace/images.h"
#include "trace/memory_image.h"
#include "trace/rays_file.h"

namespace kdrt::cli {
namespace {

void ParseResolution(const std::string& res, int* w, int* h) {
  char x = 0;
  std::istringstream in(res);
  if (!(in >> *w >> x >> *h) || x != 'x' || *w < 1 || *h < 1 || *w > 65536 || *h > 65536 || !in.eof()) {
    throw InputError("--res '" + res + "': expected WxH with 1 <= W, H <= 65536, e.g. 512x512");
  }
}

Camera ParseCamera(const std::string& text, const Camera& base) {
  std::istringstream in(text);
  float f[10];
  for (float& v : f) {
    if (!(in >> v) || !std::isfinite(v)) {
      throw InputError("--camera '" + text + "': expected 10 finite numbers: from(3) at(3) up(3) angle");
    }
  }
  Camera c = base;
  c.from = {f[0], f[1], f[2]};
  c.at = {f[3], f[4], f[5]};
  c.up = {f[6], f[7], f[8]};
  c.angle_deg = f[9];
  if (!(c.angle_deg > 0 && c.angle_deg < 180)) throw InputError("--camera: angle must lie in (0, 180) degrees");
  return c;
}

std::string DefaultImageNameFor(const std::string& scene) {
  if (scene.rfind("gen:", 0) == 0) {
    std::string s = scene.substr(4);
    for (char& c : s) c = c == ':' ? '_' : c;
    return s + ".png";
  }
  const size_t slash = scene.find_last_of('/');
  std::string base = scene.substr(slash == std::string::npos ? 0 : slash + 1);
  const size_t dot = base.find_last_of('.');
  return base.substr(0, dot) + ".png";
}

}  // namespace

RaySet MakeRays(const Scene& scene, const std::string& rays_file, const std::string& camera,
                const std::string& res) {
  RaySet set;
  if (!rays_file.empty()) {
    set.rays = ReadRaysFile(rays_file);
    set.width = static_cast<int>(set.rays.size());
    return set;
  }
  Camera cam = scene.camera ? *scene.camera : AutoCamera(scene, 512, 512);
  if (!camera.empty()) cam = ParseCamera(camera, cam);
  if (!res.empty()) ParseResolution(res, &cam.width, &cam.height);
  set.width = cam.width;
  set.height = cam.height;
  set.rays.reserve(static_cast<size_t>(cam.width) * cam.height);
  for (int y = 0; y < cam.height; ++y) {
    for (int x = 0; x < cam.width; ++x) {
      const CameraRay cr = PrimaryRay(cam, x, y);
      set.rays.push_back(Ray{cr.o, cr.d, cr.tmin, INFINITY});
    }
  }
  return set;
}

std::string DefaultImageName(const std::string& scene_arg, bool from_rays_file) {
  return from_rays_file ? std::string() : DefaultImageNameFor(scene_arg);
}

void AddTraceOutputs(OutputSet& outputs, const Scene& scene, const RaySet& rays, const std::vector<Hit>& hits,
                     const std::string& image_path, const std::string& hits_path, const std::string& json_path,
                     const nlohmann::json& stats) {
  if (!image_path.empty()) {
    const std::vector<float> rgb = ShadeEyeLight(scene, rays.rays, hits);
    outputs.Add(image_path, [&](const std::string& tmp) { WriteRgbImage(tmp, rays.width, rays.height, rgb); });
  }
  if (!hits_path.empty()) {
    outputs.Add(hits_path, [&](const std::string& tmp) { WriteHitBuffer(tmp, rays.width, rays.height, hits); });
  }
  if (!json_path.empty()) {
    outputs.Add(json_path, [&](const std::string& tmp) {
      std::ofstream f(tmp);
      f << stats.dump(2) << "\n";
      if (!f) throw InputError(json_path, 0, "cannot write JSON stats");
    });
  }
}

void AddSceneOptions(CLI::App& cmd, SceneArgs& args) {
  cmd.add_option("scene", args.scene,
                 "Scene file (.nff, .obj, .ply, .off) or gen:NAME:SIZE for a procedural scene "
                 "(see `kdrt gen --help`)")
      ->required();
  cmd.add_option("--accel", args.accel, "kd-tree split method: sah, median or midpoint")
      ->capture_default_str();
  cmd.add_option("--max-depth", args.max_depth, "Maximum tree depth (-1: round(8 + 1.3 log2 N))")
      ->capture_default_str();
  cmd.add_option("--max-leaf", args.max_leaf_prims, "Make a leaf at this many triangles or fewer")
      ->capture_default_str();
  cmd.add_option("--isect-cost", args.isect_cost, "SAH cost of a triangle test")->capture_default_str();
  cmd.add_option("--trav-cost", args.traversal_cost, "SAH cost of a traversal step")->capture_default_str();
  cmd.add_option("--empty-bonus", args.empty_bonus, "SAH bonus for empty children")->capture_default_str();
  cmd.add_flag("--perfect-splits", args.perfect_splits, "Clip triangles to the node box (SAH only)");
  cmd.add_option("--sphere-segments", args.sphere_segments,
                 "Tessellation of NFF spheres and cones (0: the loader's default)");
}

PreparedScene PrepareScene(const SceneArgs& args) {
  PreparedScene p;
  const auto start = std::chrono::steady_clock::now();
  if (args.scene.rfind("gen:", 0) == 0) {
    const std::string rest = args.scene.substr(4);
    const size_t colon = rest.find(':');
    const std::string name = rest.substr(0, colon);
    int size = 1000;
    if (colon != std::string::npos) {
      try {
        size = std::stoi(rest.substr(colon + 1));
      } catch (const std::exception&) {
        throw InputError(args.scene + ": size after the generator name is not an integer");
      }
    }
    p.scene = GenerateScene(name, size);
  } else {
    LoadOptions lo;
    if (args.sphere_segments > 0) lo.sphere_segments = args.sphere_segments;
    p.scene = LoadScene(args.scene, lo);
  }
  p.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  BuildOptions bo;
  bo.method = ParseSplitMethod(args.accel);
  bo.max_depth = args.max_depth;
  bo.max_leaf_prims = args.max_leaf_prims;
  bo.isect_cost = args.isect_cost;
  bo.traversal_cost = args.traversal_cost;
  bo.empty_bonus = args.empty_bonus;
  bo.perfect_splits = args.perfect_splits;
  p.tree = BuildKdTree(p.scene, bo);
  p.image = BuildMemoryImage(p.scene, p.tree);
  return p;
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
          {"build_seconds", s.build_seconds}};
}

void PrintTreeStats(const PreparedScene& p) {
  const TreeStats& s = p.tree.stats;
  std::printf("scene          %s\n", p.scene.source.c_str());
  std::printf("triangles      %zu (%u degenerate, left out of the tree)\n", p.scene.triangles.size(),
              s.degenerate_triangles);
  std::printf("kd-tree        %u nodes: %u inner, %u leaves (%u empty)\n", s.nodes, s.inner_nodes, s.leaves,
              s.empty_leaves);
  std::printf("depth          max %u, avg leaf %.2f\n", s.max_depth, s.avg_leaf_depth);
  std::printf("leaf triangles max %u, avg %.2f (non-empty leaves)\n", s.max_leaf_prims, s.avg_leaf_prims);
  std::printf("references     %llu (%.2f per triangle)\n", static_cast<unsigned long long>(s.references),
              s.refs_per_triangle);
  std::printf("SAH cost       %.2f\n", s.sah_cost);
  std::printf("build time     %.3f s (load %.3f s)\n", s.build_seconds, p.load_seconds);
  std::printf("memory image   %zu bytes\n", p.image.size());
}

}  // namespace kdrt::cli
