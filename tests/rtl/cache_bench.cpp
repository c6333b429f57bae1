// Verilator bench of rtl/rt_cache.sv against a C++ model of a direct-mapped
// cache: every response carries the right line (checked against memory) and
// tag, in request order; hits and misses match the model exactly. Memory
// answers each beat after a random latency and in random order; the requester
// sends in random bursts and applies random backpressure.
#include <cstdio>
#include <deque>
#include <map>
#include <random>
#include <vector>

#include "Vrt_cache_lines2.h"
#include "Vrt_cache_lines3.h"
#include "tests/rtl/isect_bench_util.h"

namespace kdrt::rtlbench {
namespace {

constexpr int kLines = 8;  // must match the verilated parameters

uint8_t MemByte(uint64_t addr) { return static_cast<uint8_t>((addr * 2654435761u) >> 13); }

struct Request {
  uint32_t key, addr, tag;
};

template <class Dut>
bool Run(const char* name, int beats, uint64_t count) {
  Dut dut;
  std::mt19937 rng(5);
  std::bernoulli_distribution bubble(0.3), stall(0.2);
  std::uniform_int_distribution<int> latency(1, 30);
  // Keys from a small range so that lines are reused and evicted.
  std::uniform_int_distribution<uint32_t> key_dist(0, 3 * kLines);
  std::vector<uint32_t> model_key(kLines, 0);
  std::vector<bool> model_valid(kLines, false);
  std::deque<Request> expected;
  struct Beat {
    uint64_t due;
    uint32_t addr;
    int beat;
  };
  std::vector<Beat> in_flight;
  uint64_t sent = 0, checked = 0, hits = 0, misses = 0, model_hits = 0, model_misses = 0;
  Request pending{};
  bool have_pending = false;

  dut.clk_i = 0;
  dut.rst_ni = 0;
  dut.eval();
  dut.clk_i = 1;
  dut.eval();
  dut.rst_ni = 1;
  for (uint64_t cycle = 0; checked < count; ++cycle) {
    if (cycle > 200 * count + 1000) {
      std::printf("rt_cache %s: FAIL (timeout)\n", name);
      return false;
    }
    dut.clk_i = 0;
    if (!have_pending && sent < count && !bubble(rng)) {
      const uint32_t key = key_dist(rng);
      pending = Request{key, 0x1000u + key * 16u * static_cast<uint32_t>(beats), static_cast<uint32_t>(rng() & 0xFF)};
      have_pending = true;
    }
    dut.req_valid_i = have_pending;
    dut.req_key_i = pending.key;
    dut.req_addr_i = pending.addr;
    dut.req_tag_i = pending.tag;
    dut.resp_ready_i = !stall(rng);
    // Memory: one due beat per cycle, in random order among the due ones.
    dut.mem_resp_valid_i = 0;
    for (size_t i = 0; i < in_flight.size(); ++i) {
      if (in_flight[i].due <= cycle) {
        dut.mem_resp_valid_i = 1;
        dut.mem_resp_beat_i = in_flight[i].beat;
        for (int k = 0; k < 16; ++k) PutBits(dut.mem_resp_data_i, 8 * k, 8, MemByte(in_flight[i].addr + k));
        in_flight.erase(in_flight.begin() + static_cast<long>(i));
        break;
      }
    }
    dut.mem_req_ready_i = !stall(rng);
    dut.eval();
    if (dut.mem_req_valid_o && dut.mem_req_ready_i) {
      in_flight.push_back(Beat{cycle + static_cast<uint64_t>(latency(rng)), dut.mem_req_addr_o, dut.mem_req_beat_o});
    }
    hits += dut.hit_o;
    misses += dut.miss_o;
    if (dut.req_valid_i && dut.req_ready_o) {
      const int idx = static_cast<int>(pending.key % kLines);
      if (model_valid[idx] && model_key[idx] == pending.key) {
        ++model_hits;
      } else {
        ++model_misses;
        model_valid[idx] = true;
        model_key[idx] = pending.key;
      }
      expected.push_back(pending);
      have_pending = false;
      ++sent;
    }
    if (dut.resp_valid_o && dut.resp_ready_i) {
      if (expected.empty()) {
        std::printf("rt_cache %s: FAIL: response without a request\n", name);
        return false;
      }
      const Request& r = expected.front();
      bool ok = dut.resp_tag_o == r.tag;
      for (int k = 0; k < 16 * beats && ok; ++k) ok = GetBits(dut.resp_data_o, 8 * k, 8) == MemByte(r.addr + k);
      if (!ok) {
        std::printf("rt_cache %s: FAIL at response %llu: key %u addr 0x%x tag %u (got tag %u)\n", name,
                    static_cast<unsigned long long>(checked), r.key, r.addr, r.tag, unsigned(dut.resp_tag_o));
        return false;
      }
      expected.pop_front();
      ++checked;
    }
    dut.clk_i = 1;
    dut.eval();
  }
  if (hits != model_hits || misses != model_misses) {
    std::printf("rt_cache %s: FAIL: %llu hits %llu misses, model %llu and %llu\n", name,
                static_cast<unsigned long long>(hits), static_cast<unsigned long long>(misses),
                static_cast<unsigned long long>(model_hits), static_cast<unsigned long long>(model_misses));
    return false;
  }
  std::printf("rt_cache %s: PASS (%llu requests, %llu hits, %llu misses)\n", name,
              static_cast<unsigned long long>(count), static_cast<unsigned long long>(hits),
              static_cast<unsigned long long>(misses));
  return true;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  Verilated::commandArgs(argc, argv);
  const uint64_t count = LongRun() ? 2000000 : 200000;
  bool ok = Run<Vrt_cache_lines2>("2-beat lines", 2, count);
  ok = Run<Vrt_cache_lines3>("3-beat lines", 3, count) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
