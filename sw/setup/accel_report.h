// The reports of `kdrt compare-accel`: the human table (stdout, README) and
// the HTML page (a table and a bar chart per scene).
#pragma once

#include <string>
#include <vector>

#include "setup/accel_compare.h"

namespace kdrt {

// One block per scene, one row per structure (Havran's columns), the fastest
// marked; markdown when `markdown` (for docs), else aligned text.
std::string AccelTable(const std::vector<AccelComparison>& scenes, bool markdown);

// Writes dir/index.html.
void WriteAccelHtml(const std::vector<AccelComparison>& scenes, const std::string& dir);

}  // namespace kdrt
