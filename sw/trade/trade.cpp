#include "trade/trade.h"

#include <unistd.h>

#include <cinttypes>
#include <cstdio>

#include "common/error.h"
#include "sim/core_params.h"
#include "sim/model_runner.h"
#include "sim/phys.h"
#include "trace/hit_compare.h"
#include "trace/images.h"
#include "trace/precision.h"
#include "trace/tracer.h"

namespace kdrt::trade {
namespace {

void Say(const TradeOptions& o, const std::string& text) {
  if (o.progress) o.progress(text);
}

// Traces every ray in `format` and fills the software columns.
FormatResult Trace(const PreparedScene& p, const RaySet& rays, const fp::Format& format, const TradeOptions& o) {
  FormatResult r;
  r.format = format;
  TraceOptions to;
  to.format = format;
  to.threads = o.threads;
  TraceStats ts;
  // The format's own packed image (fp64: the fp32 one): the same hits as
  // from the fp32 image, and the bytes a core of this format would hold.
  const img::ImageLayout layout = LayoutFor(format);
  const std::vector<uint8_t> packed = layout.IsFp32() ? std::vector<uint8_t>{} : RepackImage(ImageView(p.image), layout);
  r.hits = TraceRays(layout.IsFp32() ? ImageView(p.image) : ImageView(packed), rays.rays, to, &ts);
  const double n = rays.rays.empty() ? 1.0 : static_cast<double>(rays.rays.size());
  r.nodes = ts.totals.nodes / n;
  r.leaves = ts.totals.leaves / n;
  r.tri_tests = ts.totals.tri_tests / n;
  r.trace_seconds = ts.seconds;
  r.rgb = ShadeEyeLight(p.scene, rays.rays, r.hits);
  r.memory_bytes = layout.IsFp32() ? p.image.size() : packed.size();
  return r;
}

// Runs the RTL core on every stride-th ray and checks its records against the
// reference tracer's in the same format, as `kdrt sim` does (a whole frame in
// Z-order, as `kdrt sim`'s default; a subsample in its order).
SimNumbers Simulate(const PreparedScene& p, const RaySet& rays, uint64_t stride, const FormatResult& r,
                    bool progress) {
  std::vector<Ray> sub;
  std::vector<size_t> index;
  for (size_t i = 0; i < rays.rays.size(); i += stride) {
    sub.push_back(rays.rays[i]);
    index.push_back(i);
  }
  sim::RunOptions run;
  run.progress = progress;  // the model's own progress line
  if (stride == 1) {  // the whole frame: in kdrt sim's order for a camera's rays
    run.ray_order = sim::kFrameRayOrder;
    run.frame_width = static_cast<uint32_t>(rays.width);
  }
  const sim::ModelRun m = sim::Simulate(p.image, sub, r.format, run);
  if (m.exit_code != 0) {
    throw InputError("the RTL core failed in " + r.format.Name() + " (kdrt sim exit " + std::to_string(m.exit_code) +
                     "; its messages are above)");
  }
  for (size_t k = 0; k < sub.size(); ++k) {
    if (!SameBits(m.hits[k], r.hits[index[k]])) {
      throw InputError("the RTL core and the reference differ in " + r.format.Name() + " at ray " +
                       std::to_string(index[k]) + ": RTL " + HitText(m.hits[k]) + ", reference " +
                       HitText(r.hits[index[k]]));
    }
  }
  SimNumbers s;
  s.rays = sub.size();
  s.cycles_per_ray = m.report.value("cycles_per_ray", 0.0);
  s.efficiency = m.report.value("efficiency", 0.0);
  if (m.report.contains("memory")) s.bytes_per_ray = m.report["memory"].value("bytes_per_ray", 0.0);
  s.cache_hit_rate = m.report.value("cache_hit_rate", nlohmann::json::object());
  s.model = m.report.value("model", nlohmann::json::object());
  return s;
}

// The configuration a model run reports in "model" (CoreConfig::Json).
sim::CoreConfig ConfigOf(const nlohmann::json& model) {
  sim::CoreConfig c;
  for (int i = 0; i < sim::kParamCount; ++i) c.value[i] = model.at(sim::kCoreParams[i].sv_name).get<int>();
  return c;
}

}  // namespace

std::optional<double> FormatResult::RaysPerCyclePerKcell() const {
  if (!sim || !area || area->cells <= 0 || sim->cycles_per_ray <= 0) return std::nullopt;
  return sim->RaysPerCycle() / (area->cells / 1000.0);
}

namespace {
std::optional<double> PhysicalNumber(const nlohmann::json& physical, const nlohmann::json::json_pointer& at) {
  if (!physical.is_object() || !physical.contains(at) || !physical[at].is_number()) return std::nullopt;
  return physical[at].get<double>();
}
}  // namespace

std::optional<double> FormatResult::MraysPerSPerMm2() const {
  return PhysicalNumber(physical, nlohmann::json::json_pointer("/mrays_per_s_per_mm2"));
}

std::optional<double> FormatResult::MraysPerSPerMm2At28nm() const {
  return PhysicalNumber(physical, nlohmann::json::json_pointer("/scaled/28nm/mrays_per_s_per_mm2"));
}

std::string Recommend(const std::vector<FormatResult>& formats, double target) {
  const FormatResult* best = nullptr;
  for (const FormatResult& r : formats) {
    if (r.accuracy.MismatchFraction() > target || r.holes.holes != 0) continue;
    if (best == nullptr || r.format.Width() < best->format.Width() ||
        (r.format.Width() == best->format.Width() && r.area && best->area && r.area->cells < best->area->cells)) {
      best = &r;
    }
  }
  return best ? best->format.Name() : "";
}

TradeResult MeasureTrade(const PreparedScene& p, const RaySet& rays, const TradeOptions& o) {
  for (const fp::Format& f : o.formats) {
    if (f.IsFp64()) throw InputError("trade: fp64 is the truth every format is compared with, not a format to trade");
  }
  TradeResult t;
  t.scene = p.scene.source;
  t.triangles = p.scene.triangles.size();
  t.width = rays.width;
  t.height = rays.height;
  t.rays = rays.rays.size();
  t.target_mismatch = o.target_mismatch;
  if (o.sim && o.sim_rays > 0 && o.sim_rays < t.rays) {
    t.sim_stride = (t.rays + o.sim_rays - 1) / o.sim_rays;
    t.notes.push_back("cycles are measured on a subsample: every " + std::to_string(t.sim_stride) + "th ray (" +
                      std::to_string((t.rays + t.sim_stride - 1) / t.sim_stride) + " of " + std::to_string(t.rays) +
                      ")");
  }

  Say(o, "precision requirement of the scene");
  const PrecisionRequirement req = AnalyzePrecision(ImageView(p.image), rays.rays, o.threads);
  t.minimal_format = req.MinimalFormat();

  Say(o, "fp64 (truth): tracing " + std::to_string(t.rays) + " rays");
  t.truth = Trace(p, rays, fp::kFp64, o);
  t.truth.holes = WatertightHoles(fp::kFp64);

  const size_t n = o.formats.size();
  std::string no_synthesis;  // the simulated formats whose configuration has no synthesis in build/phys
  for (size_t k = 0; k < n; ++k) {
    const fp::Format& f = o.formats[k];
    const std::string tag = "[" + std::to_string(k + 1) + "/" + std::to_string(n) + "] " + f.Name() + ": ";
    Say(o, tag + "tracing");
    FormatResult r;
    try {
      r = Trace(p, rays, f, o);
    } catch (const InputError& e) {
      // The format's packed image cannot hold this tree (docs/memory-image.md):
      // the other formats are still compared, and the table says why this one is missing.
      t.notes.push_back(f.Name() + " is left out: " + e.what());
      continue;
    }
    r.warning = req.Shortfall(f);
    if (!r.warning.empty()) std::fprintf(stderr, "kdrt: warning: %s\n", r.warning.c_str());
    r.accuracy = CompareWithTruth(r.hits, t.truth.hits, r.rgb, t.truth.rgb);
    Say(o, tag + "watertightness set");
    r.holes = WatertightHoles(f);
    if (o.sim) {
      Say(o, tag + "simulating the RTL core on " + std::to_string((t.rays + t.sim_stride - 1) / t.sim_stride) +
                 " rays");
      r.sim = Simulate(p, rays, t.sim_stride, r, o.progress && isatty(STDERR_FILENO));
      // The physical cost of exactly the simulated configuration, when it
      // was synthesized (kdrt synth); never another configuration's.
      const sim::CoreConfig config = ConfigOf(r.sim->model);
      const nlohmann::json core = sim::ReadCoreJson(config);
      if (core.is_null()) {
        no_synthesis += (no_synthesis.empty() ? "" : ", ") + f.Name() + " (" + config.Key() + ")";
      } else {
        r.physical = sim::PhysicalBlock(core, sim::PhysPath(config), config, r.sim->cycles_per_ray);
        for (const auto& e : r.physical["estimated_units"]) {
          t.notes.push_back(f.Name() + " physical: " + e["unit"].get<std::string>() + " is estimated (" +
                            e["method"].get<std::string>() + "), not synthesized");
        }
      }
    }
    if (o.area) {
      Say(o, tag + "area");
      r.area = CoreArea(f, o.area_options);
      if (r.area->source == "estimate") {
        t.notes.push_back(f.Name() + " area is an estimate (" + r.area->detail + "), not a synthesis");
      }
    }
    t.formats.push_back(std::move(r));
  }
  if (!no_synthesis.empty()) {
    t.notes.push_back("no synthesis of the simulated core of " + no_synthesis +
                      " in build/phys: no Mrays/s per mm^2 for them (kdrt synth SCENE --format F, minutes each); "
                      "their area columns are the units' generic Yosys cells at the units' module defaults");
  } else if (!o.sim && o.area) {
    t.notes.push_back("area columns: the units' generic Yosys cells at the units' module defaults, not a cell "
                      "library's area; --sim with a synthesis of the simulated core (kdrt synth) adds Mrays/s per mm^2");
  }
  if (o.area) {
    // rt_mem_system has no format parameter in the table: it is counted with
    // fp32's 3-beat triangle lines, where some narrower cores' images have
    // 2- or 1-beat lines (docs/memory-image.md).
    std::string narrower;
    for (const FormatResult& r : t.formats) {
      if (LayoutFor(r.format).TriangleLineBeats() < 3) narrower += (narrower.empty() ? "" : ", ") + r.format.Name();
    }
    if (!narrower.empty()) {
      t.notes.push_back("area of " + narrower + " counts rt_mem_system with fp32's 3-beat triangle cache lines; "
                        "those cores read shorter lines, so their cells and flip-flops are overestimated (docs/trade.md)");
    }
    // The unit rows are the units at their module sizes; the simulated core
    // is the prebuilt default's (DefaultConfig), the same sizes in every format.
    const sim::CoreConfig c = sim::DefaultConfig(fp::kFp32);
    const std::string note = UnitSizesNote(c[sim::kThreads], c[sim::kCacheMshrs], c[sim::kCacheTargets],
                                           c[sim::kListPrefetch]);
    if (!note.empty()) t.notes.push_back(note);
  }
  if (t.formats.empty()) {
    std::string why;
    for (const std::string& note : t.notes) why += "; " + note;
    throw InputError("trade: no format to compare" + why);
  }
  t.recommended = Recommend(t.formats, o.target_mismatch);
  for (const std::string& note : t.notes) std::fprintf(stderr, "kdrt: note: %s\n", note.c_str());
  return t;
}

}  // namespace kdrt::trade
