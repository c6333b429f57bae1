// The outputs of `kdrt trade`: the table on stdout, JSON, CSV and the HTML
// page (DIR/index.html with its images and SVG plots beside it).
#pragma once

#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "scene/scene.h"
#include "trade/trade.h"

namespace kdrt::trade {

void PrintTable(const TradeResult& t, FILE* out);
nlohmann::json TradeJson(const TradeResult& t);
// One row per format, a header first; empty cells where a column was not
// measured (no --sim, --no-area).
std::string TradeCsv(const TradeResult& t);
// Writes index.html, the images (one per format and fp64, a difference image
// per format) and the plots into `dir` (an existing, empty directory).
void WriteHtml(const TradeResult& t, const std::string& dir);

}  // namespace kdrt::trade
