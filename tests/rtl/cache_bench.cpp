// Verilator bench of rtl/rt_cache.sv, a non-blocking cache whose responses
// may come back out of order: every request carries a tag that is unique
// among the outstanding ones, and every response must carry the tag of an
// outstanding request and that request's line (checked against memory).
// Every request is answered exactly once, hits + misses == requests, no more
// misses are in flight than there are miss registers, and the run must show
// that the cache really overlaps misses and hits under a miss. With Targets >
// 1, misses to a line already being fetched must merge (merge_o) and fetch
// nothing: memory sees exactly one fetch per miss that did not merge; with
// Targets = 1 nothing merges. With MissPort, a second requester offers its
// own requests on the miss-only port: what it takes must be a miss, at most
// one miss is taken per cycle, and a request it leaves may move to the first
// port. A wait reason (wait_inflight_o, wait_mshr_o)
// is only given for a request not taken. Memory answers
// each beat after a random latency and in random order; the requester sends
// in random bursts and applies random backpressure.
//
// Prefetch port (RunPrefetch, PrefetchPort = 1): a prefetcher offers the
// keys the requester will ask for a few requests later on the second port,
// holding each until taken. A prefetch never gets a response and is never
// counted as a miss; a prefetch that takes a miss register raises prefetch_o
// (the core's list_prefetch event), and every line fetched is either such a
// prefetch or an own miss that did not merge; every request is still answered
// exactly once with its line; after the drain no miss register stays in use (filling_o low: a
// prefetch nobody joined is freed when its line is in); and the same request
// stream starts fewer fetches of its own (misses that did not merge) with the
// prefetcher than without it.
//
// The fast model's cache (sim/fast_units.h: fast::Cache) runs in lock-step
// with the RTL in Run and in the prefetch runs: its step gets the RTL's
// inputs of every cycle; its registered outputs (response valid and tag,
// memory request valid, address and id) must equal the RTL's in every cycle,
// and its step must take the same requests and count the same events (hit,
// miss, merge, prefetch, the two wait reasons). The first divergence names
// the cycle, the signal and both values. With KeyIsLine (the _keyline
// model) the requests' addresses are the keys times the line's bytes and the
// RTL makes the memory's addresses from the keys alone.
//
// Replacement (RunReplacement): requests one at a time, each answered before
// the next, on keys that crowd a few sets; every hit or miss must be the one
// a C++ model of the sets predicts (lowest invalid way, else the tree
// pseudo-LRU victim; hits and fills touch the tree), for Ways 1, 2 and 8.
#include <cstdio>
#include <map>
#include <random>
#include <vector>

#include "Vrt_cache_keyline.h"
#include "Vrt_cache_lines2.h"
#include "Vrt_cache_lines3.h"
#include "Vrt_cache_merge2.h"
#include "Vrt_cache_merge3.h"
#include "Vrt_cache_missport.h"
#include "Vrt_cache_prefetch.h"
#include "Vrt_cache_ways2.h"
#include "Vrt_cache_ways8.h"
#include "sim/fast_units.h"
#include "sim/sim_ctrl.h"
#include "tests/rtl/isect_bench_util.h"

namespace kdrt::rtlbench {
namespace {

using sim::SimCtrl;

constexpr int kLines = 8;    // must match the verilated parameters
constexpr int kTags = 256;   // TagWidth = 8

uint8_t MemByte(uint64_t addr) { return static_cast<uint8_t>((addr * 2654435761u) >> 13); }

constexpr uint32_t kBase = 0x1000;  // the lines' base address (a request's address: kBase + key x line bytes)

struct Request {
  uint32_t key, addr, tag;
};

// fast::Cache beside the Verilated cache: Check() after the cycle's inputs
// are applied and settled, before the clock edge.
class FastLockStep {
 public:
  FastLockStep(const char* name, int beats, int ways, int mshrs, int targets, bool miss_port, bool prefetch_port,
               uint32_t base = kBase)
      : name_(name),
        cache_(kLines, ways, beats, mshrs, targets, miss_port, base, 16u * static_cast<uint64_t>(beats),
               prefetch_port) {}

  template <class Dut>
  bool Check(const Dut& dut, uint64_t cycle) {
    cycle_ = cycle;
    if (dut.resp_valid_o != cache_.resp_valid()) return Diverge("resp_valid_o", dut.resp_valid_o, cache_.resp_valid());
    if (dut.resp_valid_o && dut.resp_tag_o != cache_.resp_tag()) {
      return Diverge("resp_tag_o", dut.resp_tag_o, cache_.resp_tag());
    }
    if (dut.mem_req_valid_o != cache_.mem_valid()) {
      return Diverge("mem_req_valid_o", dut.mem_req_valid_o, cache_.mem_valid());
    }
    if (dut.mem_req_valid_o && dut.mem_req_addr_o != cache_.mem_addr()) {
      return Diverge("mem_req_addr_o", dut.mem_req_addr_o, cache_.mem_addr());
    }
    if (dut.mem_req_valid_o && static_cast<int>(dut.mem_req_id_o) != cache_.mem_id()) {
      return Diverge("mem_req_id_o", dut.mem_req_id_o, static_cast<uint64_t>(cache_.mem_id()));
    }
    const sim::fast::Cache::Events before = cache_.events();
    const unsigned taken = cache_.Step({dut.req_valid_i != 0, dut.req_key_i, dut.req_tag_i},
                                       {dut.req2_valid_i != 0, dut.req2_key_i, dut.req2_tag_i}, dut.resp_ready_i != 0,
                                       dut.mem_req_valid_o && dut.mem_req_ready_i,
                                       dut.mem_resp_valid_i ? static_cast<int>(dut.mem_resp_id_i) : -1);
    const sim::fast::Cache::Events& after = cache_.events();
    const unsigned rtl_taken = (dut.req_valid_i && dut.req_ready_o ? 1u : 0u) |
                               (dut.req2_valid_i && dut.req2_ready_o ? 2u : 0u);
    if (rtl_taken != taken) return Diverge("requests taken (bit 0: the first port)", rtl_taken, taken);
    if (dut.hit_o != after.hit - before.hit) return Diverge("hit_o", dut.hit_o, after.hit - before.hit);
    if (dut.miss_o != after.miss - before.miss) return Diverge("miss_o", dut.miss_o, after.miss - before.miss);
    if (dut.merge_o != after.merge - before.merge) return Diverge("merge_o", dut.merge_o, after.merge - before.merge);
    if (dut.prefetch_o != after.prefetch - before.prefetch) {
      return Diverge("prefetch_o", dut.prefetch_o, after.prefetch - before.prefetch);
    }
    if (dut.wait_inflight_o != after.wait_inflight - before.wait_inflight) {
      return Diverge("wait_inflight_o", dut.wait_inflight_o, after.wait_inflight - before.wait_inflight);
    }
    if (dut.wait_mshr_o != after.wait_mshr - before.wait_mshr) {
      return Diverge("wait_mshr_o", dut.wait_mshr_o, after.wait_mshr - before.wait_mshr);
    }
    return true;
  }

 private:
  bool Diverge(const char* what, uint64_t rtl, uint64_t model) const {
    std::printf("rt_cache %s: FAIL: the fast model's cache diverges at cycle %llu: %s RTL %llu, fast model %llu\n",
                name_, static_cast<unsigned long long>(cycle_), what, static_cast<unsigned long long>(rtl),
                static_cast<unsigned long long>(model));
    return false;
  }

  const char* name_;
  sim::fast::Cache cache_;
  uint64_t cycle_ = 0;
};

template <class Dut>
bool Run(const char* name, int beats, int ways, int mshrs, int targets, bool miss_port, uint64_t count,
         uint32_t base = kBase) {
  SimCtrl<Dut> sim;
  Dut& dut = sim.top();
  FastLockStep fast(name, beats, ways, mshrs, targets, miss_port, false, base);
  std::mt19937 rng(5);
  std::bernoulli_distribution bubble(0.3), stall(0.2);
  std::uniform_int_distribution<int> latency(1, 30);
  // Keys from a small range so that lines are reused and evicted.
  std::uniform_int_distribution<uint32_t> key_dist(0, 3 * kLines);
  std::map<uint32_t, Request> outstanding;  // by tag
  std::vector<uint32_t> free_tags;
  for (uint32_t t = 0; t < kTags; ++t) free_tags.push_back(t);
  struct Beat {
    uint64_t due;
    uint32_t addr;
    uint32_t id;
  };
  std::vector<Beat> in_flight;
  // Memory beats requested per miss register, to count the misses in flight.
  std::map<uint32_t, int> beats_owed;
  uint64_t sent = 0, answered = 0, hits = 0, misses = 0, hits_under_miss = 0, merges = 0, fetched_beats = 0;
  uint64_t waits_in_flight = 0, waits_no_mshr = 0;
  size_t max_misses_in_flight = 0;
  Request pending{}, pending2{};
  bool have_pending = false, have_pending2 = false;
  uint32_t next_tag = 0;  // resp_tag_next_o of the cycle before
  uint64_t taken2 = 0;  // requests the miss-only port took
  auto new_request = [&](Request* r) {
    const uint32_t key = key_dist(rng);
    const size_t pick = std::uniform_int_distribution<size_t>(0, free_tags.size() - 1)(rng);
    const uint32_t tag = free_tags[pick];
    free_tags[pick] = free_tags.back();
    free_tags.pop_back();
    *r = Request{key, base + key * 16u * static_cast<uint32_t>(beats), tag};
  };

  auto fail = [&](const char* what) {
    std::printf("rt_cache %s: FAIL after %llu requests: %s\n", name,
                static_cast<unsigned long long>(sent), what);
    return false;
  };

  dut.req_valid_i = 0;
  dut.mem_resp_valid_i = 0;
  sim.Reset();
  for (uint64_t cycle = 0; answered < count; ++cycle) {
    if (cycle > 200 * count + 1000) return fail("timeout");
    if (!have_pending && sent + have_pending2 < count && !free_tags.empty() && !bubble(rng)) {
      new_request(&pending);
      have_pending = true;
    }
    // The miss-only port: its own requests; one it does not take may be
    // withdrawn and come again on the first port (as rt_core's fetches do).
    if (miss_port && have_pending2 && !have_pending && rng() % 4 == 0) {
      pending = pending2;
      have_pending = true;
      have_pending2 = false;
    }
    if (miss_port && !have_pending2 && sent + have_pending < count && !free_tags.empty() && !bubble(rng)) {
      new_request(&pending2);
      have_pending2 = true;
    }
    dut.req2_valid_i = have_pending2;
    dut.req2_key_i = pending2.key;
    dut.req2_addr_i = pending2.addr;
    dut.req2_tag_i = pending2.tag;
    dut.req_valid_i = have_pending;
    dut.req_key_i = pending.key;
    dut.req_addr_i = pending.addr;
    dut.req_tag_i = pending.tag;
    dut.resp_ready_i = !stall(rng);
    // Memory: one due beat per cycle, in random order among the due ones.
    dut.mem_resp_valid_i = 0;
    std::vector<size_t> due;
    for (size_t i = 0; i < in_flight.size(); ++i) {
      if (in_flight[i].due <= cycle) due.push_back(i);
    }
    if (!due.empty()) {
      const size_t i = due[std::uniform_int_distribution<size_t>(0, due.size() - 1)(rng)];
      dut.mem_resp_valid_i = 1;
      dut.mem_resp_id_i = in_flight[i].id;
      for (int k = 0; k < 16; ++k) {
        PutBits(dut.mem_resp_data_i, 8 * k, 8, MemByte(in_flight[i].addr + k));
      }
      const uint32_t mshr = in_flight[i].id >> 2;
      if (--beats_owed[mshr] == 0) beats_owed.erase(mshr);
      in_flight.erase(in_flight.begin() + static_cast<long>(i));
    }
    dut.mem_req_ready_i = !stall(rng);
    sim.Settle();
    if (dut.resp_valid_o && dut.resp_tag_o != next_tag) return fail("resp_tag_next_o was not the next response's tag");
    if (!fast.Check(dut, cycle)) return false;
    if (dut.mem_req_valid_o && dut.mem_req_ready_i) {
      in_flight.push_back(
          Beat{cycle + static_cast<uint64_t>(latency(rng)), dut.mem_req_addr_o, dut.mem_req_id_o});
      ++beats_owed[dut.mem_req_id_o >> 2];
      ++fetched_beats;
      if (dut.mem_req_id_o >> 2 >= static_cast<uint32_t>(mshrs)) {
        return fail("memory id names no miss register");
      }
      if (beats_owed.size() > max_misses_in_flight) max_misses_in_flight = beats_owed.size();
    }
    const bool accept1 = dut.req_valid_i && dut.req_ready_o, accept2 = dut.req2_valid_i && dut.req2_ready_o;
    if (!miss_port && dut.req2_ready_o) return fail("the miss-only port takes requests with MissPort = 0");
    if (dut.hit_o && dut.miss_o && !accept2) return fail("hit and miss at once on one port");
    if (accept2 && !dut.miss_o) return fail("the miss-only port took a request that is not a miss");
    if (accept1 && accept2 && !dut.hit_o) return fail("two misses taken in one cycle");
    hits += dut.hit_o;
    misses += dut.miss_o;
    merges += dut.merge_o;
    waits_in_flight += dut.wait_inflight_o;
    waits_no_mshr += dut.wait_mshr_o;
    if (dut.merge_o && !dut.miss_o) return fail("a merge that is not a miss");
    if ((dut.wait_inflight_o || dut.wait_mshr_o) && (dut.req_ready_o || !dut.req_valid_i)) {
      return fail("a wait reason for a request that does not wait");
    }
    if (dut.wait_inflight_o && dut.wait_mshr_o) return fail("two wait reasons at once");
    if (dut.hit_o && !beats_owed.empty()) ++hits_under_miss;
    if (accept1) {
      if (!dut.hit_o && !dut.miss_o) return fail("request accepted as neither hit nor miss");
      outstanding[pending.tag] = pending;
      have_pending = false;
      ++sent;
    } else if (dut.hit_o || (dut.miss_o && !accept2)) {
      return fail("hit or miss event without an accepted request");
    }
    if (accept2) {
      outstanding[pending2.tag] = pending2;
      have_pending2 = false;
      ++sent;
      ++taken2;
    }
    if (dut.resp_valid_o && dut.resp_ready_i) {
      const uint32_t tag = dut.resp_tag_o;
      auto it = outstanding.find(tag);
      if (it == outstanding.end()) {
        std::printf("rt_cache %s: FAIL: response with tag %u that no outstanding request has\n",
                    name, tag);
        return false;
      }
      const Request& r = it->second;
      for (int k = 0; k < 16 * beats; ++k) {
        if (GetBits(dut.resp_data_o, 8 * k, 8) != MemByte(r.addr + k)) {
          std::printf("rt_cache %s: FAIL at response %llu: key %u addr 0x%x tag %u: byte %d\n",
                      name, static_cast<unsigned long long>(answered), r.key, r.addr, r.tag, k);
          return false;
        }
      }
      outstanding.erase(it);
      free_tags.push_back(tag);
      ++answered;
    }
    next_tag = dut.resp_tag_next_o;
    sim.Tick();
  }
  // Drain: nothing more may come back.
  for (int cycle = 0; cycle < 100; ++cycle) {
    dut.req_valid_i = 0;
    dut.resp_ready_i = 1;
    dut.mem_resp_valid_i = 0;
    sim.Settle();
    if (dut.resp_valid_o) return fail("response after every request was answered");
    sim.Tick();
  }
  if (sent != count || !outstanding.empty() || !in_flight.empty()) {
    return fail("requests left unanswered");
  }
  if (hits + misses != sent) return fail("hits + misses != requests");
  if (static_cast<int>(max_misses_in_flight) > mshrs) {
    return fail("more misses in flight than miss registers");
  }
  if (mshrs > 1 && max_misses_in_flight < 2) return fail("misses never overlapped");
  if (hits_under_miss == 0) return fail("no hit under a miss");
  if (fetched_beats != (misses - merges) * static_cast<uint64_t>(beats)) {
    return fail("memory beats fetched != beats of the misses that did not merge");
  }
  if (targets > 1 && merges == 0) return fail("no miss merged");
  if (targets == 1 && merges != 0) return fail("a miss merged with Targets = 1");
  if (waits_in_flight == 0 || waits_no_mshr == 0) return fail("a wait reason never seen");
  if (miss_port && taken2 == 0) return fail("the miss-only port never took a miss");
  std::printf(
      "rt_cache %s: PASS (%llu requests, %llu hits, %llu misses of which %llu merged, %llu hits under "
      "miss, up to %zu misses in flight)\n",
      name, static_cast<unsigned long long>(count), static_cast<unsigned long long>(hits),
      static_cast<unsigned long long>(misses), static_cast<unsigned long long>(merges),
      static_cast<unsigned long long>(hits_under_miss), max_misses_in_flight);
  return true;
}

// One run of RunPrefetch: the requests' misses that did not merge (their own
// fetches), or -1 on a failure.
template <class Dut>
int64_t PrefetchRun(const char* name, int beats, bool prefetch, uint64_t count) {
  SimCtrl<Dut> sim;
  Dut& dut = sim.top();
  std::mt19937 rng(11), key_rng(12);
  std::bernoulli_distribution bubble(0.3), stall(0.2), offer(0.7);
  std::uniform_int_distribution<int> latency(1, 30);
  std::uniform_int_distribution<uint32_t> key_dist(0, 3 * kLines);
  constexpr uint64_t kAhead = 6;  // the prefetcher's lead, in requests
  std::vector<uint32_t> keys(count + kAhead);
  for (auto& k : keys) k = key_dist(key_rng);
  auto addr_of = [&](uint32_t key) { return kBase + key * 16u * static_cast<uint32_t>(beats); };
  FastLockStep fast(name, beats, 2, 4, 3, false, true);  // the prefetch configuration's Ways, Mshrs, Targets
  std::map<uint32_t, Request> outstanding;
  std::vector<uint32_t> free_tags;
  for (uint32_t t = 0; t < kTags; ++t) free_tags.push_back(t);
  struct Beat {
    uint64_t due;
    uint32_t addr, id;
  };
  std::vector<Beat> in_flight;
  uint64_t sent = 0, answered = 0, misses = 0, prefetches = 0, pf_next = kAhead, prefetch_fetches = 0, fetched_beats = 0;
  Request pending{};
  bool have_pending = false, have_pf = false;
  uint32_t pf_key = 0;
  uint32_t next_tag = 0;  // resp_tag_next_o of the cycle before
  auto fail = [&](const char* what) {
    std::printf("rt_cache %s: FAIL after %llu requests: %s\n", name, static_cast<unsigned long long>(sent), what);
    return int64_t{-1};
  };
  auto memory = [&](uint64_t cycle) {
    dut.mem_resp_valid_i = 0;
    std::vector<size_t> due;
    for (size_t i = 0; i < in_flight.size(); ++i) {
      if (in_flight[i].due <= cycle) due.push_back(i);
    }
    if (due.empty()) return;
    const size_t i = due[std::uniform_int_distribution<size_t>(0, due.size() - 1)(rng)];
    dut.mem_resp_valid_i = 1;
    dut.mem_resp_id_i = in_flight[i].id;
    for (int k = 0; k < 16; ++k) PutBits(dut.mem_resp_data_i, 8 * k, 8, MemByte(in_flight[i].addr + k));
    in_flight.erase(in_flight.begin() + static_cast<long>(i));
  };
  dut.req_valid_i = 0;
  dut.req2_valid_i = 0;
  dut.mem_resp_valid_i = 0;
  sim.Reset();
  uint64_t cycle = 0;
  for (; answered < count; ++cycle) {
    if (cycle > 200 * count + 1000) return fail("timeout");
    if (!have_pending && sent < count && !free_tags.empty() && !bubble(rng)) {
      const uint32_t tag = free_tags.back();
      free_tags.pop_back();
      pending = Request{keys[sent], addr_of(keys[sent]), tag};
      have_pending = true;
    }
    // The prefetcher: the key of a later request, held until taken.
    if (prefetch && !have_pf && pf_next < sent + 2 * kAhead && pf_next < keys.size() && offer(rng)) {
      pf_key = keys[pf_next++];
      have_pf = true;
    }
    dut.req_valid_i = have_pending;
    dut.req_key_i = pending.key;
    dut.req_addr_i = pending.addr;
    dut.req_tag_i = pending.tag;
    dut.req2_valid_i = have_pf;
    dut.req2_key_i = pf_key;
    dut.req2_addr_i = addr_of(pf_key);
    dut.req2_tag_i = 0;
    dut.resp_ready_i = !stall(rng);
    memory(cycle);
    dut.mem_req_ready_i = !stall(rng);
    sim.Settle();
    if (dut.resp_valid_o && dut.resp_tag_o != next_tag) return fail("resp_tag_next_o was not the next response's tag");
    if (!fast.Check(dut, cycle)) return -1;
    if (!prefetch && dut.req2_ready_o && dut.req2_valid_i) return fail("a prefetch taken with none offered");
    if (dut.mem_req_valid_o && dut.mem_req_ready_i) {
      in_flight.push_back(Beat{cycle + static_cast<uint64_t>(latency(rng)), dut.mem_req_addr_o, dut.mem_req_id_o});
      ++fetched_beats;
    }
    const bool accept1 = dut.req_valid_i && dut.req_ready_o;
    if (dut.miss_o && !(accept1 && !dut.hit_o)) return fail("a miss counted for a prefetch");
    if (dut.prefetch_o && !(have_pf && dut.req2_ready_o)) return fail("a prefetch event without a prefetch taken");
    misses += dut.miss_o && !dut.merge_o;
    prefetch_fetches += dut.prefetch_o;
    if (accept1) {
      outstanding[pending.tag] = pending;
      have_pending = false;
      ++sent;
    }
    if (have_pf && dut.req2_ready_o) {
      have_pf = false;
      ++prefetches;
    }
    if (dut.resp_valid_o && dut.resp_ready_i) {
      auto it = outstanding.find(dut.resp_tag_o);
      if (it == outstanding.end()) return fail("a response no request asked for (a prefetch's?)");
      for (int k = 0; k < 16 * beats; ++k) {
        if (GetBits(dut.resp_data_o, 8 * k, 8) != MemByte(it->second.addr + k)) return fail("wrong line");
      }
      free_tags.push_back(it->first);
      outstanding.erase(it);
      ++answered;
    }
    next_tag = dut.resp_tag_next_o;
    sim.Tick();
  }
  // Drain: the prefetches' beats come in, nothing is answered, every miss
  // register is freed.
  dut.req_valid_i = 0;
  dut.req2_valid_i = 0;
  dut.resp_ready_i = 1;
  dut.mem_req_ready_i = 1;
  for (int k = 0; k < 200; ++k, ++cycle) {
    memory(cycle);
    sim.Settle();
    if (dut.mem_req_valid_o) {
      in_flight.push_back(Beat{cycle + static_cast<uint64_t>(latency(rng)), dut.mem_req_addr_o, dut.mem_req_id_o});
      ++fetched_beats;
    }
    if (dut.resp_valid_o) return fail("a response after every request was answered");
    if (dut.prefetch_o) return fail("a prefetch event with no prefetch offered");
    sim.Tick();
  }
  sim.Settle();
  if (!in_flight.empty() || !outstanding.empty()) return fail("beats or requests left over");
  if (dut.filling_o) return fail("a miss register stays in use after the drain (a prefetch not freed?)");
  if (prefetch && prefetches == 0) return fail("no prefetch taken");
  // Every line fetched is a miss of the requests' own that did not merge or
  // a prefetch that took a register (prefetch_o, the list_prefetch event).
  if (fetched_beats != (misses + prefetch_fetches) * static_cast<uint64_t>(beats)) {
    return fail("the beats fetched are not the own misses' and the counted prefetches' lines");
  }
  if (prefetch && prefetch_fetches == 0) return fail("no prefetch fetched a line");
  return static_cast<int64_t>(misses);
}

template <class Dut>
bool RunPrefetch(const char* name, int beats, uint64_t count) {
  const int64_t with = PrefetchRun<Dut>(name, beats, true, count);
  const int64_t without = PrefetchRun<Dut>(name, beats, false, count);
  if (with < 0 || without < 0) return false;
  if (with >= without) {
    std::printf("rt_cache %s: FAIL: %lld fetching misses with the prefetcher, %lld without\n", name,
                static_cast<long long>(with), static_cast<long long>(without));
    return false;
  }
  std::printf("rt_cache %s: PASS prefetch (%llu requests: %lld fetching misses with the prefetcher, %lld without)\n", name,
              static_cast<unsigned long long>(count), static_cast<long long>(with), static_cast<long long>(without));
  return true;
}

// The cache's sets as the header of rtl/rt_cache.sv states them.
class SetModel {
 public:
  SetModel(int lines, int ways) : ways_(ways), sets_(lines / ways), key_(lines, -1), tree_(sets_, 0) {
    while ((1 << bits_) < ways) ++bits_;
  }
  // Whether `key` hits; a miss fills its line. Either touches the tree.
  bool Access(int key) {
    const int set = key % sets_;
    int way = -1;
    for (int w = 0; w < ways_; ++w) {
      if (key_[set * ways_ + w] == key) way = w;
    }
    const bool hit = way >= 0;
    if (!hit) {
      for (int w = ways_ - 1; w >= 0; --w) {
        if (key_[set * ways_ + w] < 0) way = w;
      }
      if (way < 0) {  // follow the tree from its root
        way = 0;
        for (int l = 0; l < bits_; ++l) {
          way |= ((tree_[set] >> ((1 << l) - 1 + (way >> (bits_ - l)))) & 1) << (bits_ - 1 - l);
        }
      }
      key_[set * ways_ + way] = key;
    }
    for (int l = 0; l < bits_; ++l) {  // point away from the way
      const int node = (1 << l) - 1 + (way >> (bits_ - l));
      const int toward = (way >> (bits_ - 1 - l)) & 1;
      tree_[set] = (tree_[set] & ~(1 << node)) | (!toward) << node;
    }
    return hit;
  }

 private:
  int ways_, sets_, bits_ = 0;
  std::vector<int> key_, tree_;
};

template <class Dut>
bool RunReplacement(const char* name, int ways, int beats, int count) {
  SimCtrl<Dut> sim;
  Dut& dut = sim.top();
  SetModel model(kLines, ways);
  std::mt19937 rng(11);
  // Keys of two sets (or of the one set), a few more than they hold.
  const int sets = kLines / ways;
  std::uniform_int_distribution<int> key_dist(0, 2 * ways + 1);
  dut.req_valid_i = 0;
  dut.req2_valid_i = 0;
  dut.mem_resp_valid_i = 0;
  dut.resp_ready_i = 1;
  dut.mem_req_ready_i = 1;
  sim.Reset();
  struct Beat {
    uint64_t due;
    uint32_t addr, id;
  };
  std::vector<Beat> in_flight;
  int hits = 0, evictions_seen = 0;
  uint64_t cycle = 0;
  for (int n = 0; n < count; ++n) {
    const int k = key_dist(rng);
    const uint32_t key = static_cast<uint32_t>((k % 2) + (k / 2) * sets);  // sets 0 and 1
    const bool expect_hit = model.Access(static_cast<int>(key));
    dut.req_valid_i = 1;
    dut.req_key_i = key;
    dut.req_addr_i = 0x1000u + key * 16u * static_cast<uint32_t>(beats);
    dut.req_tag_i = static_cast<uint32_t>(n & 0xFF);
    bool taken = false, answered = false;
    for (int wait = 0; !answered; ++wait, ++cycle) {
      if (wait > 1000) {
        std::printf("rt_cache %s: FAIL: request %d (key %u) not answered\n", name, n, key);
        return false;
      }
      dut.mem_resp_valid_i = 0;
      for (size_t i = 0; i < in_flight.size(); ++i) {
        if (in_flight[i].due > cycle) continue;
        dut.mem_resp_valid_i = 1;
        dut.mem_resp_id_i = in_flight[i].id;
        for (int b = 0; b < 16; ++b) PutBits(dut.mem_resp_data_i, 8 * b, 8, MemByte(in_flight[i].addr + b));
        in_flight.erase(in_flight.begin() + static_cast<long>(i));
        break;
      }
      sim.Settle();
      if (dut.mem_req_valid_o) in_flight.push_back(Beat{cycle + 1 + cycle % 4, dut.mem_req_addr_o, dut.mem_req_id_o});
      if (!taken && dut.req_ready_o) {
        if (dut.hit_o != expect_hit) {
          std::printf("rt_cache %s: FAIL: request %d (key %u) %s, the model says %s\n", name, n, key,
                      dut.hit_o ? "hit" : "missed", expect_hit ? "hit" : "miss");
          return false;
        }
        taken = true;
        hits += expect_hit;
      }
      if (dut.resp_valid_o) {
        if (!taken || dut.resp_tag_o != static_cast<uint32_t>(n & 0xFF)) {
          std::printf("rt_cache %s: FAIL: response of another request\n", name);
          return false;
        }
        answered = true;
      }
      sim.Tick();
      if (taken) dut.req_valid_i = 0;
    }
    evictions_seen += !expect_hit && n >= 2 * ways;
  }
  if (hits == 0 || hits == count) {
    std::printf("rt_cache %s: FAIL: replacement never exercised (%d hits of %d)\n", name, hits, count);
    return false;
  }
  std::printf("rt_cache %s: PASS replacement (%d requests, %d hits, as the model)\n", name, count, hits);
  return true;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  Verilated::commandArgs(argc, argv);
  const uint64_t count = LongRun() ? 2000000 : 200000;
  // Beats, ways, miss registers and targets must match the verilated parameters.
  bool ok = Run<Vrt_cache_lines2>("2-beat lines, 4 miss registers", 2, 1, 4, 1, false, count);
  ok = Run<Vrt_cache_lines3>("3-beat lines, 3 miss registers", 3, 1, 3, 1, false, count) && ok;
  ok = Run<Vrt_cache_merge2>("2-beat lines, 4 miss registers of 3 targets", 2, 1, 4, 3, false, count) && ok;
  ok = Run<Vrt_cache_merge3>("3-beat lines, 2 miss registers of 5 targets", 3, 1, 2, 5, false, count) && ok;
  ok = Run<Vrt_cache_missport>("2-beat lines, 4 miss registers of 3 targets, miss-only port", 2, 1, 4, 3, true,
                               count) &&
       ok;
  ok = Run<Vrt_cache_ways2>("2-beat lines, 2 ways, 4 miss registers of 3 targets", 2, 2, 4, 3, false, count) && ok;
  ok = Run<Vrt_cache_ways8>("3-beat lines, 8 ways (one set), 3 miss registers of 2 targets, miss-only port", 3, 8,
                            3, 2, true, count) &&
       ok;
  // KeyIsLine: no address per miss register, a line's address is its key
  // times its bytes (base 0).
  ok = Run<Vrt_cache_keyline>("2-beat lines, 2 ways, 4 miss registers of 3 targets, miss-only port, address from "
                              "the key",
                              2, 2, 4, 3, true, count, 0) &&
       ok;
  ok = RunPrefetch<Vrt_cache_prefetch>("2-beat lines, 2 ways, 4 miss registers of 3 targets, prefetch port", 2,
                                       count / 4) &&
       ok;
  ok = RunReplacement<Vrt_cache_lines2>("direct-mapped", 1, 2, 4000) && ok;
  ok = RunReplacement<Vrt_cache_ways2>("2 ways", 2, 2, 4000) && ok;
  ok = RunReplacement<Vrt_cache_ways8>("8 ways", 8, 3, 4000) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
