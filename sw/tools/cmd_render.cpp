// kdrt render: the software reference tracer.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <unistd.h>

#include "common/error.h"
#include "scene/camera.h"
#include "tools/commands.h"
#include "setup/accel_compare.h"
#include "setup/precision_check.h"
#include "setup/prepared_scene.h"
#include "setup/ray_set.h"
#include "setup/shaded_frame.h"
#include "setup/trace_outputs.h"
#include "tools/scene_options.h"
#include "trace/images.h"
#include "trace/output_file.h"
#include "trace/rays_file.h"
#include "structures/structure_tracer.h"
#include "trace/tracer.h"

namespace kdrt::cli {
namespace {

struct RenderArgs {
  SceneSpec scene;
  std::string res;
  std::string out;
  std::string hits;
  std::string json;
  std::string isect = "watertight";
  std::string format = "fp32";
  std::string trav_format;  // empty: --format
  std::string image_format = "native";
  std::string rays;
  std::string camera;
  int threads = 0;
  std::string packets = std::to_string(kDefaultPacketWidth);
  bool packets_given = false;
  bool quiet = false;
  bool strict = false;
  ShadingArgs shading;
};

nlohmann::json PassStats(const AccelTotals& ts, bool mailbox) {
  return {{"rays", ts.rays}, {"hits", ts.hits}, {"trace_seconds", ts.seconds}, {"per_ray", PerRayJson(ts, mailbox)}};
}

// One batch through the kd-tree image or the software structure.
std::vector<Hit> TraceBatch(const PreparedScene& p, const ImageView& traced, const std::vector<Ray>& rays,
                            const TraceOptions& options, AccelTotals* totals) {
  if (p.structure) return TraceStructureRays(*p.structure, p.frame, rays, options, totals);
  TraceStats ts;
  std::vector<Hit> hits = TraceRays(traced, rays, options, &ts);
  *totals = ToAccelTotals(ts);
  return hits;
}

int Run(const RenderArgs& args) {
  const fp::Format format = fp::ParseFormat(args.format);
  // A narrower image than the datapath (splits and vertices stored in fewer
  // bits, loaded exactly): its format decides the storage criteria of the
  // precision check.
  std::optional<fp::Format> narrow_image;
  if (args.image_format != "native" && args.image_format != "fp32") {
    narrow_image = fp::ParseFormat(args.image_format);
    CheckImageFormat(format, *narrow_image);
    if (!IsKdTree(args.scene.accel)) {
      throw InputError("--image-format " + args.image_format + ": only the kd-tree's memory image has a format; "
                       "--accel " + std::string(AccelKindName(args.scene.accel)) + " traces its own structure");
    }
  }
  TraceOptions to;
  to.format = format;
  if (!args.trav_format.empty()) to.trav_format = fp::ParseFormat(args.trav_format);
  const bool mixed = TravFormat(to) != format;
  CheckTravFormat(to);
  to.isect = ParseIsectMethod(args.isect);
  to.threads = args.threads;
  to.packets = ParsePacketWidth(args.packets);
  if (!IsKdTree(args.scene.accel)) CheckStructureTraceOptions(to);  // before the build
  SceneSpec spec = args.scene;
  spec.strict = args.strict;
  PreparedScene p = PrepareScene(spec);
  const bool mailbox = p.structure && p.structure->uses_mailbox();
  const ImageView image(p.image);
  // The image the tracer reads: the format's own packed image (splits and
  // vertices rounded once, as a load from the fp32 image rounds them: the
  // hits are the same), or the fp32 image.
  const img::ImageLayout layout = args.image_format == "fp32" ? img::ImageLayout{}
                                  : narrow_image              ? LayoutFor(*narrow_image)
                                                              : LayoutFor(format);
  const std::vector<uint8_t> packed = layout.IsFp32() ? std::vector<uint8_t>{} : RepackImage(image, layout);
  const ImageView traced = layout.IsFp32() ? image : ImageView(packed);

  const RaySet ray_set = MakeRays(p.scene, args.rays, args.camera, args.res);
  CheckShadingArgs(args.shading, ray_set);
  const std::vector<Ray>& rays = ray_set.rays;
  const int width = ray_set.width, height = ray_set.height;

  to.query = ray_set.query;
  if (args.rays.empty()) to.row_width = width;  // camera rays: packets by tiles
  const PacketPlan plan = PlanPackets(traced, to);
  if (args.packets_given && to.packets > 0 && (plan.width == 0 || p.structure)) {
    std::fprintf(stderr, "kdrt render: note: --packets %s: %s\n", args.packets.c_str(),
                 p.structure ? "only the kd-tree traces in packets" : plan.why_scalar.c_str());
  }
  to.progress = !args.quiet && isatty(STDERR_FILENO) && rays.size() >= 1000000;
  const PrecisionCheck check = CheckPrecision(image, rays, to.format, args.strict, args.threads, "", narrow_image);
  AccelTotals ts;
  const std::vector<Hit> hits = TraceBatch(p, traced, rays, to, &ts);

  const double n = static_cast<double>(rays.size());
  nlohmann::json j = {
      {"command", "render"},
      {"scene", p.scene.source},
      {"triangles", p.scene.triangles.size()},
      {"accel", AccelKindName(p.accel)},
      {"isect", IsectMethodName(to.isect)},
      {"format", args.format},
      {"trav_format", TravFormat(to).Name()},
      {"width", width},
      {"height", height},
      {p.structure ? "structure" : "tree",
       p.structure ? StructureStatsJson(p.structure->stats()) : TreeStatsJson(p.tree.stats)},
      {"image_format", fp::Format{layout.e, layout.m}.Name()},
      {"image_bytes", traced.size()},
      {"fp32_image_bytes", p.image.size()},
      {"rays", ts.rays},
      {"hits", ts.hits},
      {"trace_seconds", ts.seconds},
      {"threads", to.threads},
      {"packets",
       {{"width", p.structure ? 0 : plan.width},
        {"isa", p.structure || plan.width == 0 ? "scalar" : plan.isa},
        {"formats_packed", PacketFormats()},
        {"scalar_reason", p.structure ? "only the kd-tree traces in packets" : plan.why_scalar}}},
      {"mrays_per_second", ts.seconds > 0 ? n / ts.seconds * 1e-6 : 0.0},
      {"per_ray", PerRayJson(ts, mailbox)},
      {"totals", {{"nodes", ts.nodes}, {"leaves", ts.leaves}, {"tri_tests", ts.tri_tests}}},
      {"precision", check.requirement.Json()},
      {"warnings", check.warnings},
  };
  if (!p.structure) j["build"] = BuildOptionsJson(args.scene.build, p.tree.stats);
  for (const std::string& w : p.scene.warnings) j["warnings"].push_back(w);

  // Shading: the secondary passes, traced by the same model.
  ShadedFrame frame;
  if (args.shading.On()) {
    const PassTracer trace = [&](const RayPass& pass, nlohmann::json* stats) {
      // Secondary rays start on surfaces: they get their own precision check.
      for (const std::string& w :
           CheckPrecision(image, pass.rays, to.format, args.strict, args.threads, pass.name, narrow_image).warnings) {
        j["warnings"].push_back(w);
      }
      TraceOptions po = to;
      po.query = pass.query;
      po.progress = false;
      po.row_width = 0;  // a pass's rays in pixel order: packets of consecutive pixels
      AccelTotals ps;
      std::vector<Hit> h = TraceBatch(p, traced, pass.rays, po, &ps);
      *stats = PassStats(ps, mailbox);
      return h;
    };
    frame = TraceShadedFrame(p.scene, args.shading.options, rays, hits, PassStats(ts, mailbox), trace);
    j["passes"] = PassesJson(frame.passes);
  }

  OutputSet outputs;
  const std::string out = args.out.empty() ? DefaultImageName(args.scene.scene, !args.rays.empty()) : args.out;
  AddTraceOutputs(outputs, p.scene, ray_set, hits, out, args.hits, args.json, j,
                  args.shading.On() ? &frame.rgb : nullptr);
  if (!args.shading.write_rays.empty()) AddRayPassFiles(outputs, args.shading.write_rays, frame.passes);
  outputs.Commit();

  if (!args.quiet) {
    PrintTreeStats(p);
    std::printf("format         %s%s, %s test (minimal format %s)\n", args.format.c_str(),
                mixed ? (" (traversal " + TravFormat(to).Name() + ")").c_str() : "", IsectMethodName(to.isect),
                check.requirement.MinimalFormat().c_str());
    if (!p.structure) {
      std::printf("memory image   %zu bytes (%s", traced.size(), fp::Format{layout.e, layout.m}.Name().c_str());
      if (!layout.IsFp32()) std::printf("; the fp32 image: %zu", p.image.size());
      std::printf(")\n");
    }
    std::printf("rays           %llu (%dx%d), %llu hits (%.1f %%)\n", static_cast<unsigned long long>(ts.rays), width,
                height, static_cast<unsigned long long>(ts.hits), 100.0 * ts.hits / n);
    std::printf("per ray        %.2f %s, %.2f leaves, %.2f triangle tests", ts.nodes / n,
                p.structure ? "cells/nodes" : "nodes", ts.leaves / n, ts.tri_tests / n);
    if (mailbox) std::printf(", %.2f tests saved by the mailboxes", ts.mailbox_hits / n);
    std::printf("\n");
    std::printf("trace time     %.3f s, %.2f Mrays/s\n", ts.seconds, ts.seconds > 0 ? n / ts.seconds * 1e-6 : 0.0);
    for (size_t k = 1; k < frame.passes.size(); ++k) {
      const TracedPass& tp = frame.passes[k];
      const double pn = static_cast<double>(tp.pass.rays.size());
      if (tp.stats.is_null()) {
        std::printf("pass %-9s 0 rays\n", tp.pass.name.c_str());
        continue;
      }
      const auto& pr = tp.stats["per_ray"];
      std::printf("pass %-9s %zu rays (%s), %llu hits (%.1f %%), %.2f nodes, %.2f triangle tests per ray\n",
                  tp.pass.name.c_str(), tp.pass.rays.size(), tp.pass.query == Query::kAny ? "any hit" : "closest hit",
                  static_cast<unsigned long long>(tp.stats["hits"].get<uint64_t>()),
                  100.0 * tp.stats["hits"].get<double>() / pn, pr["nodes"].get<double>(), pr["tri_tests"].get<double>());
    }
    if (!out.empty()) std::printf("image          %s\n", out.c_str());
    if (!args.hits.empty()) std::printf("hit buffer     %s\n", args.hits.c_str());
    if (!args.json.empty()) std::printf("stats          %s\n", args.json.c_str());
    if (!args.shading.write_rays.empty()) std::printf("ray sets       %s\n", args.shading.write_rays.c_str());
  }
  return 0;
}

}  // namespace

Runner AddRenderCommand(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Trace a scene with the software reference tracer");
  AddSceneOptions(*cmd, args->scene, /*structures=*/true);
  cmd->add_option("--res", args->res, "Image resolution WxH (default: the scene's, else 512x512)");
  cmd->add_option("-o,--output", args->out, "Image file (.png, .ppm, .exr; default: <scene>.png)");
  cmd->add_option("--hits", args->hits, "EXR hit buffer with channels t, prim, u, v");
  cmd->add_option("--json", args->json, "Machine-readable statistics");
  cmd->add_option("--isect", args->isect, "Ray/triangle test: watertight or moller")->capture_default_str();
  cmd->add_option("--format", args->format, "Number format of traversal and intersection: " + fp::PresetNames() +
                                                            ", eXmY, or fp64 (native double, the accuracy reference)")
      ->capture_default_str();
  cmd->add_option("--trav-format", args->trav_format,
                  "Number format of the traversal alone (clip, split distances, cell intervals, stack), at least "
                  "--format's exponent and mantissa bits; default: --format. Splits and vertices stay stored in "
                  "--format. kdrt sim --trav-format runs the RTL core with that traversal (at most fp32)");
  cmd->add_option("--image-format", args->image_format,
                  "Memory image the tracer reads: native (splits and vertices stored in --format's width; "
                  "fp64 reads the fp32 image), fp32 (every format rounds on load; the hits are native's), or a "
                  "format narrower than --format (at most its exponent and mantissa bits: splits and vertices "
                  "stored in fewer bits and loaded exactly, the arithmetic in --format; kdrt sim --image-format)")
      ->capture_default_str();
  cmd->add_flag("--strict", args->strict,
                "Refuse (exit 1, no output) instead of warning: a format that cannot represent the scene, or "
                "data of the scene file the reader would leave out");
  cmd->add_option("--rays", args->rays, "Trace this ray file (KDRTRAYS) instead of the camera");
  cmd->add_option("--camera", args->camera, "Override the camera: \"fx fy fz ax ay az ux uy uz angle\"");
  AddShadingOptions(*cmd, args->shading);
  cmd->add_option("--threads", args->threads, "Threads (0: all cores; results do not depend on it)");
  cmd->add_option("--packets", args->packets,
                  "Rays traced together: off, 4, 8 or 16 (camera rays by tiles, shading passes by pixel; the same bits "
                  "either way). Packed: " + std::string(PacketFormats()) + "; other formats trace one ray at a time")
      ->capture_default_str()
      ->each([args](const std::string&) { args->packets_given = true; });
  cmd->add_flag("-q,--quiet", args->quiet, "No summary on stdout");
  return [cmd, args]() { return cmd->parsed() ? Run(*args) : -1; };
}

}  // namespace kdrt::cli
