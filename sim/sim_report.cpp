#include "sim/sim_report.h"

#include <algorithm>
#include <cstdio>
#include <string_view>

namespace kdrt::sim {
namespace {

constexpr int kTravBusy = PerfBit("trav_busy"), kListBusy = PerfBit("list_busy"), kIsectBusy = PerfBit("isect_busy");
constexpr int kNodeHit = PerfBit("node_hit"), kNodeMiss = PerfBit("node_miss"), kListHit = PerfBit("list_hit");
constexpr int kListMiss = PerfBit("list_miss"), kTriHit = PerfBit("tri_hit"), kTriMiss = PerfBit("tri_miss");
constexpr int kStallMem = PerfBit("stall_mem"), kStallStack = PerfBit("stall_stack");
constexpr int kStallBackpressure = PerfBit("stall_backpressure");
constexpr int kBusy = PerfBit("busy"), kTravStall = PerfBit("trav_stall"), kIsectStall = PerfBit("isect_stall");
constexpr int kHitStall = PerfBit("hit_stall");

double Ratio(double a, double b) { return b > 0 ? a / b : 0.0; }

// One cache's waits as fractions of all cycles: a request offered and not
// taken, and of those the misses waiting on a line being fetched (its miss
// register full or answering) and on a free miss register; the rest are hits
// waiting for the response register. Merges are counts.
nlohmann::json CacheWaits(const std::array<uint64_t, kPerfBits>& p, const std::string& cache, double cycles) {
  auto at = [&](const std::string& field) { return static_cast<double>(p[PerfBit(field)]); };
  return {{"wait", Ratio(at(cache + "_wait"), cycles)},
          {"wait_in_flight", Ratio(at(cache + "_wait_inflight"), cycles)},
          {"wait_no_mshr", Ratio(at(cache + "_wait_mshr"), cycles)},
          {"merged_misses", p[PerfBit(cache + "_merge")]}};
}

// The list cache's, and the list lines its prefetch port fetched ahead of
// their jobs (rt_list_unit ListPrefetch; 0 without the prefetcher).
nlohmann::json ListWaits(const std::array<uint64_t, kPerfBits>& p, double cycles) {
  nlohmann::json j = CacheWaits(p, "list", cycles);
  j["prefetched_lines"] = p[PerfBit("list_prefetch")];
  return j;
}

// The share of thread-cycles in each state.
nlohmann::json ThreadStates(const HarnessResult& r) {
  double total = 0;
  for (uint64_t n : r.thread_states) total += static_cast<double>(n);
  nlohmann::json j;
  for (int s = 0; s < 8; ++s) j[kThreadStateNames[s]] = Ratio(static_cast<double>(r.thread_states[s]), total);
  return j;
}

}  // namespace

nlohmann::json ReportJson(const ReportInputs& in) {
  const HarnessResult& r = in.run->result;
  const double cycles = static_cast<double>(r.cycles);
  const double rays = static_cast<double>(in.rays);
  const auto& p = r.perf;
  nlohmann::json perf;
  for (int b = 0; b < kPerfBits; ++b) perf[kPerfFields[b].name] = p[b];
  const double nodes = in.reference_totals.nodes, tests = in.reference_totals.tri_tests;
  const double bound_cycles = std::max(nodes, tests);
  return {
      {"command", "sim"},
      {"format", in.config.Format().Name()},
      {"trav_format", in.config.TravFormat().Name()},
      {"image_format", in.config.ImageFormat().Name()},
      {"loop", in.loop},
      {"model", in.config.Json()},
      {"requirements", in.requirements.Json()},
      {"memory",
       {{"size_bytes", in.memory.size_bytes},
        {"latency", in.memory.latency},
        {"bytes_per_cycle", in.memory.bytes_per_cycle},
        {"bytes_per_cycle_effective", PortBytesPerCycle(in.memory)},
        {"bytes_read", in.run->mem_bytes_read},
        {"requests", in.run->mem_requests},
        {"max_outstanding", in.run->mem_max_outstanding},
        {"bytes_per_ray", Ratio(in.run->mem_bytes_read, rays)},
        {"bytes_per_cycle_used", Ratio(in.run->mem_bytes_read, cycles)}}},
      {"rays", in.rays},
      {"query", in.query == Query::kAny ? "any" : "closest"},
      {"hits", r.hit_count},
      {"overflows", r.overflows},
      {"cycles", r.cycles},
      {"rays_per_cycle", Ratio(rays, cycles)},
      {"cycles_per_ray", Ratio(cycles, rays)},
      {"max_rays_in_flight", r.max_in_flight},
      {"utilisation",
       {{"traversal", Ratio(p[kTravBusy], cycles)},
        {"list", Ratio(p[kListBusy], cycles)},
        {"intersection", Ratio(p[kIsectBusy], cycles)}}},
      {"stalls",
       {{"memory", Ratio(p[kStallMem], cycles)},
        {"stack", Ratio(p[kStallStack], cycles)},
        {"backpressure", Ratio(p[kStallBackpressure], cycles)}}},
      {"waits",
       {{"node", CacheWaits(p, "node", cycles)},
        {"list", ListWaits(p, cycles)},
        {"tri", CacheWaits(p, "tri", cycles)}}},
      // A unit stalls when its input waits on it, starves when rays are in
      // flight and it has nothing to take.
      {"unit_stalls",
       {{"traversal", Ratio(p[kTravStall], cycles)},
        {"intersection", Ratio(p[kIsectStall], cycles)},
        {"hit_out", Ratio(p[kHitStall], cycles)}}},
      {"unit_starve",
       {{"traversal", Ratio(static_cast<double>(p[kBusy]) - p[kTravBusy] - p[kTravStall], cycles)},
        {"intersection", Ratio(static_cast<double>(p[kBusy]) - p[kIsectBusy] - p[kIsectStall], cycles)}}},
      {"busy", Ratio(p[kBusy], cycles)},
      {"thread_states", ThreadStates(r)},
      {"cache_hit_rate",
       {{"node", Ratio(p[kNodeHit], p[kNodeHit] + p[kNodeMiss])},
        {"list", Ratio(p[kListHit], p[kListHit] + p[kListMiss])},
        {"tri", Ratio(p[kTriHit], p[kTriHit] + p[kTriMiss])}}},
      {"perf_counts", perf},
      {"reference_per_ray",
       {{"nodes", Ratio(nodes, rays)},
        {"leaves", Ratio(in.reference_totals.leaves, rays)},
        {"empty_skipped", Ratio(in.reference_totals.empty_skipped, rays)},
        {"tri_tests", Ratio(tests, rays)}}},
      {"bound_cycles_per_ray", Ratio(bound_cycles, rays)},
      {"efficiency", Ratio(bound_cycles, cycles)},
      {"window_bound",
       {{"rays", in.window_rays},
        {"cycles_per_ray", Ratio(in.window_bound_cycles, rays)},
        {"efficiency", Ratio(in.window_bound_cycles, cycles)}}},
      // The memory's own bound: the bytes this run read at the modelled
      // bandwidth. Where it exceeds the core's bound, the memory limits.
      {"memory_bound_cycles_per_ray", Ratio(Ratio(in.run->mem_bytes_read, rays), PortBytesPerCycle(in.memory))},
      {"efficiency_vs_both_bounds",
       Ratio(std::max(bound_cycles, Ratio(in.run->mem_bytes_read, PortBytesPerCycle(in.memory))), cycles)},
      {"sim_seconds", r.wall_seconds},
      {"sim_cycles_per_second", Ratio(cycles, r.wall_seconds)},
      {"sim_rays_per_second", Ratio(rays, r.wall_seconds)},
  };
}

nlohmann::json SystemReportJson(const ReportInputs& in, const SystemOutcome& sys,
                                const std::vector<RayCounters>& per_ray) {
  const double n = static_cast<double>(sys.cores.size());
  // The whole run as one core of N x cycles: shares of core-cycles.
  RunOutcome all;
  all.result.cycles = static_cast<uint64_t>(n) * sys.cycles;
  all.result.wall_seconds = sys.wall_seconds;
  for (const RunOutcome& c : sys.cores) {
    for (int b = 0; b < kPerfBits; ++b) all.result.perf[b] += c.result.perf[b];
    for (size_t k = 0; k < all.result.thread_states.size(); ++k) {
      all.result.thread_states[k] += c.result.thread_states[k];
    }
    // A core done before the last one spends the rest of the run idle: its
    // threads are FREE.
    uint64_t thread_cycles = 0;
    for (uint64_t v : c.result.thread_states) thread_cycles += v;
    if (c.result.cycles > 0) {
      all.result.thread_states[0] += (sys.cycles - c.result.cycles) * (thread_cycles / c.result.cycles);
    }
    all.result.hit_count += c.result.hit_count;
    all.result.overflows += c.result.overflows;
    all.result.max_in_flight += c.result.max_in_flight;
  }
  all.mem_bytes_read = sys.mem_bytes_read;
  all.mem_requests = sys.mem_requests;
  all.mem_max_outstanding = sys.mem_max_outstanding;
  ReportInputs whole = in;
  whole.run = &all;
  nlohmann::json j = ReportJson(whole);

  const double cycles = static_cast<double>(sys.cycles), rays = static_cast<double>(in.rays);
  const double bound = j["bound_cycles_per_ray"].get<double>() / n;
  const double mem_bound = Ratio(Ratio(sys.mem_bytes_read, rays), PortBytesPerCycle(in.memory));
  j["cycles"] = sys.cycles;
  j["core_cycles"] = all.result.cycles;
  j["rays_per_cycle"] = Ratio(rays, cycles);
  j["cycles_per_ray"] = Ratio(cycles, rays);
  j["bound_cycles_per_ray"] = bound;
  j["efficiency"] = Ratio(bound, Ratio(cycles, rays));
  // The N cores' units take the windows' work together.
  const double window_bound = Ratio(in.window_bound_cycles, n * rays);
  j["window_bound"]["cycles_per_ray"] = window_bound;
  j["window_bound"]["efficiency"] = Ratio(window_bound, Ratio(cycles, rays));
  j["memory"]["bytes_per_cycle_used"] = Ratio(sys.mem_bytes_read, cycles);
  j["memory_bound_cycles_per_ray"] = mem_bound;
  j["efficiency_vs_both_bounds"] = Ratio(std::max(bound, mem_bound), Ratio(cycles, rays));
  j["sim_cycles_per_second"] = Ratio(cycles, sys.wall_seconds);
  j["cores"] = sys.cores.size();

  nlohmann::json cores = nlohmann::json::array();
  for (const RunOutcome& c : sys.cores) {
    ReportInputs one = in;
    RunOutcome co = c;
    co.mem_bytes_read = kBeatBytes * c.result.mem_requests;  // what the core read from the L2
    co.mem_requests = c.result.mem_requests;
    one.run = &co;
    one.rays = c.result.ray_ids.size();
    one.reference_totals = RayCounters{};
    for (uint32_t id : c.result.ray_ids) one.reference_totals += per_ray[id];
    const nlohmann::json cj = ReportJson(one);
    cores.push_back({{"rays", cj["rays"]},
                     {"cycles", cj["cycles"]},
                     {"cycles_per_ray", cj["cycles_per_ray"]},
                     {"bound_cycles_per_ray", cj["bound_cycles_per_ray"]},
                     {"efficiency", cj["efficiency"]},
                     {"l2_bytes_per_ray", cj["memory"]["bytes_per_ray"]},
                     {"utilisation", cj["utilisation"]},
                     {"cache_hit_rate", cj["cache_hit_rate"]},
                     {"stalls", cj["stalls"]}});
  }
  j["per_core"] = cores;
  j["l2"] = {{"size_bytes", sys.l2_config.size_bytes},
             {"ways", sys.l2_config.ways},
             {"line_bytes", sys.l2_config.line_bytes},
             {"latency", sys.l2_config.latency},
             {"requests", sys.l2.requests},
             {"hits", sys.l2.hits},
             {"merged_misses", sys.l2.merged},
             {"line_fills", sys.l2.line_fills},
             {"hit_rate", Ratio(sys.l2.hits, sys.l2.requests)},
             {"bytes_per_ray", Ratio(kBeatBytes * sys.l2.requests, rays)}};
  return j;
}

double WindowBoundCycles(const std::vector<RayCounters>& per_ray, const std::vector<uint32_t>* order,
                         uint64_t window) {
  if (window == 0) return 0;
  // An empty order is the rays' own (IssueOrder's "linear").
  const bool reorder = order != nullptr && !order->empty();
  double total = 0, nodes = 0, tests = 0;
  uint64_t in_window = 0;
  for (size_t i = 0; i < per_ray.size(); ++i) {
    const RayCounters& c = per_ray[reorder ? (*order)[i] : i];
    nodes += c.nodes;
    tests += c.tri_tests;
    if (++in_window == window || i + 1 == per_ray.size()) {
      total += std::max(nodes, tests);
      nodes = tests = 0;
      in_window = 0;
    }
  }
  return total;
}

void SetWindowBound(const std::vector<RayCounters>& per_ray, const std::vector<uint32_t>* order, int threads,
                    int cores, ReportInputs* in) {
  in->window_rays = static_cast<uint64_t>(threads) * static_cast<uint64_t>(std::max(1, cores));
  in->window_bound_cycles = WindowBoundCycles(per_ray, order, in->window_rays);
}

void AddScene(const SceneFacts& f, nlohmann::json* report) {
  nlohmann::json& j = *report;
  j["scene"] = f.scene;
  j["width"] = f.width;
  j["height"] = f.height;
  j["triangles"] = f.triangles;
  j["tree"] = {{"nodes", f.tree_nodes}, {"max_depth", f.tree_depth}};
}

void PrintReport(const nlohmann::json& j, std::FILE* out) {
  auto d = [&](const nlohmann::json& v) { return v.get<double>(); };
  auto u = [&](const nlohmann::json& v) { return static_cast<unsigned long long>(v.get<uint64_t>()); };
  const auto& m = j["model"];
  const auto& q = j["requirements"];
  std::fprintf(out, "model          %s (%s loop)\n", m["key"].get<std::string>().c_str(),
               j["loop"].get<std::string>().c_str());
  std::fprintf(out, "scene needs    stack %d, node index %d bits, triangle index %d bits, address %d bits\n",
               q["stack_depth"].get<int>(), q["node_idx_bits"].get<int>(), q["tri_idx_bits"].get<int>(),
               q["addr_bits"].get<int>());
  std::fprintf(out, "footprint      nodes %llu B, lists %llu B, triangles %llu B (image %llu B)\n",
               u(q["node_bytes"]), u(q["list_bytes"]), u(q["tri_bytes"]), u(q["image_bytes"]));
  const auto& mem = j["memory"];
  const double bw = d(mem["bytes_per_cycle"]), bw_run = mem.value("bytes_per_cycle_effective", bw);
  std::fprintf(out, "memory         %llu B, latency %llu cycles, %.3g B/cycle%s\n", u(mem["size_bytes"]),
               u(mem["latency"]), bw, bw_run < bw ? " (runs at 16: one beat a cycle)" : "");
  const bool any_hit = j.value("query", "closest") == "any";
  const std::string order = j.value("ray_order", "linear");
  std::fprintf(out, "rays           %llu (%dx%d%s%s), %llu hits, %llu stack overflows\n", u(j["rays"]),
               j["width"].get<int>(), j["height"].get<int>(), any_hit ? ", any-hit queries" : "",
               order == "linear" ? "" : (", issued in " + order + " order").c_str(), u(j["hits"]),
               u(j["overflows"]));
  std::fprintf(out, "cycles         %llu\n", u(j["cycles"]));
  std::fprintf(out, "rays per cycle %.4f\n", d(j["rays_per_cycle"]));
  std::fprintf(out, "cycles per ray %.2f (bound %.2f: max(nodes, tests) per ray, efficiency %.1f %%)\n",
               d(j["cycles_per_ray"]), d(j["bound_cycles_per_ray"]), 100 * d(j["efficiency"]));
  const auto& wb = j["window_bound"];
  if (wb["rays"].get<uint64_t>() > 0) {
    std::fprintf(out, "window bound   %.2f cycles per ray (the bound taken %llu rays at a time in issue order, the rays"
                 " in flight: an estimate; efficiency %.1f %%)\n",
                 d(wb["cycles_per_ray"]), u(wb["rays"]), 100 * d(wb["efficiency"]));
  }
  std::fprintf(out, "memory bound   %.2f cycles per ray (bytes per ray / bytes per cycle; efficiency %.1f %% against the"
               " larger bound)\n",
               d(j["memory_bound_cycles_per_ray"]), 100 * d(j["efficiency_vs_both_bounds"]));
  const auto& ut = j["utilisation"];
  std::fprintf(out, "utilisation    traversal %.1f %%, list %.1f %%, intersection %.1f %%\n",
               100 * d(ut["traversal"]), 100 * d(ut["list"]), 100 * d(ut["intersection"]));
  const auto& st = j["stalls"];
  std::fprintf(out, "stalls         memory %.1f %%, stack %.1f %%, backpressure %.1f %% of cycles\n",
               100 * d(st["memory"]), 100 * d(st["stack"]), 100 * d(st["backpressure"]));
  const auto& w = j["waits"];
  std::fprintf(out, "cache waits    node %.1f %%, list %.1f %%, triangle %.1f %% of cycles"
               " (on a line in flight %.1f/%.1f/%.1f %%, no miss register %.1f/%.1f/%.1f %%)\n",
               100 * d(w["node"]["wait"]), 100 * d(w["list"]["wait"]), 100 * d(w["tri"]["wait"]),
               100 * d(w["node"]["wait_in_flight"]), 100 * d(w["list"]["wait_in_flight"]),
               100 * d(w["tri"]["wait_in_flight"]), 100 * d(w["node"]["wait_no_mshr"]),
               100 * d(w["list"]["wait_no_mshr"]), 100 * d(w["tri"]["wait_no_mshr"]));
  std::fprintf(out, "merged misses  node %llu, list %llu, triangle %llu", u(w["node"]["merged_misses"]),
               u(w["list"]["merged_misses"]), u(w["tri"]["merged_misses"]));
  if (w["list"].contains("prefetched_lines") && u(w["list"]["prefetched_lines"]) > 0) {
    std::fprintf(out, "; list lines prefetched %llu", u(w["list"]["prefetched_lines"]));
  }
  std::fprintf(out, "\n");
  const auto& us = j["unit_stalls"];
  const auto& uv = j["unit_starve"];
  std::fprintf(out, "units          traversal stalled %.1f %%, starved %.1f %%; intersection stalled %.1f %%,"
               " starved %.1f %%; hit out stalled %.1f %%\n",
               100 * d(us["traversal"]), 100 * d(uv["traversal"]), 100 * d(us["intersection"]),
               100 * d(uv["intersection"]), 100 * d(us["hit_out"]));
  const auto& ts = j["thread_states"];
  std::fprintf(out, "thread states ");
  for (const char* name : kThreadStateNames) std::fprintf(out, " %s %.1f %%", name, 100 * d(ts[name]));
  std::fprintf(out, "\n");
  const auto& ch = j["cache_hit_rate"];
  std::fprintf(out, "cache hits     node %.1f %%, list %.1f %%, triangle %.1f %%\n", 100 * d(ch["node"]),
               100 * d(ch["list"]), 100 * d(ch["tri"]));
  std::fprintf(out, "memory traffic %.1f B/ray, %.2f B/cycle, %llu reads, max %llu outstanding\n",
               d(mem["bytes_per_ray"]), d(mem["bytes_per_cycle_used"]), u(mem["requests"]),
               u(mem["max_outstanding"]));
  const auto& rp = j["reference_per_ray"];
  std::fprintf(out, "reference/ray  %.2f nodes, %.2f leaves (and %.2f empty ones, not fetched), %.2f triangle tests\n",
               d(rp["nodes"]), d(rp["leaves"]), d(rp["empty_skipped"]), d(rp["tri_tests"]));
  std::fprintf(out, "sim speed      %.3f s, %.0f cycles/s, %.0f rays/s%s\n", d(j["sim_seconds"]),
               d(j["sim_cycles_per_second"]), d(j["sim_rays_per_second"]),
               j.value("model_build", "") == "quick" ? " (a quick build, one unit at -O1 without waveforms: KDRT_QUICK_MODELS)" : "");
}

nlohmann::json FrameTotals(const nlohmann::json& passes) {
  uint64_t rays = 0, cycles = 0, bytes = 0;
  double bound = 0;
  for (const auto& p : passes) {
    if (p["stats"].is_null()) continue;
    const auto& s = p["stats"];
    rays += s["rays"].get<uint64_t>();
    cycles += s["cycles"].get<uint64_t>();
    bytes += s["memory"]["bytes_read"].get<uint64_t>();
    bound += s["bound_cycles_per_ray"].get<double>() * s["rays"].get<double>();
  }
  return {{"rays", rays},
          {"cycles", cycles},
          {"cycles_per_ray", Ratio(cycles, rays)},
          {"bound_cycles_per_ray", Ratio(bound, rays)},
          {"efficiency", Ratio(bound, cycles)},
          {"bytes_per_ray", Ratio(bytes, rays)}};
}

void PrintCores(const nlohmann::json& j, std::FILE* out) {
  if (!j.contains("per_core")) return;
  const auto d = [](const nlohmann::json& v) { return v.get<double>(); };
  const auto u = [](const nlohmann::json& v) { return static_cast<unsigned long long>(v.get<uint64_t>()); };
  std::fprintf(out, "cores          %llu sharing the L2; cycles, rays per cycle and bound above are the system's\n",
               u(j["cores"]));
  int k = 0;
  for (const auto& c : j["per_core"]) {
    std::fprintf(out, "  core %-3d     %llu rays, done at cycle %llu, %.2f cycles per ray (bound %.2f, %.1f %%), "
                 "%.1f L2 B/ray, node cache %.1f %%\n",
                 k++, u(c["rays"]), u(c["cycles"]), d(c["cycles_per_ray"]), d(c["bound_cycles_per_ray"]),
                 100 * d(c["efficiency"]), d(c["l2_bytes_per_ray"]), 100 * d(c["cache_hit_rate"]["node"]));
  }
  const auto& l2 = j["l2"];
  std::fprintf(out, "L2             %llu KiB, %llu ways, %llu-byte lines, latency %llu: %llu reads, %.1f %% hits, "
               "%llu merged misses, %llu line fills, %.1f B/ray\n",
               u(l2["size_bytes"]) / 1024, u(l2["ways"]), u(l2["line_bytes"]), u(l2["latency"]), u(l2["requests"]),
               100 * d(l2["hit_rate"]), u(l2["merged_misses"]), u(l2["line_fills"]), d(l2["bytes_per_ray"]));
}

void PrintPasses(const nlohmann::json& passes, const nlohmann::json& totals, std::FILE* out) {
  const auto d = [](const nlohmann::json& v) { return v.get<double>(); };
  const auto u = [](const nlohmann::json& v) { return static_cast<unsigned long long>(v.get<uint64_t>()); };
  std::fprintf(out, "pass       query     rays     hits      cycles  cyc/ray  bound  effic.  B/ray  "
               "node/tri cache hits\n");
  for (const auto& p : passes) {
    const std::string name = p["name"], query = p["query"];
    if (p["stats"].is_null()) {
      std::fprintf(out, "%-10s %-8s %5d\n", name.c_str(), query.c_str(), 0);
      continue;
    }
    const auto& s = p["stats"];
    std::fprintf(out, "%-10s %-8s %7llu %8llu %11llu %8.2f %6.2f %6.1f%% %6.1f  %5.1f/%5.1f %%\n", name.c_str(),
                 query.c_str(), u(s["rays"]), u(s["hits"]), u(s["cycles"]), d(s["cycles_per_ray"]),
                 d(s["bound_cycles_per_ray"]), 100 * d(s["efficiency"]), d(s["memory"]["bytes_per_ray"]),
                 100 * d(s["cache_hit_rate"]["node"]), 100 * d(s["cache_hit_rate"]["tri"]));
  }
  std::fprintf(out, "%-10s %-8s %7llu %8s %11llu %8.2f %6.2f %6.1f%% %6.1f\n", "frame", "", u(totals["rays"]), "",
               u(totals["cycles"]), d(totals["cycles_per_ray"]), d(totals["bound_cycles_per_ray"]),
               100 * d(totals["efficiency"]), d(totals["bytes_per_ray"]));
}

}  // namespace kdrt::sim
