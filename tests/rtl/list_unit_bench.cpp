// Verilator bench of rtl/rt_list_unit.sv against a C++ model of the leaf-job
// queue and the list walker, cycle by cycle: job_ready_o (room in the queue
// of Jobs entries), and the list-entry requests: one per entry of each job,
// in job order, address list_base + 4 * (first + k), the job's tag, a new job
// taken only when the walker is idle (a job queued in a cycle is seen the
// next). Jobs come in random bursts, held until taken (picorv32's rule);
// requests meet random backpressure. First entries span the whole 32-bit
// word (the address keeps AddrWidth bits), counts 1 .. 12. Twice: one entry
// a request, and with ListStream 1, where a request names every entry of
// the job left in the entry's 32-byte line (req_count_o) and the next
// request starts at the next line. With ListPrefetch N (the _prefetch
// models), the prefetcher too: valid while it is at one of the N oldest
// queued jobs (not the walker's), one line address a cycle from the job's
// first entry's line to its last's, then the next job; a pop of its job
// restarts it at the new oldest one; random backpressure on pf_ready_i.
// Without ListPrefetch pf_valid_o stays low. The fast model's list unit
// (sim/fast_units.h: fast::ListUnit) runs beside it on the same inputs and
// must show the same outputs every cycle (job_ready_o, the request and the
// prefetch with their payloads).
#include <algorithm>
#include <cstdio>
#include <deque>

#include "Vrt_list_unit.h"
#include "Vrt_list_unit_prefetch.h"
#include "Vrt_list_unit_prefetch5.h"
#include "Vrt_list_unit_stream.h"
#include "sim/fast_units.h"
#include "sim/sim_ctrl.h"
#include "tests/rtl/isect_bench_util.h"

namespace kdrt::rtlbench {
namespace {

using sim::SimCtrl;

// As verilated (tests/rtl/CMakeLists.txt).
constexpr unsigned kJobs = 3;
constexpr unsigned kAddrBits = 20;
constexpr uint32_t kAddrMask = (1u << kAddrBits) - 1;
constexpr uint32_t kTagMask = 0xF;

struct Job {
  uint32_t tag = 0, first = 0, count = 0;
};

// The walker as specified: idle, or requesting entry `addr` of job `tag`
// with `left` entries to go.
struct Model {
  std::deque<Job> queue;
  bool active = false;
  uint32_t tag = 0, addr = 0, left = 0;
  size_t pf_off = 0;  // the prefetcher's job: queue[pf_off]
  uint32_t pf_k = 0;  // its next entry
};

// The entries a request names: one, or (stream) the job's left in the line.
uint32_t RequestCount(bool stream, uint32_t addr, uint32_t left) {
  return stream ? std::min(left, (32 - (addr & 31)) / 4) : 1;
}

template <class Dut>
bool Run(const char* name, bool stream, uint32_t prefetch, uint64_t cycles) {
  SimCtrl<Dut> sim;
  Dut& dut = sim.top();
  dut.job_valid_i = 0;
  dut.req_ready_i = 0;
  sim.Reset();
  Rng rng(3);
  Model m;
  Job pending;
  bool offering = false;
  double p_job = 0.3, p_ready = 0.7;
  uint64_t jobs = 0, requests = 0, entries = 0, full_cycles = 0, multi = 0, prefetches = 0, restarts = 0;
  uint32_t base = 0;
  sim::fast::ListUnit fast(kJobs, stream, prefetch, base, 32, 4);
  auto fail = [&](const char* what, uint64_t cycle) {
    std::printf("rt_list_unit (%s): FAIL at cycle %llu: %s\n", name, static_cast<unsigned long long>(cycle), what);
    std::printf("  model: %zu jobs queued, walker %s tag %u addr 0x%05x left %u\n", m.queue.size(),
                m.active ? "busy" : "idle", m.tag, m.addr, m.left);
    std::printf("  rtl:   job_ready %d req_valid %d tag %u addr 0x%05x count %u\n", dut.job_ready_o,
                dut.req_valid_o, dut.req_tag_o, dut.req_addr_o, dut.req_count_o);
    return false;
  };
  for (uint64_t cycle = 0; cycle < cycles; ++cycle) {
    if (cycle % 512 == 0) {
      p_job = std::array<double, 3>{0.9, 0.3, 0.05}[rng.Below(3)];
      p_ready = std::array<double, 4>{1.0, 0.9, 0.5, 0.1}[rng.Below(4)];
    }
    // list_base_i is stable while busy: a new one only when all is quiet.
    // (With ListStream or ListPrefetch a multiple of the entry size, as the
    // image's list section is: an entry never straddles two lines.)
    if (!m.active && m.queue.empty() && !offering && rng.Chance(0.01)) {
      base = rng.Bits32() & kAddrMask & (stream || prefetch > 0 ? ~3u : ~0u);
    }
    if (!offering && rng.Chance(p_job)) {
      offering = true;
      pending = Job{rng.Bits32() & kTagMask, rng.Chance(0.5) ? rng.Bits32() : rng.Below(64), 1 + rng.Below(12)};
    }
    dut.list_base_i = base;
    dut.job_valid_i = offering;
    dut.job_tag_i = pending.tag;
    dut.job_first_i = pending.first;
    dut.job_count_i = pending.count;
    dut.req_ready_i = rng.Chance(p_ready);
    dut.pf_ready_i = rng.Chance(0.6);
    sim.Settle();
    const bool pf_valid = m.pf_off < m.queue.size() && m.pf_off < prefetch;
    uint32_t pf_addr = 0, pf_next = 0;
    if (pf_valid) {
      const Job& pj = m.queue[m.pf_off];
      pf_addr = (base + 4 * pj.first + 4 * m.pf_k) & kAddrMask;
      pf_next = m.pf_k + (32 - (pf_addr & 31)) / 4;
    }
    if (static_cast<bool>(dut.pf_valid_o) != pf_valid) return fail("pf_valid_o", cycle);
    if (pf_valid && dut.pf_addr_o != (pf_addr & ~31u)) return fail("pf_addr_o", cycle);
    const bool pf_fire = pf_valid && dut.pf_ready_i;
    const bool pf_done = pf_valid && pf_next >= m.queue[m.pf_off].count;
    if (static_cast<bool>(dut.job_ready_o) != (m.queue.size() < kJobs)) return fail("job_ready_o", cycle);
    if (static_cast<bool>(dut.req_valid_o) != m.active) return fail("req_valid_o", cycle);
    const uint32_t n = m.active ? RequestCount(stream, m.addr, m.left) : 0;
    if (m.active && n == 0) return fail("the model asks for no entry", cycle);
    if (m.active && (dut.req_tag_o != m.tag || dut.req_addr_o != m.addr || dut.req_count_o != n)) {
      return fail("request payload", cycle);
    }
    full_cycles += m.queue.size() == kJobs;
    const bool job_fire = dut.job_valid_i && dut.job_ready_o;
    const bool req_fire = dut.req_valid_o && dut.req_ready_i;
    // The fast model's list unit, on the same inputs.
    fast.set_list_base(base);
    if (fast.job_ready() != static_cast<bool>(dut.job_ready_o)) return fail("the fast model's job_ready", cycle);
    if (fast.req_valid() != static_cast<bool>(dut.req_valid_o)) return fail("the fast model's req_valid", cycle);
    if (fast.req_valid() && (static_cast<uint32_t>(fast.req_job().thread) != dut.req_tag_o ||
                             (fast.req_addr() & kAddrMask) != dut.req_addr_o || fast.req_count() != dut.req_count_o)) {
      return fail("the fast model's request payload", cycle);
    }
    if (fast.pf_valid() != static_cast<bool>(dut.pf_valid_o)) return fail("the fast model's pf_valid", cycle);
    if (fast.pf_valid() && (fast.pf_addr() & kAddrMask & ~31u) != dut.pf_addr_o) {
      return fail("the fast model's pf_addr", cycle);
    }
    const sim::fast::ListJob fast_job{static_cast<int>(pending.tag), pending.first, pending.count};
    fast.Edge(req_fire, pf_fire, job_fire ? &fast_job : nullptr);
    sim.Tick();
    // The model's edge: the prefetcher and the walker (they see the queue as
    // it was), then the push.
    const bool pop = !m.active && !m.queue.empty();
    prefetches += pf_fire;
    if (pop && m.pf_off == 0) {
      m.pf_k = 0;
      restarts += pf_valid;
    } else {
      m.pf_off = m.pf_off + (pf_fire && pf_done ? 1 : 0) - (pop ? 1 : 0);
      if (pf_fire) m.pf_k = pf_done ? 0 : pf_next;
    }
    if (pop) {
      const Job j = m.queue.front();
      m.queue.pop_front();
      m.active = true;
      m.tag = j.tag;
      m.addr = (base + 4 * j.first) & kAddrMask;
      m.left = j.count;
    } else if (req_fire) {
      ++requests;
      entries += n;
      multi += n > 1;
      m.addr = (m.addr + 4 * n) & kAddrMask;
      m.left -= n;
      if (m.left == 0) m.active = false;
    }
    if (job_fire) {
      m.queue.push_back(pending);
      offering = false;
      ++jobs;
    }
  }
  if (full_cycles == 0) {
    std::printf("rt_list_unit (%s): FAIL: the job queue never filled\n", name);
    return false;
  }
  if ((prefetch > 0) != (prefetches > 0) || (prefetch > 0 && restarts == 0)) {
    std::printf("rt_list_unit (%s): FAIL: %llu prefetches, %llu restarted by the walker\n", name,
                static_cast<unsigned long long>(prefetches), static_cast<unsigned long long>(restarts));
    return false;
  }
  if (stream != (multi > 0)) {
    std::printf("rt_list_unit (%s): FAIL: %llu requests of several entries\n", name,
                static_cast<unsigned long long>(multi));
    return false;
  }
  std::printf("rt_list_unit (%s): PASS (%llu cycles, %llu jobs, %llu requests for %llu entries, queue full in "
              "%llu cycles, %llu line prefetches)\n",
              name, static_cast<unsigned long long>(cycles), static_cast<unsigned long long>(jobs),
              static_cast<unsigned long long>(requests), static_cast<unsigned long long>(entries),
              static_cast<unsigned long long>(full_cycles), static_cast<unsigned long long>(prefetches));
  return true;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  Verilated::commandArgs(argc, argv);
  const uint64_t cycles = LongRun() ? 10000000 : 1000000;
  bool ok = Run<Vrt_list_unit>("an entry a request", false, 0, cycles);
  ok = Run<Vrt_list_unit_stream>("ListStream 1", true, 0, cycles) && ok;
  ok = Run<Vrt_list_unit_prefetch>("ListStream 1, ListPrefetch 2", true, 2, cycles) && ok;
  ok = Run<Vrt_list_unit_prefetch5>("an entry a request, ListPrefetch 5 (more than the queue)", false, 5, cycles) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
