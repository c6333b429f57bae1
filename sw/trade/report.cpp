#include "trade/report.h"

#include <cmath>
#include <sstream>
#include <string>

namespace kdrt::trade {
namespace {

std::string Fixed(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, x);
  return buf;
}

std::string Sci(double x) {
  if (x == 0) return "0";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1e", x);
  return buf;
}

std::string PsnrText(double db) { return std::isinf(db) ? "inf" : Fixed(db, 1); }

// JSON has no infinity: an identical image is null with "identical": true.
nlohmann::json PsnrJson(double db) { return std::isinf(db) ? nlohmann::json(nullptr) : nlohmann::json(db); }

nlohmann::json FormatJson(const FormatResult& r) {
  const Accuracy& a = r.accuracy;
  nlohmann::json j = {
      {"format", r.format.Name()},
      {"E", r.format.e},
      {"M", r.format.m},
      {"bits", r.format.Width()},
      {"warning", r.warning},
      {"accuracy",
       {{"hitmiss_mismatch", a.HitmissFraction()},
        {"prim_mismatch", a.PrimFraction()},
        {"mismatch", a.MismatchFraction()},
        {"hitmiss_rays", a.hitmiss},
        {"prim_rays", a.prim},
        {"common_hits", a.common_hits},
        {"t_rel_p50", a.t_rel_p50},
        {"t_rel_p99", a.t_rel_p99},
        {"t_rel_max", a.t_rel_max},
        {"psnr_db", PsnrJson(a.psnr_db)},
        {"identical_image", std::isinf(a.psnr_db)},
        {"holes", r.holes.holes},
        {"holes_must_hit", r.holes.must_hit}}},
      {"work", {{"nodes", r.nodes}, {"leaves", r.leaves}, {"tri_tests", r.tri_tests}}},
      {"trace_seconds", r.trace_seconds},
      {"memory_bytes", r.memory_bytes},
      {"cycles_per_ray", nullptr},
      {"rays_per_cycle", nullptr},
      {"efficiency", nullptr},
      {"bytes_per_ray", nullptr},
      {"area", nullptr},
      {"rays_per_cycle_per_kcell", nullptr},
  };
  if (r.sim) {
    j["cycles_per_ray"] = r.sim->cycles_per_ray;
    j["rays_per_cycle"] = r.sim->RaysPerCycle();
    j["efficiency"] = r.sim->efficiency;
    j["bytes_per_ray"] = r.sim->bytes_per_ray;
    j["cache_hit_rate"] = r.sim->cache_hit_rate;
    j["sim_rays"] = r.sim->rays;
  }
  if (r.area) {
    j["area"] = {{"cells", r.area->cells},
                 {"flip_flops", r.area->flip_flops},
                 {"depth", r.area->depth},
                 {"sram_bits", r.area->sram_bits},
                 {"source", r.area->source},
                 {"detail", r.area->detail}};
  }
  if (auto perf = r.RaysPerCyclePerKcell()) j["rays_per_cycle_per_kcell"] = *perf;
  if (r.sim) j["model"] = r.sim->model;
  j["physical"] = r.physical;
  return j;
}

}  // namespace

nlohmann::json TradeJson(const TradeResult& t) {
  nlohmann::json formats = nlohmann::json::array();
  for (const FormatResult& r : t.formats) formats.push_back(FormatJson(r));
  nlohmann::json truth = FormatJson(t.truth);
  truth.erase("accuracy");
  truth["holes"] = t.truth.holes.holes;
  return {{"command", "trade"},
          {"scene", t.scene},
          {"triangles", t.triangles},
          {"width", t.width},
          {"height", t.height},
          {"rays", t.rays},
          {"sim_stride", t.sim_stride},
          {"truth", truth},
          {"holes_set", t.truth.holes.cases},
          {"minimal_format", t.minimal_format},
          {"target_mismatch", t.target_mismatch},
          {"recommended", t.recommended.empty() ? nlohmann::json(nullptr) : nlohmann::json(t.recommended)},
          {"notes", t.notes},
          {"formats", formats}};
}

void PrintTable(const TradeResult& t, FILE* out) {
  std::fprintf(out, "scene          %s, %llu triangles, %llu rays (%dx%d)\n", t.scene.c_str(),
               static_cast<unsigned long long>(t.triangles), static_cast<unsigned long long>(t.rays), t.width,
               t.height);
  std::fprintf(out, "\naccuracy against fp64 (hit/miss, triangle: fraction of rays; t: relative error over common "
                    "hits; holes: of %llu must-hit rays)\n",
               static_cast<unsigned long long>(t.truth.holes.must_hit));
  std::fprintf(out, "%-8s %4s %9s %9s %9s %9s %9s %7s %6s\n", "format", "bits", "hit/miss", "triangle", "t p50",
               "t p99", "t max", "PSNR", "holes");
  for (const FormatResult& r : t.formats) {
    const Accuracy& a = r.accuracy;
    std::fprintf(out, "%-8s %4d %9s %9s %9s %9s %9s %7s %6llu%s\n", r.format.Name().c_str(), r.format.Width(),
                 Sci(a.HitmissFraction()).c_str(), Sci(a.PrimFraction()).c_str(), Sci(a.t_rel_p50).c_str(),
                 Sci(a.t_rel_p99).c_str(), Sci(a.t_rel_max).c_str(), PsnrText(a.psnr_db).c_str(),
                 static_cast<unsigned long long>(r.holes.holes), r.warning.empty() ? "" : "  W");
  }
  std::fprintf(out, "\ncost (per ray: nodes, leaves, triangle tests from the model; cycles from the RTL core; "
                    "area: the core's units in Yosys cells)\n");
  std::fprintf(out, "%-8s %7s %7s %7s %9s %6s %9s %9s %8s %6s %9s %-8s\n", "format", "nodes", "leaves", "tests",
               "cyc/ray", "eff", "bytes/ray", "cells", "FFs", "depth", "ray/c/kc", "area");
  auto row = [&](const FormatResult& r, const char* name) {
    std::fprintf(out, "%-8s %7.2f %7.2f %7.2f", name, r.nodes, r.leaves, r.tri_tests);
    if (r.sim) {
      std::fprintf(out, " %9.2f %5.1f%% %9.1f", r.sim->cycles_per_ray, 100 * r.sim->efficiency,
                   r.sim->bytes_per_ray);
    } else {
      std::fprintf(out, " %9s %6s %9s", "-", "-", "-");
    }
    if (r.area) {
      std::fprintf(out, " %9lld %8lld %6d", static_cast<long long>(r.area->cells),
                   static_cast<long long>(r.area->flip_flops), r.area->depth);
    } else {
      std::fprintf(out, " %9s %8s %6s", "-", "-", "-");
    }
    const auto perf = r.RaysPerCyclePerKcell();
    std::fprintf(out, " %9s %-8s\n", perf ? Sci(*perf).c_str() : "-", r.area ? r.area->source.c_str() : "");
  };
  row(t.truth, "fp64");
  for (const FormatResult& r : t.formats) row(r, r.format.Name().c_str());
  std::string sram;
  for (const FormatResult& r : t.formats) {
    if (r.area && r.area->sram_bits > 0) {
      sram += " " + r.format.Name() + " " + std::to_string(static_cast<long long>(r.area->sram_bits));
    }
  }
  if (!sram.empty()) {
    std::fprintf(out, "SRAM          %s bits of memories beside the cells (caches' lines, stacks, queues: SRAM "
                      "macros, whose area is not a Yosys figure)\n",
                 sram.c_str());
  }
  bool physical = false;
  for (const FormatResult& r : t.formats) physical |= !r.physical.is_null();
  if (physical) {
    std::fprintf(out, "\nphysical cost of the simulated core (kdrt synth: every unit on the cell library; 28 nm: "
                      "Stillmaker & Baas 2017, interpolated between 32 and 20 nm)\n");
    std::fprintf(out, "%-8s %-8s %8s %9s %11s %13s %13s  %s\n", "format", "library", "clock ns", "mm^2", "Mrays/s",
                 "Mrays/s/mm^2", "28nm /mm^2", "critical unit");
    for (const FormatResult& r : t.formats) {
      const nlohmann::json& p = r.physical;
      if (p.is_null()) {
        std::fprintf(out, "%-8s no synthesis of %s\n", r.format.Name().c_str(),
                     r.sim ? r.sim->model.value("key", "?").c_str() : "its core (no --sim)");
        continue;
      }
      std::fprintf(out, "%-8s %-8s %8.2f %9.3f %11.3f %13.4f %13.2f  %s%s\n", r.format.Name().c_str(),
                   p["library"].get<std::string>().c_str(), p["clock_ns"].get<double>(),
                   p["area_mm2"]["total"].get<double>(), p["mrays_per_s"].get<double>(),
                   p["mrays_per_s_per_mm2"].get<double>(), p["scaled"]["28nm"]["mrays_per_s_per_mm2"].get<double>(),
                   p["critical_unit"].get<std::string>().c_str(),
                   p["estimated_units"].empty() ? "" : " (estimated units: see notes)");
    }
  }
  std::fprintf(out, "\nmemory image  ");
  for (const FormatResult& r : t.formats) {
    std::fprintf(out, " %s %llu", r.format.Name().c_str(), static_cast<unsigned long long>(r.memory_bytes));
  }
  std::fprintf(out, " bytes (splits and vertices in the format's width)\n");
  std::fprintf(out, "minimal format %s (the scene's precision requirement)\n", t.minimal_format.c_str());
  std::fprintf(out, "recommended    %s (smallest format with at most %s of rays whose hit differs from fp64 (hit/miss or triangle), "
                    "and no holes)\n",
               t.recommended.empty() ? "none" : t.recommended.c_str(), Sci(t.target_mismatch).c_str());
  bool warned = false;
  for (const FormatResult& r : t.formats) warned |= !r.warning.empty();
  if (warned) std::fprintf(out, "W: the scene's precision requirement says the format cannot represent it\n");
  for (const std::string& note : t.notes) std::fprintf(out, "note: %s\n", note.c_str());
}

std::string TradeCsv(const TradeResult& t) {
  std::ostringstream s;
  s << "scene,format,E,M,bits,hitmiss_mismatch,prim_mismatch,t_rel_p50,t_rel_p99,t_rel_max,psnr_db,holes,nodes,"
       "leaves,tri_tests,cycles_per_ray,efficiency,bytes_per_ray,cells,flip_flops,depth,sram_bits,area_source,"
       "memory_bytes,"
       "rays_per_cycle_per_kcell,area_mm2,clock_ns,mrays_per_s,mrays_per_s_per_mm2,mrays_per_s_per_mm2_28nm,"
       "warning\n";
  s.precision(9);
  for (const FormatResult& r : t.formats) {
    const Accuracy& a = r.accuracy;
    s << '"' << t.scene << "\"," << r.format.Name() << ',' << r.format.e << ',' << r.format.m << ','
      << r.format.Width() << ',' << a.HitmissFraction() << ',' << a.PrimFraction() << ',' << a.t_rel_p50 << ','
      << a.t_rel_p99 << ',' << a.t_rel_max << ',' << (std::isinf(a.psnr_db) ? "inf" : std::to_string(a.psnr_db))
      << ',' << r.holes.holes << ',' << r.nodes << ',' << r.leaves << ',' << r.tri_tests << ',';
    if (r.sim) {
      s << r.sim->cycles_per_ray << ',' << r.sim->efficiency << ',' << r.sim->bytes_per_ray << ',';
    } else {
      s << ",,,";
    }
    if (r.area) {
      s << r.area->cells << ',' << r.area->flip_flops << ',' << r.area->depth << ',' << r.area->sram_bits << ','
        << r.area->source << ',';
    } else {
      s << ",,,,,";
    }
    s << r.memory_bytes << ',';
    if (auto perf = r.RaysPerCyclePerKcell()) s << *perf;
    // The physical columns: empty without a synthesis of the simulated configuration.
    const nlohmann::json& p = r.physical;
    if (const auto per_mm2 = r.MraysPerSPerMm2()) {
      s << ',' << p["area_mm2"]["total"].get<double>() << ',' << p["clock_ns"].get<double>() << ','
        << p["mrays_per_s"].get<double>() << ',' << *per_mm2 << ',';
      if (auto scaled = r.MraysPerSPerMm2At28nm()) s << *scaled;
    } else {
      s << ",,,,";
    }
    std::string w = r.warning;
    for (char& c : w) c = c == '"' ? '\'' : c;
    s << ",\"" << w << "\"\n";
  }
  return s.str();
}

}  // namespace kdrt::trade
