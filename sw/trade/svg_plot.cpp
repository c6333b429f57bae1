#include "trade/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace kdrt::trade {
namespace {

constexpr double kLeft = 78, kRight = 24, kTop = 36, kBottom = 52;

std::string Escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

std::string TickText(double v) {
  char buf[32];
  const double a = std::fabs(v);
  if (a != 0 && (a < 1e-3 || a >= 1e7)) {
    std::snprintf(buf, sizeof buf, "%.0e", v);
  } else if (a >= 1e4) {
    std::snprintf(buf, sizeof buf, "%gk", v / 1000);  // cells: 250k reads better than 250000
  } else {
    std::snprintf(buf, sizeof buf, "%g", v);
  }
  return buf;
}

// One axis: data value -> [0,1] and its ticks.
struct Axis {
  bool log = false;
  double lo = 0, hi = 1;  // in data units (log10 units on a log axis)
  double floor_value = 0; // log axis: where values <= 0 are drawn (log10 units)
  bool has_zero = false;
  std::vector<std::pair<double, std::string>> ticks;  // position in axis units, text

  double Map(double v) const {
    const double a = log ? (v > 0 ? std::log10(v) : floor_value) : v;
    return (a - lo) / (hi - lo);
  }
};

Axis MakeAxis(std::vector<double> values, bool log, const std::string& zero_label) {
  Axis ax;
  ax.log = log;
  if (log) {
    double min_pos = HUGE_VAL, max_pos = 0;
    for (double v : values) {
      if (v > 0) {
        min_pos = std::min(min_pos, v);
        max_pos = std::max(max_pos, v);
      } else {
        ax.has_zero = true;
      }
    }
    if (max_pos == 0) min_pos = max_pos = 1;
    double lo = std::floor(std::log10(min_pos)), hi = std::ceil(std::log10(max_pos));
    if (hi <= lo) hi = lo + 1;
    if (ax.has_zero) {
      ax.floor_value = lo - 1;
      lo -= 1;
      ax.ticks.push_back({ax.floor_value, zero_label});
    }
    ax.lo = lo - 0.15;
    ax.hi = hi + 0.15;
    const int step = static_cast<int>(std::max(1.0, std::ceil((hi - lo) / 7)));
    for (int d = static_cast<int>(ax.has_zero ? lo + 1 : lo); d <= hi; d += step) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "1e%d", d);
      ax.ticks.push_back({static_cast<double>(d), d >= 0 && d <= 4 ? TickText(std::pow(10.0, d)) : buf});
    }
    return ax;
  }
  double lo = *std::min_element(values.begin(), values.end());
  double hi = *std::max_element(values.begin(), values.end());
  lo = std::min(lo, 0.0);  // costs read best from zero
  if (hi <= lo) hi = lo + 1;
  const double raw = (hi - lo) / 5;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double step = raw / mag < 1.5 ? mag : raw / mag < 3.5 ? 2 * mag : raw / mag < 7.5 ? 5 * mag : 10 * mag;
  ax.lo = std::floor(lo / step) * step;
  ax.hi = std::ceil(hi * 1.08 / step) * step;
  for (double v = ax.lo; v <= ax.hi + step / 2; v += step) ax.ticks.push_back({v, TickText(v)});
  return ax;
}

}  // namespace

std::string ScatterSvg(const PlotSpec& spec, int width, int height) {
  std::vector<double> xs, ys;
  for (const PlotPoint& p : spec.points) {
    xs.push_back(p.x);
    ys.push_back(p.y);
  }
  if (xs.empty()) {
    xs.push_back(0);
    ys.push_back(0);
  }
  const Axis ax = MakeAxis(xs, spec.log_x, spec.zero_label), ay = MakeAxis(ys, spec.log_y, spec.zero_label);
  const double pw = width - kLeft - kRight, ph = height - kTop - kBottom;
  auto px = [&](double v) { return kLeft + ax.Map(v) * pw; };
  auto py = [&](double v) { return kTop + (1 - ay.Map(v)) * ph; };
  auto axis_pos_x = [&](double a) { return kLeft + (a - ax.lo) / (ax.hi - ax.lo) * pw; };
  auto axis_pos_y = [&](double a) { return kTop + (1 - (a - ay.lo) / (ay.hi - ay.lo)) * ph; };

  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
    << "\" viewBox=\"0 0 " << width << ' ' << height << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  s << "<rect class=\"plot-bg\" x=\"0\" y=\"0\" width=\"" << width << "\" height=\"" << height
    << "\" fill=\"#f4f8fc\"/>\n";
  s << "<text x=\"" << width / 2 << "\" y=\"20\" text-anchor=\"middle\" font-size=\"14\" font-weight=\"bold\">"
    << Escape(spec.title) << "</text>\n";
  s << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << pw << "\" height=\"" << ph
    << "\" fill=\"#ffffff\" stroke=\"#444\"/>\n";
  for (const auto& [a, text] : ax.ticks) {
    const double x = axis_pos_x(a);
    s << "<line x1=\"" << Num(x) << "\" y1=\"" << kTop << "\" x2=\"" << Num(x) << "\" y2=\"" << kTop + ph
      << "\" stroke=\"#ddd\"/><text x=\"" << Num(x) << "\" y=\"" << kTop + ph + 16
      << "\" text-anchor=\"middle\">" << Escape(text) << "</text>\n";
  }
  for (const auto& [a, text] : ay.ticks) {
    const double y = axis_pos_y(a);
    s << "<line x1=\"" << kLeft << "\" y1=\"" << Num(y) << "\" x2=\"" << kLeft + pw << "\" y2=\"" << Num(y)
      << "\" stroke=\"#ddd\"/><text x=\"" << kLeft - 6 << "\" y=\"" << Num(y + 4) << "\" text-anchor=\"end\">"
      << Escape(text) << "</text>\n";
  }
  s << "<text x=\"" << Num(kLeft + pw / 2) << "\" y=\"" << height - 12 << "\" text-anchor=\"middle\">"
    << Escape(spec.x_title) << "</text>\n";
  s << "<text transform=\"translate(16," << Num(kTop + ph / 2) << ") rotate(-90)\" text-anchor=\"middle\">"
    << Escape(spec.y_title) << "</text>\n";
  for (const PlotPoint& p : spec.points) {
    const double x = px(p.x), y = py(p.y);
    s << "<circle class=\"point\" cx=\"" << Num(x) << "\" cy=\"" << Num(y)
      << "\" r=\"6\" fill=\"#d62728\" stroke=\"#000\" stroke-width=\"0.5\"><title>" << Escape(p.label)
      << "</title></circle><text x=\"" << Num(x + 9) << "\" y=\"" << Num(y - 7) << "\">" << Escape(p.label)
      << "</text>\n";
  }
  s << "</svg>\n";
  return s.str();
}

}  // namespace kdrt::trade
