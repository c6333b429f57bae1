// The `kdrt trade --html DIR` page: one self-contained index.html (inline
// style, no scripts, nothing fetched) with the images and plots beside it.
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.h"
#include "trace/images.h"
#include "trade/report.h"
#include "trade/svg_plot.h"

namespace kdrt::trade {
namespace {

std::string Esc(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return out;
}

std::string Fmt(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out.good()) throw InputError(path, 0, "cannot write");
}

// Red where the ray's hit differs from fp64's (hit/miss or triangle),
// elsewhere the shading difference amplified 8x on black.
std::vector<float> DifferenceImage(const FormatResult& r, const FormatResult& truth) {
  std::vector<float> rgb(r.rgb.size());
  for (size_t i = 0; i < r.hits.size(); ++i) {
    const bool other = r.hits[i].IsHit() != truth.hits[i].IsHit() ||
                       (r.hits[i].IsHit() && r.hits[i].prim != truth.hits[i].prim);
    for (int k = 0; k < 3; ++k) {
      const float d = std::min(1.0f, 8.0f * std::fabs(r.rgb[3 * i + k] - truth.rgb[3 * i + k]));
      rgb[3 * i + k] = other ? (k == 0 ? 1.0f : 0.0f) : d;
    }
  }
  return rgb;
}

std::string TableHtml(const TradeResult& t) {
  std::ostringstream s;
  s << "<table class=\"trade\">\n<tr><th>format</th><th>bits</th><th>hit/miss</th><th>triangle</th>"
       "<th>t p50</th><th>t p99</th><th>t max</th><th>PSNR dB</th><th>holes</th><th>nodes/ray</th>"
       "<th>leaves/ray</th><th>tests/ray</th><th>cycles/ray</th><th>efficiency</th><th>bytes/ray</th>"
       "<th>image bytes</th><th>cells</th><th>flip-flops</th><th>depth</th><th>area from</th>"
       "<th>rays/cycle/kcell</th><th>Mrays/s/mm^2</th><th>28 nm</th></tr>\n";
  for (const FormatResult& r : t.formats) {
    const Accuracy& a = r.accuracy;
    const bool rec = r.format.Name() == t.recommended;
    s << "<tr" << (rec ? " class=\"recommended\"" : "") << "><td>" << r.format.Name() << (rec ? " &#9733;" : "")
      << (r.warning.empty() ? "" : " <span title=\"" + Esc(r.warning) + "\">W</span>") << "</td><td>"
      << r.format.Width() << "</td><td>" << Fmt("%.2e", a.HitmissFraction()) << "</td><td>"
      << Fmt("%.2e", a.PrimFraction()) << "</td><td>" << Fmt("%.1e", a.t_rel_p50) << "</td><td>"
      << Fmt("%.1e", a.t_rel_p99) << "</td><td>" << Fmt("%.1e", a.t_rel_max) << "</td><td>"
      << (std::isinf(a.psnr_db) ? "identical" : Fmt("%.1f", a.psnr_db)) << "</td><td>" << r.holes.holes
      << "</td><td>" << Fmt("%.2f", r.nodes) << "</td><td>" << Fmt("%.2f", r.leaves) << "</td><td>"
      << Fmt("%.2f", r.tri_tests) << "</td>";
    if (r.sim) {
      s << "<td>" << Fmt("%.2f", r.sim->cycles_per_ray) << "</td><td>" << Fmt("%.1f %%", 100 * r.sim->efficiency)
        << "</td><td>" << Fmt("%.1f", r.sim->bytes_per_ray) << "</td>";
    } else {
      s << "<td>-</td><td>-</td><td>-</td>";
    }
    s << "<td>" << r.memory_bytes << "</td>";
    if (r.area) {
      s << "<td>" << r.area->cells << "</td><td>" << r.area->flip_flops << "</td><td>" << r.area->depth
        << "</td><td title=\"" << Esc(r.area->detail) << "\">" << r.area->source << "</td>";
    } else {
      s << "<td>-</td><td>-</td><td>-</td><td>-</td>";
    }
    const auto perf = r.RaysPerCyclePerKcell();
    const auto per_mm2 = r.MraysPerSPerMm2();
    const auto per_mm2_28 = r.MraysPerSPerMm2At28nm();
    s << "<td>" << (perf ? Fmt("%.2e", *perf) : "-") << "</td><td>" << (per_mm2 ? Fmt("%.4f", *per_mm2) : "-")
      << "</td><td>" << (per_mm2_28 ? Fmt("%.2f", *per_mm2_28) : "-") << "</td></tr>\n";
  }
  s << "</table>\n";
  return s.str();
}

// Error versus area and cycles versus area. Without area the x axis is the
// format's bits; without --sim the y axis of the cost plot is the model's
// triangle tests per ray. The titles say which.
void WritePlots(const TradeResult& t, const std::string& dir) {
  bool have_area = true, have_sim = true;
  for (const FormatResult& r : t.formats) {
    have_area &= r.area.has_value();
    have_sim &= r.sim.has_value();
  }
  const std::string x_title = have_area ? "area: cells of the core's units (Yosys)" : "format bits";
  auto x_of = [&](const FormatResult& r) {
    return have_area ? static_cast<double>(r.area->cells) : static_cast<double>(r.format.Width());
  };
  PlotSpec error{"Error versus area", x_title, "rays whose hit differs from fp64 (fraction)", false, true, "0", {}};
  PlotSpec cost{have_sim ? "Cycles versus area" : "Triangle tests versus area (no --sim)", x_title,
                have_sim ? "cycles per ray (RTL)" : "triangle tests per ray (model)", false, false, "0", {}};
  for (const FormatResult& r : t.formats) {
    error.points.push_back({x_of(r), r.accuracy.MismatchFraction(), r.format.Name()});
    cost.points.push_back({x_of(r), have_sim ? r.sim->cycles_per_ray : r.tri_tests, r.format.Name()});
  }
  WriteText(dir + "/error-vs-area.svg", ScatterSvg(error));
  WriteText(dir + "/cycles-vs-area.svg", ScatterSvg(cost));
}

// Error versus Mrays/s per mm^2 of the simulated core (kdrt sim's physical
// block), for the formats that have a synthesis of their configuration;
// written only when one has. Returns the formats left out.
std::vector<std::string> WritePhysicalPlot(const TradeResult& t, const std::string& dir, bool* written) {
  std::vector<std::string> left_out;
  std::string library;
  PlotSpec plot{"Error versus Mrays/s per mm^2", "", "rays whose hit differs from fp64 (fraction)", false, true, "0",
                {}};
  for (const FormatResult& r : t.formats) {
    const auto per_mm2 = r.MraysPerSPerMm2();
    if (!per_mm2) {
      left_out.push_back(r.format.Name());
      continue;
    }
    library = r.physical.value("library", "");
    plot.points.push_back({*per_mm2, r.accuracy.MismatchFraction(), r.format.Name()});
  }
  *written = !plot.points.empty();
  if (*written) {
    plot.x_title = "Mrays/s per mm^2 of the simulated core (" + library + ", kdrt synth)";
    WriteText(dir + "/error-vs-mrays-per-mm2.svg", ScatterSvg(plot));
  }
  return left_out;
}

std::string Joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

void WriteHtml(const TradeResult& t, const std::string& dir) {
  WritePlots(t, dir);
  bool physical_plot = false;
  const std::vector<std::string> no_synthesis = WritePhysicalPlot(t, dir, &physical_plot);
  const bool images = t.height > 1;  // a ray file has no picture
  if (images) {
    WriteRgbImage(dir + "/fp64.png", t.width, t.height, t.truth.rgb);
    for (const FormatResult& r : t.formats) {
      WriteRgbImage(dir + "/" + r.format.Name() + ".png", t.width, t.height, r.rgb);
      WriteRgbImage(dir + "/" + r.format.Name() + "-diff.png", t.width, t.height, DifferenceImage(r, t.truth));
    }
  }
  std::ostringstream s;
  s << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>kdrt trade: " << Esc(t.scene)
    << "</title>\n<style>\n"
       "body{font-family:sans-serif;margin:24px;color:#222}\n"
       "table.trade{border-collapse:collapse;font-size:12px}\n"
       "table.trade th{background:#1f4e79;color:#fff;padding:4px 5px}\n"
       "table.trade td{border:1px solid #bbb;padding:3px 5px;text-align:right;white-space:nowrap}\n"
       "tr.recommended td{background:#e2f0d9}\n"
       ".plots img{margin:8px 16px 8px 0;border:1px solid #ccc}\n"
       ".images{display:flex;flex-wrap:wrap;gap:16px}\n"
       ".images figure{margin:0}\n"
       ".images img{image-rendering:pixelated;width:200px;border:1px solid #ccc}\n"
       ".note{color:#8a4b00}\n"
       "</style></head><body>\n";
  s << "<h1>Speed/accuracy trade: " << Esc(t.scene) << "</h1>\n<p>" << t.triangles << " triangles, " << t.rays
    << " rays";
  if (images) s << " (" << t.width << "x" << t.height << ")";
  s << ". Accuracy against fp64 (fractions of rays; t errors over rays both hit; holes on the closed-mesh "
       "watertightness set: "
    << Esc(t.truth.holes.cases) << ", " << t.truth.holes.must_hit << " must-hit rays). Minimal format from the "
    << "scene's precision requirement: <b>" << Esc(t.minimal_format) << "</b>. Recommended (at most "
    << Fmt("%.0e", t.target_mismatch) << " of rays with another hit than fp64, no holes): <b>"
    << (t.recommended.empty() ? "none" : t.recommended) << "</b>.</p>\n";
  for (const std::string& note : t.notes) s << "<p class=\"note\">Note: " << Esc(note) << "</p>\n";
  s << "<div style=\"overflow-x:auto\">" << TableHtml(t) << "</div>\n";
  s << "<h2>Plots</h2>\n<div class=\"plots\"><img src=\"error-vs-area.svg\" alt=\"error versus area\">"
       "<img src=\"cycles-vs-area.svg\" alt=\"cycles versus area\">";
  if (physical_plot) s << "<img src=\"error-vs-mrays-per-mm2.svg\" alt=\"error versus Mrays/s per mm^2\">";
  s << "</div>\n";
  if (!no_synthesis.empty()) {
    s << "<p class=\"note\">Not in the Mrays/s per mm^2 " << (physical_plot ? "plot" : "column (and no plot)")
      << ": " << Esc(Joined(no_synthesis))
      << " (no synthesis of the simulated configuration: <code>kdrt synth SCENE --format F</code> with the same "
         "options, or <code>--sim</code> was not given).</p>\n";
  }
  if (images) {
    s << "<h2>Images</h2>\n<p>Top: each format's image; bottom: its difference against fp64 (red: the ray's hit "
         "differs (hit/miss or triangle); elsewhere the shading difference, amplified 8x).</p>\n<div class=\"images\">\n"
         "<figure><img src=\"fp64.png\" alt=\"fp64\"><figcaption>fp64 (truth)</figcaption></figure>\n";
    for (const FormatResult& r : t.formats) {
      const std::string n = r.format.Name();
      s << "<figure><img src=\"" << n << ".png\" alt=\"" << n << "\"><br><img src=\"" << n << "-diff.png\" alt=\""
        << n << " difference\"><figcaption>" << n << "</figcaption></figure>\n";
    }
    s << "</div>\n";
  } else {
    s << "<p>The rays came from a ray file: no images.</p>\n";
  }
  s << "<p>Generated by kdrt trade; the same numbers are in its JSON and CSV outputs.</p>\n</body></html>\n";
  WriteText(dir + "/index.html", s.str());
}

}  // namespace kdrt::trade
