#include "sim/fast_model.h"

#include <chrono>
#include <deque>
#include <stdexcept>
#include <string>
#include <string_view>

#include "trace/tracer.h"

namespace kdrt::sim {
namespace {

constexpr int PerfBit(std::string_view name) {
  for (int b = 0; b < kPerfBits; ++b) {
    if (std::string_view(kPerfFields[b].name) == name) return b;
  }
  return -1;
}

// rt_rr_arb: the first requester after the last grant; the pointer moves on
// every grant when ack is set.
class RrArb {
 public:
  explicit RrArb(int n) : n_(n), last_(n - 1) {}
  int Pick(const std::vector<uint8_t>& req) const {
    for (int k = 1; k <= n_; ++k) {
      const int i = (last_ + k) % n_;
      if (req[i]) return i;
    }
    return -1;
  }
  void Ack(int idx) {
    if (idx >= 0) last_ = idx;
  }

 private:
  int n_, last_;
};

// rt_cache at the level of its registers (the header comment of
// rtl/rt_cache.sv): Eval() is the combinational part of one cycle from the
// registered state, Commit() the clock edge.
class Cache {
 public:
  struct Req {
    bool valid = false;
    uint64_t key = 0, addr = 0, tag = 0;
  };
  struct Events {
    uint64_t hit = 0, miss = 0, merge = 0, wait = 0, wait_inflight = 0, wait_mshr = 0;
  };

  Cache(int lines, int line_beats, int mshrs, int targets, bool miss_port)
      : lines_(lines), beats_(line_beats), targets_(targets), miss_port_(miss_port), line_valid_(lines, 0),
        line_key_(lines, 0), mshr_(mshrs) {}

  // Registered outputs, valid before Eval().
  bool resp_valid() const { return hit_valid_ || del_valid_; }
  uint64_t resp_tag() const { return del_valid_ ? del_tag_ : hit_tag_; }
  bool mem_valid() const { return held_ || PickSending() >= 0; }
  uint64_t mem_addr() const { return mshr_[SendIdx()].addr + 16u * mshr_[SendIdx()].sent; }
  int mem_id() const { return SendIdx() * 4 + static_cast<int>(mshr_[SendIdx()].sent); }

  void Eval(const Req& r1, const Req& r2, bool resp_ready) {
    c_ = Comb{};
    c_.r1 = r1;
    c_.r2 = r2;
    const int m_count = static_cast<int>(mshr_.size());
    int free_idx = -1, done_idx = -1, join_idx = -1, join2_idx = -1;
    bool any_match = false, any_match2 = false;
    for (int m = 0; m < m_count; ++m) {
      const Mshr& s = mshr_[m];
      if (!s.valid) {
        if (free_idx < 0) free_idx = m;
        continue;
      }
      const bool done = s.got == (1u << beats_) - 1;
      const bool room = s.cnt < targets_;
      if (done && done_idx < 0) done_idx = m;
      if (s.key == r1.key) {
        any_match = true;
        if (!done && room && join_idx < 0) join_idx = m;
      }
      if (s.key == r2.key) {
        any_match2 = true;
        if (!done && room && join2_idx < 0) join2_idx = m;
      }
    }
    const bool lookup_hit = Present(r1.key), lookup2_hit = Present(r2.key);
    c_.out_take = resp_valid() && resp_ready;
    const bool hit_free = !hit_valid_ || (c_.out_take && !del_valid_);
    const bool del_free = !del_valid_ || c_.out_take;
    c_.deliver = done_idx >= 0 && del_free && !(hit_valid_ && !del_valid_ && !resp_ready);
    c_.done_idx = done_idx;
    const bool hit_ok = lookup_hit && hit_free;
    const bool join_ok = !lookup_hit && join_idx >= 0;
    const bool alloc_ok = !lookup_hit && !any_match && free_idx >= 0;
    c_.ready1 = hit_ok || join_ok || alloc_ok;
    c_.accept = r1.valid && c_.ready1;
    const bool join2_ok = !lookup2_hit && join2_idx >= 0;
    const bool alloc2_ok = !lookup2_hit && !any_match2 && free_idx >= 0;
    c_.ready2 = miss_port_ && !(c_.accept && !lookup_hit) && (join2_ok || alloc2_ok);
    c_.accept2 = r2.valid && c_.ready2;
    c_.hit = c_.accept && lookup_hit;
    c_.m_take = (c_.accept && !lookup_hit) || c_.accept2;
    c_.m_join = c_.accept2 ? join2_ok : join_ok;
    c_.m_join_idx = c_.accept2 ? join2_idx : join_idx;
    c_.free_idx = free_idx;
    c_.m = c_.accept2 ? r2 : r1;
    if (c_.hit) ++ev_.hit;
    if (c_.m_take) ++ev_.miss;
    if (c_.m_take && c_.m_join) ++ev_.merge;
    if (r1.valid && !c_.ready1) ++ev_.wait;
    if (r1.valid && !lookup_hit && any_match && join_idx < 0) ++ev_.wait_inflight;
    if (r1.valid && !lookup_hit && !any_match && free_idx < 0) ++ev_.wait_mshr;
    c_.send_valid = mem_valid();
    c_.send_idx = c_.send_valid ? SendIdx() : -1;
  }
  bool ready1() const { return c_.ready1; }
  bool ready2() const { return c_.ready2; }
  bool accept1() const { return c_.accept; }
  bool accept2() const { return c_.accept2; }
  bool out_take() const { return c_.out_take; }

  // The clock edge: `mem_taken` (the arbiter took this cache's beat),
  // `resp_id` (>= 0: the memory's beat for {register, beat}).
  void Commit(bool mem_taken, int resp_id) {
    if (c_.out_take && del_valid_) {
      del_valid_ = false;
    } else if (c_.out_take) {
      hit_valid_ = false;
    }
    if (c_.hit) {
      hit_valid_ = true;
      hit_tag_ = c_.r1.tag;
    }
    if (c_.m_take) {
      if (c_.m_join) {
        Mshr& s = mshr_[c_.m_join_idx];
        s.tags.push_back(c_.m.tag);
        ++s.cnt;
      } else {
        Mshr& s = mshr_[c_.free_idx];
        s = Mshr{};
        s.valid = true;
        s.key = c_.m.key;
        s.addr = c_.m.addr;
        s.cnt = 1;
        s.tags = {c_.m.tag};
      }
    }
    if (mem_taken) ++mshr_[c_.send_idx].sent;
    if (resp_id >= 0) mshr_[resp_id / 4].got |= 1u << (resp_id % 4);
    if (c_.deliver) {
      Mshr& s = mshr_[c_.done_idx];
      del_tag_ = s.tags[s.out];
      ++s.out;
      const size_t line = s.key % lines_;
      line_valid_[line] = 1;
      line_key_[line] = s.key;
      del_valid_ = true;
      if (s.out == s.cnt) s.valid = false;
    }
    held_ = c_.send_valid && !mem_taken;
    held_idx_ = c_.send_idx;
  }

  const Events& events() const { return ev_; }

 private:
  struct Mshr {
    bool valid = false;
    uint64_t key = 0, addr = 0;
    uint32_t sent = 0, got = 0;
    int cnt = 0, out = 0;
    std::vector<uint64_t> tags;
  };
  struct Comb {
    Req r1, r2, m;
    bool out_take = false, deliver = false, ready1 = false, ready2 = false, accept = false, accept2 = false;
    bool hit = false, m_take = false, m_join = false, send_valid = false;
    int done_idx = -1, m_join_idx = -1, free_idx = -1, send_idx = -1;
  };

  bool Present(uint64_t key) const {
    const size_t line = key % lines_;
    return line_valid_[line] && line_key_[line] == key;
  }
  int PickSending() const {
    for (size_t m = 0; m < mshr_.size(); ++m) {
      if (mshr_[m].valid && mshr_[m].sent < static_cast<uint32_t>(beats_)) return static_cast<int>(m);
    }
    return -1;
  }
  int SendIdx() const { return held_ ? held_idx_ : PickSending(); }

  size_t lines_;
  int beats_, targets_;
  bool miss_port_;
  std::vector<uint8_t> line_valid_;
  std::vector<uint64_t> line_key_;
  std::vector<Mshr> mshr_;
  bool hit_valid_ = false, del_valid_ = false, held_ = false;
  uint64_t hit_tag_ = 0, del_tag_ = 0;
  int held_idx_ = 0;
  Comb c_;
  Events ev_;
};

constexpr int kBitRayIn = PerfBit("ray_in"), kBitRayOut = PerfBit("ray_out"), kBitBusy = PerfBit("busy"),
              kBitTravBusy = PerfBit("trav_busy"), kBitTravLeaf = PerfBit("trav_leaf"),
              kBitListBusy = PerfBit("list_busy"), kBitIsectBusy = PerfBit("isect_busy");
static_assert(kBitRayIn >= 0 && kBitRayOut >= 0 && kBitBusy >= 0 && kBitTravBusy >= 0 && kBitTravLeaf >= 0 &&
                  kBitListBusy >= 0 && kBitIsectBusy >= 0,
              "perf_t lost a field the fast model counts");

enum State : uint8_t { kFree, kSetup, kFetch, kWaitNode, kTrav, kLeaf, kExit, kDone };

struct Thread {
  State state = kFree;
  uint32_t ray = 0;
  size_t cursor = 0;  // the path entry fetched next (or being fetched)
  uint32_t remaining = 0, outstanding = 0;
};

struct Job {
  int thread;
  uint32_t first, count;
};

// A fixed-latency pipeline's results: (cycle, thread), in order.
using Pipe = std::deque<std::pair<uint64_t, int>>;

}  // namespace

RunOutcome RunFastModel(const FastSpec& spec, RayCounters* reference_totals) {
  const ImageView& image = *spec.image;
  const std::vector<Ray>& rays = *spec.rays;
  const CoreConfig& cfg = spec.config;
  const img::ImageLayout layout = image.layout();
  const img::Header& h = image.header();

  // What each ray does, from the reference traversal of the same image.
  RunOutcome out;
  out.result.hits.resize(rays.size());
  out.result.overflow.assign(rays.size(), 0);
  std::vector<std::vector<uint32_t>> paths(rays.size());
  TraceOptions to;
  to.format = cfg.Format();
  to.query = spec.query;
  RayCounters totals;
  for (size_t i = 0; i < rays.size(); ++i) {
    RayCounters c;
    out.result.hits[i] = TraceOne(image, rays[i], to, &c, &paths[i]);
    out.result.hit_count += out.result.hits[i].IsHit();
    totals += c;
  }
  if (reference_totals) *reference_totals = totals;
  // The simulation's own time, as the RTL harness counts it (without the
  // reference traversal, which both pay).
  const auto start = std::chrono::steady_clock::now();

  const int threads = cfg[kThreads];
  const int m = cfg.Format().m;
  const uint64_t lat_clip = static_cast<uint64_t>(m) + 8 + 11, lat_trav = 8, lat_isect = static_cast<uint64_t>(m) + 34;
  const int node_beats = 2, list_beats = 2, tri_beats = layout.TriangleBeats();
  Cache node(cfg[kNodeCacheLines], node_beats, cfg[kCacheMshrs], cfg[kCacheTargets], true);
  Cache list(cfg[kListCacheLines], list_beats, cfg[kCacheMshrs], cfg[kCacheTargets], false);
  Cache tri(cfg[kTriCacheLines], tri_beats, cfg[kCacheMshrs], cfg[kCacheTargets], false);
  MemoryModel memory(spec.memory);
  memory.LoadImage(std::vector<uint8_t>(image.data(), image.data() + image.size()));

  std::vector<Thread> th(threads);
  RrArb fetch_arb(threads), fetch2_arb(threads), exit_arb(threads), out_arb(threads), mem_arb(3);
  Pipe clip_pipe, trav_pipe, isect_pipe;
  std::deque<Job> jobs;  // rt_list_unit's FIFO: (push cycle + 1) visibility
  std::deque<std::pair<uint64_t, Job>> jobs_in;
  bool list_req_valid = false;
  Job list_job{};
  uint32_t list_k = 0;  // entries of list_job requested so far
  size_t next_ray = 0, received = 0;
  bool record_valid = false;  // rt_hit_out's register: a record leaves this cycle
  uint64_t last_record = 0;
  auto& perf = out.result.perf;
  const uint32_t* lists = image.lists();

  auto node_key = [&](uint32_t node_idx) { return (h.node_offset + layout.NodeBeatOffset(node_idx)) >> 5; };
  std::vector<uint8_t> req(threads), mreq(3);
  std::vector<int> retired;
  std::vector<State> next(threads);
  uint64_t cycle = 0;
  for (;; ++cycle) {
    // The memory's beat of this cycle, routed by {cache, register, beat}.
    MemoryResponse resp;
    int resp_cache = -1, resp_id = -1;
    if (memory.Respond(cycle, &resp)) {
      resp_cache = resp.tag >> 8;
      resp_id = resp.tag & 0xFF;
    }
    for (int t = 0; t < threads; ++t) {
      next[t] = th[t].state;
      ++out.result.thread_states[th[t].state];
    }
    bool busy = false;
    for (const Thread& t : th) busy |= t.state != kFree;
    if (busy) ++perf[kBitBusy];
    // A record leaves the core (hit_valid_o): the harness takes it.
    if (record_valid) {
      ++received;
      ++perf[kBitRayOut];
      last_record = cycle;
      record_valid = false;
      if (received == rays.size()) break;
    }
    if (cycle - last_record > spec.timeout) {
      throw std::runtime_error("fast model: no hit record for " + std::to_string(spec.timeout) + " cycles");
    }

    // Ray in: the lowest free thread takes the harness's next ray.
    int alloc = -1;
    for (int t = 0; t < threads && alloc < 0; ++t) {
      if (th[t].state == kFree) alloc = t;
    }
    if (alloc >= 0 && next_ray < rays.size()) {
      th[alloc].ray = static_cast<uint32_t>(next_ray++);
      th[alloc].cursor = 0;
      next[alloc] = kSetup;
      clip_pipe.emplace_back(cycle + lat_clip, alloc);
      ++perf[kBitRayIn];
    }
    // Setup and clip done: into FETCH, or DONE when the ray misses the box.
    while (!clip_pipe.empty() && clip_pipe.front().first == cycle) {
      const int t = clip_pipe.front().second;
      clip_pipe.pop_front();
      next[t] = paths[th[t].ray].empty() ? kDone : kFetch;
    }
    while (!trav_pipe.empty() && trav_pipe.front().first == cycle) {
      next[trav_pipe.front().second] = kFetch;
      trav_pipe.pop_front();
    }
    // Retired tests (isect_valid) this cycle.
    retired.clear();
    while (!isect_pipe.empty() && isect_pipe.front().first == cycle) {
      retired.push_back(isect_pipe.front().second);
      isect_pipe.pop_front();
    }

    // Node fetches: two arbiters, the second offered to the miss-only port.
    for (int t = 0; t < threads; ++t) req[t] = th[t].state == kFetch;
    const int f1 = fetch_arb.Pick(req);
    if (f1 >= 0) req[f1] = 0;
    const int f2 = fetch2_arb.Pick(req);
    Cache::Req n1, n2;
    if (f1 >= 0) n1 = {true, node_key(paths[th[f1].ray][th[f1].cursor]), 0, static_cast<uint64_t>(f1)};
    if (f2 >= 0) n2 = {true, node_key(paths[th[f2].ray][th[f2].cursor]), 0, static_cast<uint64_t>(f2)};
    for (Cache::Req* r : {&n1, &n2}) r->addr = r->key << 5;
    // The node response (registered) fires: the units are always ready.
    const bool node_fire = node.resp_valid();
    const int node_tag = node_fire ? static_cast<int>(node.resp_tag()) : -1;
    node.Eval(n1, n2, true);
    fetch_arb.Ack(f1);
    fetch2_arb.Ack(f2);
    if (node.accept1()) next[f1] = kWaitNode;
    if (node.accept2()) next[f2] = kWaitNode;
    if (node_fire) {
      Thread& t = th[node_tag];
      const img::Node n = image.node(paths[t.ray][t.cursor]);
      ++t.cursor;
      if (!n.IsLeaf()) {
        next[node_tag] = kTrav;
        trav_pipe.emplace_back(cycle + lat_trav, node_tag);
        ++perf[kBitTravBusy];
      } else {
        ++perf[kBitTravLeaf];
        if (n.Count() > 0) {
          next[node_tag] = kLeaf;
          t.remaining = n.Count();
          jobs_in.emplace_back(cycle + 1, Job{node_tag, n.FirstEntry(), n.Count()});
        } else {
          next[node_tag] = kExit;
        }
      }
    }

    // The list unit's request (registered), the list cache, the triangle
    // cache behind it (its request is the list cache's response).
    Cache::Req lr;
    if (list_req_valid) {
      const uint64_t addr = h.list_offset + uint64_t{list_job.first + list_k} * img::kListEntryBytes;
      lr = {true, addr >> 5, (addr >> 5) << 5, uint64_t(list_job.thread) << 32 | (list_job.first + list_k)};
    }
    Cache::Req trq;
    if (list.resp_valid()) {
      const uint64_t tag = list.resp_tag();
      const uint32_t id = lists[tag & 0xFFFFFFFFu];
      trq = {true, id, h.tri_offset + uint64_t{id} * layout.TriangleBytes(), (tag >> 32) << 32 | id};
    }
    const bool tri_fire = tri.resp_valid();
    const int tri_thread = tri_fire ? static_cast<int>(tri.resp_tag() >> 32) : -1;
    tri.Eval(trq, Cache::Req{}, true);
    list.Eval(lr, Cache::Req{}, tri.ready1());
    const bool list_fire = list_req_valid && list.ready1();
    if (list_fire) ++perf[kBitListBusy];
    if (tri_fire) {
      isect_pipe.emplace_back(cycle + lat_isect, tri_thread);
      ++perf[kBitIsectBusy];
    }

    // The memory arbiter: one beat a cycle, round robin over the caches.
    mreq[0] = node.mem_valid();
    mreq[1] = list.mem_valid();
    mreq[2] = tri.mem_valid();
    const int g = mem_arb.Pick(mreq);
    mem_arb.Ack(g);
    Cache* caches[3] = {&node, &list, &tri};
    if (g >= 0) memory.Request(caches[g]->mem_addr(), static_cast<uint16_t>(g << 8 | caches[g]->mem_id()), cycle);

    // Leaf exits and records out.
    for (int t = 0; t < threads; ++t) req[t] = th[t].state == kExit;
    const int ex = exit_arb.Pick(req);
    exit_arb.Ack(ex);
    if (ex >= 0) next[ex] = th[ex].cursor >= paths[th[ex].ray].size() ? kDone : kFetch;
    for (int t = 0; t < threads; ++t) req[t] = th[t].state == kDone;
    const int o = out_arb.Pick(req);
    out_arb.Ack(o);
    if (o >= 0) {
      next[o] = kFree;
      record_valid = true;
    }

    // LEAF: counters of tests issued and returned; EXIT once both are zero.
    for (int t = 0; t < threads; ++t) {
      if (th[t].state == kLeaf && th[t].remaining == 0 && th[t].outstanding == 0) next[t] = kExit;
    }
    if (tri_fire) {
      --th[tri_thread].remaining;
      ++th[tri_thread].outstanding;
    }
    for (int t : retired) --th[t].outstanding;

    // The clock edge.
    node.Commit(g == 0, resp_cache == 0 ? resp_id : -1);
    list.Commit(g == 1, resp_cache == 1 ? resp_id : -1);
    tri.Commit(g == 2, resp_cache == 2 ? resp_id : -1);
    // rt_list_unit: the request register and the job FIFO.
    const bool queued = !jobs.empty();
    if (list_fire) {
      ++list_k;
      if (list_k == list_job.count) list_req_valid = false;
    }
    // queued_pop: a job leaves the FIFO when req_valid_o was low this cycle.
    if (queued && !lr.valid) {
      list_job = jobs.front();
      jobs.pop_front();
      list_k = 0;
      list_req_valid = true;
    }
    while (!jobs_in.empty() && jobs_in.front().first == cycle + 1) {
      jobs.push_back(jobs_in.front().second);
      jobs_in.pop_front();
    }
    for (int t = 0; t < threads; ++t) th[t].state = next[t];
  }
  out.result.cycles = cycle + 1;
  const Cache::Events* ev[3] = {&node.events(), &list.events(), &tri.events()};
  const char* names[3] = {"node", "list", "tri"};
  for (int k = 0; k < 3; ++k) {
    const std::string n = names[k];
    perf[PerfBit(n + "_hit")] += ev[k]->hit;
    perf[PerfBit(n + "_miss")] += ev[k]->miss;
    perf[PerfBit(n + "_merge")] += ev[k]->merge;
    perf[PerfBit(n + "_wait")] += ev[k]->wait;
    perf[PerfBit(n + "_wait_inflight")] += ev[k]->wait_inflight;
    perf[PerfBit(n + "_wait_mshr")] += ev[k]->wait_mshr;
  }
  out.mem_bytes_read = memory.bytes_read();
  out.mem_requests = memory.requests();
  out.mem_max_outstanding = memory.max_outstanding();
  out.result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace kdrt::sim
