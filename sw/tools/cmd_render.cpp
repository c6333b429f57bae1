// kdrt render: the software reference tracer.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "common/error.h"
#include "scene/camera.h"
#include "tools/commands.h"
#include "tools/scene_setup.h"
#include "trace/images.h"
#include "trace/output_file.h"
#include "trace/rays_file.h"
#include "trace/tracer.h"

namespace kdrt::cli {
namespace {

struct RenderArgs {
  SceneArgs scene;
  std::string res;
  std::string out;
  std::string hits;
  std::string json;
  std::string isect = "watertight";
  std::string format = "fp32";
  std::string rays;
  std::string camera;
  int threads = 0;
  bool quiet = false;
};

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

std::string DefaultImageName(const std::string& scene) {
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

int Run(const RenderArgs& args) {
  PreparedScene p = PrepareScene(args.scene);
  const ImageView image(p.image);

  std::vector<Ray> rays;
  int width = 0, height = 1;
  if (!args.rays.empty()) {
    rays = ReadRaysFile(args.rays);
    width = static_cast<int>(rays.size());
  } else {
    Camera cam = p.scene.camera ? *p.scene.camera : AutoCamera(p.scene, 512, 512);
    if (!args.camera.empty()) cam = ParseCamera(args.camera, cam);
    if (!args.res.empty()) ParseResolution(args.res, &cam.width, &cam.height);
    width = cam.width;
    height = cam.height;
    rays.reserve(static_cast<size_t>(width) * height);
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const CameraRay cr = PrimaryRay(cam, x, y);
        rays.push_back(Ray{cr.o, cr.d, cr.tmin, INFINITY});
      }
    }
  }

  TraceOptions to;
  to.format = fp::ParseFormat(args.format);
  to.isect = ParseIsectMethod(args.isect);
  to.threads = args.threads;
  to.progress = !args.quiet && isatty(STDERR_FILENO) && rays.size() >= 1000000;
  TraceStats ts;
  const std::vector<Hit> hits = TraceRays(image, rays, to, &ts);

  const double n = static_cast<double>(rays.size());
  nlohmann::json j = {
      {"command", "render"},
      {"scene", p.scene.source},
      {"triangles", p.scene.triangles.size()},
      {"accel", args.scene.accel},
      {"isect", IsectMethodName(to.isect)},
      {"format", args.format},
      {"width", width},
      {"height", height},
      {"tree", TreeStatsJson(p.tree.stats)},
      {"image_bytes", p.image.size()},
      {"rays", ts.rays},
      {"hits", ts.hits},
      {"trace_seconds", ts.seconds},
      {"threads", to.threads},
      {"mrays_per_second", ts.seconds > 0 ? n / ts.seconds * 1e-6 : 0.0},
      {"per_ray",
       {{"nodes", ts.totals.nodes / n}, {"leaves", ts.totals.leaves / n}, {"tri_tests", ts.totals.tri_tests / n}}},
      {"totals", {{"nodes", ts.totals.nodes}, {"leaves", ts.totals.leaves}, {"tri_tests", ts.totals.tri_tests}}},
  };

  OutputSet outputs;
  std::string out = args.out;
  if (out.empty() && args.rays.empty()) out = DefaultImageName(args.scene.scene);
  if (!out.empty()) {
    const std::vector<float> rgb = ShadeEyeLight(p.scene, rays, hits);
    outputs.Add(out, [&](const std::string& tmp) { WriteRgbImage(tmp, width, height, rgb); });
  }
  if (!args.hits.empty()) {
    outputs.Add(args.hits, [&](const std::string& tmp) { WriteHitBuffer(tmp, width, height, hits); });
  }
  if (!args.json.empty()) {
    outputs.Add(args.json, [&](const std::string& tmp) {
      std::ofstream f(tmp);
      f << j.dump(2) << "\n";
      if (!f) throw InputError(args.json, 0, "cannot write JSON stats");
    });
  }
  outputs.Commit();

  if (!args.quiet) {
    PrintTreeStats(p);
    std::printf("format         %s, %s test\n", args.format.c_str(), IsectMethodName(to.isect));
    std::printf("rays           %llu (%dx%d), %llu hits (%.1f %%)\n", static_cast<unsigned long long>(ts.rays), width,
                height, static_cast<unsigned long long>(ts.hits), 100.0 * ts.hits / n);
    std::printf("per ray        %.2f nodes, %.2f leaves, %.2f triangle tests\n", ts.totals.nodes / n,
                ts.totals.leaves / n, ts.totals.tri_tests / n);
    std::printf("trace time     %.3f s, %.2f Mrays/s\n", ts.seconds, ts.seconds > 0 ? n / ts.seconds * 1e-6 : 0.0);
    if (!out.empty()) std::printf("image          %s\n", out.c_str());
    if (!args.hits.empty()) std::printf("hit buffer     %s\n", args.hits.c_str());
    if (!args.json.empty()) std::printf("stats          %s\n", args.json.c_str());
  }
  return 0;
}

}  // namespace

Runner AddRenderCommand(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Trace a scene with the software reference tracer");
  AddSceneOptions(*cmd, args->scene);
  cmd->add_option("--res", args->res, "Image resolution WxH (default: the scene's, else 512x512)");
  cmd->add_option("-o,--output", args->out, "Image file (.png, .ppm, .exr; default: <scene>.png)");
  cmd->add_option("--hits", args->hits, "EXR hit buffer with channels t, prim, u, v");
  cmd->add_option("--json", args->json, "Machine-readable statistics");
  cmd->add_option("--isect", args->isect, "Ray/triangle test: watertight or moller")->capture_default_str();
  cmd->add_option("--format", args->format, "Number format of traversal and intersection: fp32, fp24, bf16, "
                                            "fp16 or eXmY")
      ->capture_default_str();
  cmd->add_option("--rays", args->rays, "Trace this ray file (KDRTRAYS) instead of the camera");
  cmd->add_option("--camera", args->camera, "Override the camera: \"fx fy fz ax ay az ux uy uz angle\"");
  cmd->add_option("--threads", args->threads, "Threads (0: all cores; results do not depend on it)");
  cmd->add_flag("-q,--quiet", args->quiet, "No summary on stdout");
  return [cmd, args]() { return cmd->parsed() ? Run(*args) : -1; };
}

}  // namespace kdrt::cli
