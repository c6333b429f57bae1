// Verilator bench of rtl/rt_mem_system.sv (node, list and triangle caches on
// one memory port) against a memory image and the contract of its ports:
//   - every node response carries the tag of an outstanding node request
//     and that request's whole line;
//   - every list request is answered exactly once, on the triangle port,
//     with its tag, the triangle id its entry holds, and that triangle's
//     record: 48 bytes at tri_base + 48 * id, or with two records per line
//     (TriPerLine 2, the fp16 and bf16 images) 24 bytes at
//     tri_base + 48 * (id / 2) + 24 * (id % 2);
//   - per cache, hits + misses == requests taken (the triangle cache's:
//     entries passed on); mem_wait_o is high while a memory request waits;
//   - the memory port names an address in memory, and answers come back
//     with its tag.
// Memory answers every beat after a random latency, in random order, one
// per cycle, and refuses requests at random; node requests come in bursts
// and may change or drop while not taken (the core's arbiter does), list
// requests are held until taken; both responses meet random backpressure.
// Four times: direct-mapped caches, 2-way ones (CacheWays 2),
// direct-mapped with two triangle records per line, and with ListStream 1,
// where a list request names 1 .. 8 entries from its address on within its
// 32-byte line (list_req_count_i), each answered once on the triangle port.
#include <cstdio>
#include <map>
#include <vector>

#include "Vrt_mem_system.h"
#include "Vrt_mem_system_pairs.h"
#include "Vrt_mem_system_stream.h"
#include "Vrt_mem_system_ways2.h"
#include "sim/sim_ctrl.h"
#include "tests/rtl/isect_bench_util.h"

namespace kdrt::rtlbench {
namespace {

using sim::SimCtrl;

// As verilated (tests/rtl/CMakeLists.txt): AddrWidth 20, TagWidth 4,
// TriIdxWidth 8, 4 lines per cache, 2-beat node and list lines, 3 miss
// registers per cache; CacheWays 1 and 2; TriPerLine 1 and 2.
constexpr int kNodeLineBytes = 32;
constexpr uint32_t kTags = 16;
constexpr uint32_t kNodeBase = 0x01000, kNodeBytes = 0x300;   // nodes: lines reused and evicted
constexpr uint32_t kListBase = 0x04000, kListEntries = 96;     // entries name triangles 0 .. kTris-1
constexpr uint32_t kTriBase = 0x08000, kTris = 40;
constexpr uint32_t kMemBytes = 0x10000;

uint32_t EntryTri(uint32_t entry) { return (entry * 2654435761u >> 7) % kTris; }

uint8_t MemByte(uint32_t addr) {
  if (addr >= kListBase && addr < kListBase + 4 * kListEntries) {
    const uint32_t off = addr - kListBase;
    return static_cast<uint8_t>(EntryTri(off / 4) >> (8 * (off % 4)));
  }
  return static_cast<uint8_t>((addr * 2246822519u) >> 11);
}

struct NodeReq {
  uint32_t tag, addr;
};
struct ListReq {
  uint32_t tag, addr, count;
};
struct Beat {
  uint64_t due;
  uint32_t addr, tag;
};

template <class Dut>
bool Run(const char* name, uint64_t count, uint32_t tris_per_line = 1, bool stream = false) {
  std::printf("rt_mem_system, %s:\n", name);
  SimCtrl<Dut> sim;
  Dut& dut = sim.top();
  dut.node_req_valid_i = 0;
  dut.list_req_valid_i = 0;
  dut.mem_resp_valid_i = 0;
  sim.Reset();
  Rng rng(31);
  dut.tri_base_i = kTriBase;

  std::map<uint32_t, NodeReq> node_out;           // outstanding node requests, by tag
  std::multimap<uint32_t, uint32_t> list_out;     // outstanding list requests: tag -> entry address
  std::vector<Beat> memory;                       // requested beats not yet answered
  NodeReq node_offer{};
  ListReq list_offer{};
  bool node_offering = false, list_offering = false;
  uint64_t node_sent = 0, list_sent = 0, list_entries = 0, node_answered = 0, tri_answered = 0, entries = 0;
  uint64_t hits[3] = {0, 0, 0}, misses[3] = {0, 0, 0};
  double p_node = 0.5, p_list = 0.5, p_ready = 0.8, p_mem_ready = 0.8;
  uint64_t cycle = 0;
  auto fail = [&](const char* what) {
    std::printf("rt_mem_system: FAIL at cycle %llu: %s\n", static_cast<unsigned long long>(cycle), what);
    return false;
  };
  const uint64_t limit = 400 * count + 10000;
  for (; node_answered < count || tri_answered < list_entries || list_sent < count || !node_out.empty() ||
         !list_out.empty();
       ++cycle) {
    if (cycle > limit) return fail("timeout: requests left unanswered");
    if (cycle % 300 == 0) {
      p_node = std::array<double, 3>{0.9, 0.4, 0.05}[rng.Below(3)];
      p_list = std::array<double, 3>{0.9, 0.4, 0.05}[rng.Below(3)];
      p_ready = std::array<double, 3>{1.0, 0.7, 0.2}[rng.Below(3)];
      p_mem_ready = std::array<double, 3>{1.0, 0.7, 0.2}[rng.Below(3)];
    }
    // Node requests: a free tag, any address in the node area; may change or drop while waiting.
    if ((!node_offering || rng.Chance(0.1)) && node_sent < count) {
      node_offering = false;
      if (rng.Chance(p_node) && node_out.size() < kTags) {
        uint32_t tag = rng.Below(kTags);
        while (node_out.count(tag)) tag = (tag + 1) % kTags;
        node_offer = NodeReq{tag, kNodeBase + 8 * rng.Below(kNodeBytes / 8)};
        node_offering = true;
      }
    }
    if (!list_offering && list_sent < count && rng.Chance(p_list)) {
      const uint32_t addr = kListBase + 4 * rng.Below(kListEntries);
      list_offer = ListReq{rng.Below(kTags), addr, stream ? 1 + rng.Below((32 - addr % 32) / 4) : 1};
      list_offering = true;
    }
    dut.node_req_valid_i = node_offering;
    dut.node_req_tag_i = node_offer.tag;
    dut.node_req_addr_i = node_offer.addr;
    dut.list_req_valid_i = list_offering;
    dut.list_req_tag_i = list_offer.tag;
    dut.list_req_addr_i = list_offer.addr;
    dut.list_req_count_i = list_offer.count;
    dut.node_resp_ready_i = rng.Chance(p_ready);
    dut.tri_resp_ready_i = rng.Chance(p_ready);
    dut.mem_req_ready_i = rng.Chance(p_mem_ready);
    // Memory: one due beat per cycle, in random order among the due ones.
    dut.mem_resp_valid_i = 0;
    std::vector<size_t> due;
    for (size_t i = 0; i < memory.size(); ++i) {
      if (memory[i].due <= cycle) due.push_back(i);
    }
    if (!due.empty()) {
      const size_t i = due[rng.Below(static_cast<uint32_t>(due.size()))];
      dut.mem_resp_valid_i = 1;
      dut.mem_resp_tag_i = memory[i].tag;
      for (int k = 0; k < 16; ++k) PutBits(dut.mem_resp_data_i, 8 * k, 8, MemByte(memory[i].addr + k));
      memory.erase(memory.begin() + static_cast<long>(i));
    }
    sim.Settle();

    if (dut.mem_req_valid_o) {
      if (!dut.mem_wait_o) return fail("a memory request waits but mem_wait_o is low");
      if (dut.mem_req_addr_o % 16 != 0 || dut.mem_req_addr_o >= kMemBytes) return fail("memory address");
      if (dut.mem_req_ready_i) memory.push_back(Beat{cycle + 1 + rng.Below(40), dut.mem_req_addr_o, dut.mem_req_tag_o});
    }
    for (int c = 0; c < 3; ++c) {
      const bool h = (dut.hit_o >> c) & 1, m = (dut.miss_o >> c) & 1;
      if (h && m) return fail("hit and miss at once");
      hits[c] += h;
      misses[c] += m;
    }
    entries += dut.entry_fire_o;
    if (dut.node_req_valid_i && dut.node_req_ready_o) {
      node_out[node_offer.tag] = node_offer;
      node_offering = false;
      ++node_sent;
    }
    if (dut.list_req_valid_i && dut.list_req_ready_o) {
      for (uint32_t k = 0; k < list_offer.count; ++k) list_out.emplace(list_offer.tag, list_offer.addr + 4 * k);
      list_entries += list_offer.count;
      list_offering = false;
      ++list_sent;
    }
    if (dut.node_resp_valid_o && dut.node_resp_ready_i) {
      auto it = node_out.find(dut.node_resp_tag_o);
      if (it == node_out.end()) return fail("node response with a tag no outstanding request has");
      const uint32_t line = it->second.addr / kNodeLineBytes * kNodeLineBytes;
      for (int k = 0; k < kNodeLineBytes; ++k) {
        if (GetBits(dut.node_resp_line_o, 8 * k, 8) != MemByte(line + k)) return fail("node line data");
      }
      node_out.erase(it);
      ++node_answered;
    }
    if (dut.tri_resp_valid_o && dut.tri_resp_ready_i) {
      const uint32_t tag = dut.tri_resp_tag_o, id = dut.tri_resp_id_o;
      auto range = list_out.equal_range(tag);
      auto it = range.first;
      while (it != range.second && EntryTri((it->second - kListBase) / 4) != id) ++it;
      if (it == range.second) return fail("triangle response that no outstanding list request of its tag names");
      const uint32_t record_bytes = 48 / tris_per_line;
      const uint32_t record = kTriBase + 48 * (id / tris_per_line) + record_bytes * (id % tris_per_line);
      for (uint32_t k = 0; k < record_bytes; ++k) {
        if (GetBits(dut.tri_resp_o, 8 * k, 8) != MemByte(record + k)) return fail("triangle record");
      }
      list_out.erase(it);
      ++tri_answered;
    }
    sim.Tick();
    if (node_sent >= count) node_offering = false;
  }
  // Drain: nothing more may come back.
  for (int i = 0; i < 100; ++i, ++cycle) {
    dut.node_req_valid_i = 0;
    dut.list_req_valid_i = 0;
    dut.mem_resp_valid_i = 0;
    sim.Settle();
    if (dut.node_resp_valid_o || dut.tri_resp_valid_o) return fail("a response after all were answered");
    sim.Tick();
  }
  if (hits[0] + misses[0] != node_sent) return fail("node cache: hits + misses != requests");
  if (hits[1] + misses[1] != list_sent) return fail("list cache: hits + misses != requests");
  if (hits[2] + misses[2] != entries || entries != list_entries) {
    return fail("triangle cache: hits + misses != entries");
  }
  if (stream != (list_entries > list_sent)) return fail("list requests of several entries (only with ListStream)");
  if (!memory.empty()) return fail("memory beats requested and never used");
  for (int c = 0; c < 3; ++c) {
    if (hits[c] == 0 || misses[c] == 0) return fail("a cache saw no hit or no miss");
  }
  std::printf("rt_mem_system: PASS (%llu node and %llu list requests of %llu entries, %llu cycles; hits/misses node "
              "%llu/%llu, list %llu/%llu, triangle %llu/%llu)\n",
              static_cast<unsigned long long>(node_sent), static_cast<unsigned long long>(list_sent),
              static_cast<unsigned long long>(list_entries),
              static_cast<unsigned long long>(cycle), static_cast<unsigned long long>(hits[0]),
              static_cast<unsigned long long>(misses[0]), static_cast<unsigned long long>(hits[1]),
              static_cast<unsigned long long>(misses[1]), static_cast<unsigned long long>(hits[2]),
              static_cast<unsigned long long>(misses[2]));
  return true;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  Verilated::commandArgs(argc, argv);
  const uint64_t count = LongRun() ? 1000000 : 100000;
  bool ok = Run<Vrt_mem_system>("direct-mapped caches", count);
  ok = Run<Vrt_mem_system_ways2>("2-way caches", count) && ok;
  ok = Run<Vrt_mem_system_pairs>("two triangle records per line", count, 2) && ok;
  ok = Run<Vrt_mem_system_stream>("a list line a request (ListStream 1)", count, 1, true) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
