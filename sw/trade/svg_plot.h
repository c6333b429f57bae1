// A labelled scatter plot written as SVG: what the `kdrt trade` page shows
// (error versus area, cycles versus area). Small on purpose: points with a
// label each, linear or log-10 axes with ticks, axis titles.
#pragma once

#include <string>
#include <vector>

namespace kdrt::trade {

struct PlotPoint {
  double x = 0, y = 0;
  std::string label;
};

struct PlotSpec {
  std::string title, x_title, y_title;
  bool log_x = false, log_y = false;
  // On a log axis, values <= 0 cannot be drawn: they sit on the axis floor
  // (a decade below the smallest positive value) and the tick there reads
  // `zero_label`.
  std::string zero_label = "0";
  std::vector<PlotPoint> points;
};

// A complete SVG document (width x height pixels).
std::string ScatterSvg(const PlotSpec& spec, int width = 520, int height = 340);

}  // namespace kdrt::trade
