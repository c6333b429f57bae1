#include "setup/accel_report.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "common/error.h"

namespace kdrt {
namespace {

std::string Format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// The cells of one row, in the order of kColumns.
std::vector<std::string> Cells(const AccelComparison& c, const AccelRow& r) {
  if (!r.error.empty()) {
    std::vector<std::string> cells(10, "-");
    cells[0] = AccelKindName(r.kind);
    cells[9] = "not built";
    return cells;
  }
  const double n = std::max<double>(1.0, static_cast<double>(r.totals.rays));
  return {
      AccelKindName(r.kind),
      Format("%.3f", r.build_seconds),
      Format("%.1f", r.memory_bytes / 1e6),
      Format("%.2f", c.triangles ? double(r.references) / c.triangles : 0.0),
      Format("%.1f", r.totals.nodes / n),
      Format("%.1f", r.totals.tri_tests / n),
      r.mailbox ? Format("%.1f", r.totals.mailbox_hits / n) : std::string("-"),
      Format("%.2f", r.Mrays()),
      Format("%.2f", r.time_ratio) + (r.time_ratio == 1.0 ? " *" : ""),
      r.mismatches == 0 ? (r.ties ? "yes (" + std::to_string(r.ties) + " ties)" : std::string("yes"))
                        : std::to_string(r.mismatches) + " DIFFER",
  };
}

const std::vector<std::string> kColumns = {"structure",  "build s",   "memory MB", "refs/tri", "nodes/ray",
                                           "tests/ray",  "mailbox/ray", "Mrays/s", "x best",   "same hits"};

std::string Escape(const std::string& s) {
  std::string o;
  for (char ch : s) {
    if (ch == '<') o += "&lt;";
    else if (ch == '>') o += "&gt;";
    else if (ch == '&') o += "&amp;";
    else o += ch;
  }
  return o;
}

}  // namespace

std::string AccelTable(const std::vector<AccelComparison>& scenes, bool markdown) {
  std::ostringstream out;
  for (const AccelComparison& c : scenes) {
    out << (markdown ? "**" : "") << c.scene << (markdown ? "**" : "") << ": " << c.triangles << " triangles, "
        << c.width << "x" << c.height << " primary rays\n";
    std::vector<std::vector<std::string>> table = {kColumns};
    for (const AccelRow& r : c.rows) table.push_back(Cells(c, r));
    std::vector<size_t> width(kColumns.size(), 0);
    for (const auto& row : table) {
      for (size_t k = 0; k < row.size(); ++k) width[k] = std::max(width[k], row[k].size());
    }
    for (size_t i = 0; i < table.size(); ++i) {
      if (markdown) {
        out << "|";
        for (const std::string& cell : table[i]) out << " " << cell << " |";
        out << "\n";
        if (i == 0) {
          out << "|";
          for (size_t k = 0; k < kColumns.size(); ++k) out << (k == 0 ? "---|" : "---:|");
          out << "\n";
        }
      } else {
        for (size_t k = 0; k < table[i].size(); ++k) {
          const std::string& cell = table[i][k];
          const std::string pad(width[k] - cell.size(), ' ');
          out << "  " << (k == 0 ? cell + pad : pad + cell);
        }
        out << "\n";
      }
    }
    for (const AccelRow& r : c.rows) {
      if (!r.error.empty()) out << (markdown ? "\n" : "  ") << AccelKindName(r.kind) << " not built: " << r.error << "\n";
    }
    out << "\n";
  }
  return out.str();
}

void WriteAccelHtml(const std::vector<AccelComparison>& scenes, const std::string& dir) {
  const std::string path = dir + "/index.html";
  std::ofstream f(path);
  if (!f) throw InputError(path, 0, "cannot write");
  f << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>kdrt compare-accel</title>\n"
       "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse;margin-bottom:0.5em}"
       "td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}td:first-child,th:first-child{text-align:left}"
       "tr.best{background:#e6f4e6}.bad{color:#b00;font-weight:bold}</style></head><body>\n"
       "<h1>Acceleration structures compared</h1>\n"
       "<p>Each structure built and traced on the same primary rays in one run (kdrt compare-accel). "
       "Memory counts nodes or cells and reference lists, not the triangles. "
       "<i>x best</i> is the trace time over the fastest structure's on that scene; "
       "<i>same hits</i> compares every hit record with the SAH kd-tree's, bit for bit "
       "(a tie is another triangle at the same t, within 16 ulps: two triangles meeting the ray at one point).</p>\n";
  for (const AccelComparison& c : scenes) {
    f << "<h2>" << Escape(c.scene) << "</h2>\n<p>" << c.triangles << " triangles, " << c.width << "x" << c.height
      << " primary rays</p>\n<table><tr>";
    for (const std::string& h : kColumns) f << "<th>" << Escape(h) << "</th>";
    f << "</tr>\n";
    for (const AccelRow& r : c.rows) {
      f << "<tr" << (r.time_ratio == 1.0 ? " class=\"best\"" : "") << ">";
      for (const std::string& cell : Cells(c, r)) {
        f << "<td" << (cell.find("DIFFER") != std::string::npos ? " class=\"bad\"" : "") << ">" << Escape(cell)
          << "</td>";
      }
      f << "</tr>\n";
    }
    f << "</table>\n";
    for (const AccelRow& r : c.rows) {
      if (!r.error.empty()) f << "<p class=\"bad\">" << AccelKindName(r.kind) << " not built: " << Escape(r.error) << "</p>\n";
    }
    // Bars: Mrays/s, scaled to the fastest structure of the scene.
    double top = 0;
    for (const AccelRow& r : c.rows) top = std::max(top, r.Mrays());
    const int bar_h = 18, label_w = 80, plot_w = 400;
    f << "<svg width=\"" << label_w + plot_w + 80 << "\" height=\"" << bar_h * c.rows.size() + 4
      << "\" xmlns=\"http://www.w3.org/2000/svg\" font-size=\"12\">\n";
    for (size_t i = 0; i < c.rows.size(); ++i) {
      const AccelRow& r = c.rows[i];
      const double w = top > 0 ? plot_w * r.Mrays() / top : 0;
      const int y = static_cast<int>(i) * bar_h;
      f << "<text x=\"0\" y=\"" << y + 13 << "\">" << AccelKindName(r.kind) << "</text><rect x=\"" << label_w
        << "\" y=\"" << y + 2 << "\" width=\"" << Format("%.1f", w) << "\" height=\"" << bar_h - 4 << "\" fill=\""
        << (IsKdTree(r.kind) ? "#4a7ebb" : "#d08c3a") << "\"/><text x=\"" << label_w + w + 4 << "\" y=\"" << y + 13
        << "\">" << Format("%.2f", r.Mrays()) << " Mrays/s</text>\n";
    }
    f << "</svg>\n";
  }
  f << "</body></html>\n";
  if (!f) throw InputError(path, 0, "write failed");
}

}  // namespace kdrt
