// kdrt info: tree statistics, memory image size and the precision the scene
// requires (trace/precision.h) for its rays: the camera's, or --rays.
#include <algorithm>
#include <cstdio>
#include <fstream>

#include "common/error.h"
#include "tools/commands.h"
#include "setup/prepared_scene.h"
#include "setup/ray_set.h"
#include "setup/trace_outputs.h"
#include "tools/scene_options.h"
#include "trace/output_file.h"
#include "trace/memory_image.h"
#include "trace/precision.h"

namespace kdrt::cli {
namespace {

struct InfoArgs {
  SceneSpec scene;
  std::string json;
  std::string image_out;
  std::string rays;
  std::string format = "fp32";
  int threads = 0;
  bool strict = false;
};

// The image of each format: section sizes and the total.
nlohmann::json ImageSizes(const std::vector<uint8_t>& bytes) {
  const ImageView v(bytes);
  const img::Header& h = v.header();
  return {{"bytes", bytes.size()},
          {"node_bytes", v.layout().NodeSectionBytes(h.node_count)},
          {"list_bytes", uint64_t{h.list_count} * img::kListEntryBytes},
          {"tri_bytes", v.layout().TriangleSectionBytes(h.tri_count)},
          {"nodes_per_beat", v.layout().NodesPerBeat()},
          {"triangle_line_bytes", v.layout().TriangleLineBytes()},
          {"triangles_per_line", v.layout().TrianglesPerLine()}};
}

// "exponent bits set by A, mantissa bits by B": the criteria at the minimum.
std::string LimitingCriteria(const PrecisionRequirement& req) {
  std::string e, m;
  for (const PrecisionCriterion& c : req.criteria) {
    const int need = c.exponent ? req.min_exponent_bits : req.min_mantissa_bits;
    if (c.MinBits() != need) continue;
    std::string& list = c.exponent ? e : m;
    list += (list.empty() ? "" : ", ") + c.name;
  }
  return "exponent bits set by " + (e.empty() ? std::string("nothing") : e) + ", mantissa bits by " +
         (m.empty() ? std::string("nothing") : m);
}

int Run(const InfoArgs& args) {
  const fp::Format format = fp::ParseFormat(args.format);
  const img::ImageLayout layout = LayoutFor(format);
  SceneSpec spec = args.scene;
  spec.strict = args.strict;
  const PreparedScene p = PrepareScene(spec);
  const RaySet ray_set = MakeRays(p.scene, args.rays, "", "");
  const ImageView fp32_image(p.image);
  const PrecisionRequirement req = AnalyzePrecision(fp32_image, ray_set.rays, args.threads);
  // The image of every preset and of --format, packed in its width.
  std::vector<fp::Format> formats = fp::Presets();
  if (!format.IsFp64() && std::find(formats.begin(), formats.end(), format) == formats.end()) {
    formats.push_back(format);
  }
  nlohmann::json images = nlohmann::json::object();
  std::vector<uint8_t> chosen = p.image;
  for (const fp::Format& f : formats) {
    const img::ImageLayout l = LayoutFor(f);
    const bool is_chosen = l.e == layout.e && l.m == layout.m;
    std::vector<uint8_t> bytes;
    try {
      bytes = l.IsFp32() ? p.image : RepackImage(fp32_image, l);
    } catch (const InputError& e) {
      if (is_chosen) throw;  // the image asked for cannot be built: an error
      // Another preset's image does not fit this tree: said, not fatal.
      images[f.Name()] = {{"error", e.what()}};
      std::fprintf(stderr, "kdrt: note: no %s image: %s\n", f.Name().c_str(), e.what());
      continue;
    }
    images[f.Name()] = ImageSizes(bytes);
    if (is_chosen) chosen = std::move(bytes);
  }
  OutputSet outputs;
  if (!args.json.empty()) {
    nlohmann::json j = {{"command", "info"},
                        {"scene", p.scene.source},
                        {"triangles", p.scene.triangles.size()},
                        {"accel", SplitMethodName(args.scene.build.method)},
                        {"tree", TreeStatsJson(p.tree.stats)},
                        {"build", BuildOptionsJson(args.scene.build, p.tree.stats)},
                        {"image_format", fp::Format{layout.e, layout.m}.Name()},
                        {"image_bytes", chosen.size()},
                        {"images", images},
                        {"precision", req.Json()},
                        {"warnings", p.scene.warnings}};
    AddJsonOutput(outputs, args.json, j);
  }
  if (!args.image_out.empty()) {
    outputs.Add(args.image_out, [&](const std::string& tmp) {
      std::ofstream f(tmp, std::ios::binary);
      f.write(reinterpret_cast<const char*>(chosen.data()), static_cast<std::streamsize>(chosen.size()));
      if (!f) throw InputError(args.image_out, 0, "cannot write memory image");
    });
  }
  outputs.Commit();
  PrintTreeStats(p);
  std::printf("image by format");
  for (const fp::Format& f : formats) {
    const nlohmann::json& im = images[f.Name()];
    if (im.contains("bytes")) {
      std::printf(" %s %llu", f.Name().c_str(), im["bytes"].get<unsigned long long>());
    } else {
      std::printf(" %s -", f.Name().c_str());
    }
  }
  std::printf(" bytes (splits and vertices in the format's width)\n");
  std::printf("minimal format  %s\n", req.MinimalFormat().c_str());
  std::printf("minimal image   %s (the stored scene alone: the narrowest --image-format)\n",
              req.MinimalImageFormat().c_str());
  std::printf("precision      for %llu %s (%llu hits in fp64); %s\n", static_cast<unsigned long long>(req.rays),
              args.rays.empty() ? "camera rays" : "rays", static_cast<unsigned long long>(req.hit_tests),
              LimitingCriteria(req).c_str());
  return 0;
}

}  // namespace

Runner AddInfoCommand(CLI::App& app) {
  auto args = std::make_shared<InfoArgs>();
  CLI::App* cmd = app.add_subcommand("info", "Build the kd-tree and print its statistics and the image size");
  AddSceneOptions(*cmd, args->scene);
  cmd->add_option("--json", args->json, "Machine-readable statistics");
  cmd->add_option("--image", args->image_out, "Write the memory image (docs/memory-image.md) to this file");
  cmd->add_option("--format", args->format,
                  "Number format of the image --image writes and image_bytes reports: splits and vertices stored "
                  "in its width (" + fp::PresetNames() + ", eXmY; fp64 reads the fp32 image)")
      ->capture_default_str();
  cmd->add_option("--rays", args->rays,
                  "Derive the precision requirement for this ray file (KDRTRAYS) instead of the camera rays");
  cmd->add_option("--threads", args->threads, "Threads of the precision analysis (0: all cores)");
  cmd->add_flag("--strict", args->strict,
                "Refuse (exit 1, no output) data of the scene file the reader would leave out instead of warning");
  return [cmd, args]() { return cmd->parsed() ? Run(*args) : -1; };
}

}  // namespace kdrt::cli
