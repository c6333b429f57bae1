#include "sim/core_harness.h"

#include <unistd.h>

#include <cinttypes>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <type_traits>

#include "Vrt_core.h"
#include "Vrt_core___024root.h"
#include "Vrt_core_rt_core.h"
#include "fp/format.h"
#include "sim/sim_ctrl.h"
#include "trace/frame.h"
#include "trace/hit_compare.h"

namespace kdrt::sim {
namespace {

// Thread t's 3-bit state from rt_core's thread_state_o, whatever type
// Verilator gave the port (an integer up to 64 bits, else words).
template <class T>
unsigned ThreadState(const T& v, int t) {
  if constexpr (std::is_integral_v<T>) {
    return static_cast<unsigned>((static_cast<uint64_t>(v) >> (3 * t)) & 7u);
  } else {
    unsigned s = 0;
    for (int k = 0; k < 3; ++k) {
      const int b = 3 * t + k;
      s |= ((v.data()[b / 32] >> (b % 32)) & 1u) << k;
    }
    return s;
  }
}

void SetWide(uint32_t* words, int count, const uint32_t* values) {
  for (int i = 0; i < count; ++i) words[i] = values[i];
}

}  // namespace

CoreHarness::CoreHarness(Vrt_core& top, const ImageView& image, const std::vector<Ray>& rays,
                         const std::vector<Hit>& reference, MemoryPort& memory, const HarnessOptions& options,
                         RayQueue* queue, int core)
    : top_(top), image_(image), rays_(rays), reference_(reference), memory_(memory), options_(options),
      own_queue_(queue ? nullptr : std::make_unique<RayQueue>(rays.size(), 1, rays.size(), options.order)),
      queue_(queue ? queue : own_queue_.get()), core_(core) {
  result_.hits.assign(rays.size(), Hit{});
  result_.overflow.assign(rays.size(), 0);
  received_flag_.assign(rays.size(), 0);
  sent_flag_.assign(rays.size(), 0);
  dump_wanted_ = options_.trace_ray < 0;
  start_ = last_progress_ = std::chrono::steady_clock::now();
}

void CoreHarness::Configure() {
  const img::Header& h = image_.header();
  top_.node_base_i = h.node_offset;
  top_.list_base_i = h.list_offset;
  top_.tri_base_i = h.tri_offset;
  uint32_t lo[3], hi[3];
  for (int i = 0; i < 3; ++i) {
    lo[i] = fp::BitsOf(h.bounds_min[i]);
    hi[i] = fp::BitsOf(h.bounds_max[i]);
  }
  SetWide(top_.bounds_min_i.data(), 3, lo);
  SetWide(top_.bounds_max_i.data(), 3, hi);
  // The frame (docs/dataflow.md step 0). ImageView refuses |s| > 160, so s
  // fits the port's kdrt_pkg::FrameScaleWidth = 9 bits (two's complement).
  uint32_t origin[3];
  for (int i = 0; i < 3; ++i) origin[i] = fp::BitsOf(h.frame_origin[i]);
  SetWide(top_.frame_origin_i.data(), 3, origin);
  static_assert(kMaxFrameScaleLog2 <= 255, "the frame scale must fit rt_core's 9-bit frame_scale_i");
  top_.frame_scale_i = static_cast<uint32_t>(h.frame_scale_log2) & 0x1FFu;
  top_.ray_valid_i = 0;
  top_.ray_any_i = 0;
  top_.hit_ready_i = 1;
  top_.mem_req_ready_i = 1;
  top_.mem_resp_valid_i = 0;
}

std::array<uint32_t, 19> CoreHarness::DrivenInputs() const {
  std::array<uint32_t, 19> w{};
  for (int i = 0; i < 8; ++i) w[i] = top_.ray_i[i];
  for (int i = 0; i < 4; ++i) w[8 + i] = top_.mem_resp_data_i[i];
  w[12] = top_.ray_valid_i;
  w[13] = top_.ray_any_i;
  w[14] = top_.ray_id_i;
  w[15] = top_.mem_resp_valid_i;
  w[16] = top_.mem_resp_tag_i;
  w[17] = top_.hit_ready_i;
  w[18] = top_.mem_req_ready_i;
  return w;
}

bool CoreHarness::BeginCycle(uint64_t cycle) {
  const std::array<uint32_t, 19> before = DrivenInputs();
  if (!has_pending_) has_pending_ = queue_->Take(core_, &pending_ray_);
  if (has_pending_) {
    const Ray& r = rays_[pending_ray_];
    const uint32_t words[8] = {fp::BitsOf(r.o.x), fp::BitsOf(r.o.y), fp::BitsOf(r.o.z), fp::BitsOf(r.d.x),
                               fp::BitsOf(r.d.y), fp::BitsOf(r.d.z), fp::BitsOf(r.tmin), fp::BitsOf(r.tmax)};
    SetWide(top_.ray_i.data(), 8, words);
    top_.ray_id_i = static_cast<uint32_t>(pending_ray_);
    top_.ray_any_i = options_.reference.query == Query::kAny;
    top_.ray_valid_i = 1;
    if (options_.trace_ray >= 0 && static_cast<int64_t>(pending_ray_) == options_.trace_ray) dump_wanted_ = true;
  } else {
    top_.ray_valid_i = 0;
  }
  MemoryResponse resp;
  if (memory_.Respond(cycle, &resp)) {
    uint32_t words[4];
    std::memcpy(words, resp.data, sizeof words);  // little-endian host: byte k in [8k+7:8k]
    SetWide(top_.mem_resp_data_i.data(), 4, words);
    top_.mem_resp_tag_i = resp.tag;
    top_.mem_resp_valid_i = 1;
  } else {
    top_.mem_resp_valid_i = 0;
  }
  top_.hit_ready_i = 1;
  top_.mem_req_ready_i = 1;
  return DrivenInputs() != before;
}

void CoreHarness::EndCycle(uint64_t cycle) {
  const uint64_t perf = top_.perf_o;
  for (int b = 0; b < kPerfBits; ++b) result_.perf[b] += (perf >> b) & 1u;
  for (int t = 0; t < static_cast<int>(Vrt_core_rt_core::Threads); ++t) {
    ++result_.thread_states[ThreadState(top_.thread_state_o, t)];
  }

  if (top_.mem_req_valid_o && top_.mem_req_ready_i) {
    ++result_.mem_requests;
    try {
      memory_.Request(top_.mem_req_addr_o, static_cast<uint16_t>(top_.mem_req_tag_o), cycle);
    } catch (const MemoryError& e) {
      throw SimFailure(std::string("harness error: ") + e.what());
    }
  }
  if (top_.ray_valid_i && top_.ray_ready_o) {
    sent_flag_[pending_ray_] = 1;
    has_pending_ = false;
    ++sent_;
    ++in_flight_;
    if (in_flight_ > result_.max_in_flight) result_.max_in_flight = in_flight_;
  }
  bool trace_ray_done = false;
  if (top_.hit_valid_o && top_.hit_ready_i) {
    const uint32_t id = top_.hit_ray_id_o;
    Hit got;
    got.prim = top_.hit_prim_o;
    got.t = fp::FloatOf(top_.hit_t_o);
    got.u = fp::FloatOf(top_.hit_u_o);
    got.v = fp::FloatOf(top_.hit_v_o);
    const bool hit_flag = top_.hit_o;
    if (id >= rays_.size() || !sent_flag_[id] || received_flag_[id]) {
      throw SimFailure("protocol error at cycle " + std::to_string(cycle) + ": hit record for ray id " +
                       std::to_string(id) +
                       (id >= rays_.size() || !sent_flag_[id] ? ", which was never sent" : ", which already returned"));
    }
    if (hit_flag != got.IsHit()) {
      throw SimFailure("protocol error at cycle " + std::to_string(cycle) + ": ray " + std::to_string(id) +
                       ": hit_o = " + std::to_string(hit_flag) + " but hit_prim_o = " + std::to_string(got.prim));
    }
    CheckHit(cycle, id, got, top_.hit_overflow_o);
    received_flag_[id] = 1;
    result_.ray_ids.push_back(id);
    ++received_;
    queue_->Returned();
    --in_flight_;
    last_hit_cycle_ = cycle;
    trace_ray_done = options_.trace_ray >= 0 && static_cast<int64_t>(id) == options_.trace_ray;
  }
  if (trace_ray_done) dump_wanted_ = false;
  if (cycle - last_hit_cycle_ > options_.timeout) {
    std::ostringstream s;
    s << "timeout: no hit record for " << options_.timeout << " cycles (cycle " << cycle << "); " << sent_ << " of "
      << rays_.size() << " rays sent, " << received_ << " returned, " << memory_.outstanding()
      << " memory reads outstanding; rays in flight:";
    int listed = 0;
    for (size_t i = 0; i < rays_.size() && listed < 16; ++i) {
      if (sent_flag_[i] && !received_flag_[i]) {
        s << " " << i;
        ++listed;
      }
    }
    throw SimFailure(s.str());
  }
  if (options_.progress && (cycle & 0x3FFF) == 0) Progress(cycle, false);
}

void CoreHarness::CheckHit(uint64_t cycle, uint32_t id, const Hit& got, bool overflow) {
  result_.hits[id] = got;
  if (got.IsHit()) ++result_.hit_count;
  if (overflow) {
    // Not a valid answer to the query (the stack was forced smaller than the
    // tree needs), but the reference ends the ray at the same push with the
    // same hit (options_.reference.stack_depth), so it is compared all the
    // same; sim_main checks that both overflowed the same rays.
    result_.overflow[id] = 1;
    ++result_.overflows;
  }
  const Hit& want = reference_[id];
  if (SameBits(got, want)) return;

  const Ray& r = rays_[id];
  std::vector<uint32_t> path;
  RayCounters counters;
  TraceOne(image_, r, options_.reference, &counters, &path);
  std::ostringstream s;
  s << "co-simulation mismatch at cycle " << cycle << " (the first; the run stops here)\n";
  s << "  ray " << id << "\n";
  s << "    origin    " << FloatText(r.o.x) << " " << FloatText(r.o.y) << " " << FloatText(r.o.z) << "\n";
  s << "    direction " << FloatText(r.d.x) << " " << FloatText(r.d.y) << " " << FloatText(r.d.z) << "\n";
  s << "    tmin      " << FloatText(r.tmin) << "\n";
  s << "    tmax      " << FloatText(r.tmax) << "\n";
  s << "  model (" << options_.reference.format.Name() << "): " << HitText(want) << "\n";
  s << "  RTL:   " << HitText(got) << ", overflow " << (overflow ? 1 : 0) << "\n";
  s << "  model node path (" << path.size() << " nodes, " << counters.leaves << " leaves, " << counters.tri_tests
    << " triangle tests):";
  for (uint32_t n : path) {
    s << " " << n << (image_.node(n).IsLeaf() ? "L" : "");
  }
  s << "\n  (L = leaf)";
  throw SimFailure(s.str());
}

void CoreHarness::Progress(uint64_t cycle, bool final_line) {
  const auto now = std::chrono::steady_clock::now();
  if (!final_line && now - last_progress_ < std::chrono::milliseconds(500)) return;
  last_progress_ = now;
  const double secs = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "\rsim: %zu/%zu rays, %" PRIu64 " cycles, %.0f kcycles/s%s", queue_->returned(), rays_.size(), cycle,
               secs > 0 ? cycle / secs * 1e-3 : 0.0, final_line ? "\n" : "");
  std::fflush(stderr);
}

void CoreHarness::Start(SimCtrl<Vrt_core>& ctrl, const std::string& trace_path) {
  Configure();
  if (!trace_path.empty()) ctrl.OpenTrace(trace_path);
  ctrl.EnableDump(dump_wanted_);
  ctrl.Reset();
  start_ = last_progress_ = std::chrono::steady_clock::now();
}

void CoreHarness::Cycle(SimCtrl<Vrt_core>& ctrl) {
  const uint64_t cycle = ctrl.cycle();
  const bool inputs_changed = BeginCycle(cycle);
  ctrl.EnableDump(dump_wanted_);
  // Most cycles offer the same ray and no memory response as the one before:
  // then the rising edge's evaluation has settled the core on these inputs,
  // and a second evaluation (Verilator reruns all logic that depends on an
  // input on every eval()) is skipped; only the clock's fall is recorded, in
  // the member Verilator 5 keeps the clock's last evaluated value in (a
  // Verilator that names it otherwise fails to compile this line).
  if (inputs_changed) {
    ctrl.Settle();
  } else {
    ctrl.SettleUnchanged([](Vrt_core& top) { top.rootp->__Vtrigrprev__TOP__clk_i = 0; });
  }
  const bool dump_this_cycle = dump_wanted_;
  EndCycle(cycle);
  // The cycle in which the traced ray leaves is still dumped.
  ctrl.EnableDump(dump_this_cycle || dump_wanted_);
  ctrl.Tick();
}

RunOutcome CoreHarness::Finish(SimCtrl<Vrt_core>& ctrl, const MemoryModel& memory) {
  ctrl.CloseTrace();
  RunOutcome out;
  out.result = result_;
  out.result.cycles = ctrl.cycle();
  out.result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (options_.progress) Progress(out.result.cycles, true);
  out.mem_bytes_read = memory.bytes_read();
  out.mem_requests = memory.requests();
  out.mem_max_outstanding = memory.max_outstanding();
  return out;
}

CoreConfig CompiledConfig() {
  CoreConfig c;
#define KDRT_CORE_PARAM(name, ...) c[k##name] = static_cast<int>(Vrt_core_rt_core::name);
#include "sim/core_params.def"
#undef KDRT_CORE_PARAM
  return c;
}

bool QuickBuild() {
#ifdef KDRT_SIM_QUICK_BUILD
  return true;
#else
  return false;
#endif
}

RunOutcome RunVerilator(const RunSpec& spec) {
  MemoryModel memory(spec.memory);
  memory.LoadImage(std::vector<uint8_t>(spec.image->data(), spec.image->data() + spec.image->size()));
  SimCtrl<Vrt_core> ctrl;
  CoreHarness harness(ctrl.top(), *spec.image, *spec.rays, *spec.reference, memory, spec.options);
  harness.Start(ctrl, spec.trace_path);
  while (!harness.Done()) harness.Cycle(ctrl);
  return harness.Finish(ctrl, memory);
}

}  // namespace kdrt::sim
