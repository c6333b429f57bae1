#include "sim/fast_model.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <deque>
#include <stdexcept>
#include <string>

#include "trace/tracer.h"

namespace kdrt::sim {
namespace {

// A set of threads (up to 256, rt_core's limit) as bit words.
class ThreadSet {
 public:
  explicit ThreadSet(int n) : n_(n), w_((n + 63) / 64, 0) {}
  void Clear() { std::fill(w_.begin(), w_.end(), 0); }
  void Set(int i) { w_[i >> 6] |= uint64_t{1} << (i & 63); }
  void Reset(int i) { w_[i >> 6] &= ~(uint64_t{1} << (i & 63)); }
  // The lowest member at or above `from`, or -1.
  int NextFrom(int from) const {
    if (from >= n_) return -1;
    size_t k = static_cast<size_t>(from) >> 6;
    uint64_t w = w_[k] & (~uint64_t{0} << (from & 63));
    for (;;) {
      if (w) return static_cast<int>(k * 64 + __builtin_ctzll(w));
      if (++k == w_.size()) return -1;
      w = w_[k];
    }
  }
  int Lowest() const { return NextFrom(0); }

 private:
  int n_;
  std::vector<uint64_t> w_;
};

// rt_rr_arb: the first requester after the last grant; the pointer moves on
// every grant when ack is set.
class RrArb {
 public:
  explicit RrArb(int n) : last_(n - 1) {}
  int Pick(const ThreadSet& req) const {
    const int after = req.NextFrom(last_ + 1);
    return after >= 0 ? after : req.NextFrom(0);
  }
  void Ack(int idx) {
    if (idx >= 0) last_ = idx;
  }

 private:
  int last_;
};

// rt_cache at the level of its registers (the header comment of
// rtl/rt_cache.sv): Eval() is the combinational part of one cycle from the
// registered state, Commit() the clock edge. Miss registers are tracked as
// bit masks (rt_core allows at most 64): valid, beats left to send, line in.
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
      : line_mask_(static_cast<uint64_t>(lines) - 1), beats_(line_beats), targets_(targets), miss_port_(miss_port),
        all_mshrs_(mshrs >= 64 ? ~uint64_t{0} : (uint64_t{1} << mshrs) - 1), line_valid_(lines, 0),
        line_key_(lines, 0), mshr_(mshrs) {}

  // Registered outputs, valid before Eval().
  bool resp_valid() const { return hit_valid_ || del_valid_; }
  uint64_t resp_tag() const { return del_valid_ ? del_tag_ : hit_tag_; }
  bool mem_valid() const { return held_ || unsent_ != 0; }
  uint64_t mem_addr() const { return mshr_[SendIdx()].addr + 16u * mshr_[SendIdx()].sent; }
  int mem_id() const { return SendIdx() * 4 + static_cast<int>(mshr_[SendIdx()].sent); }

  // Nothing can happen here until a memory beat arrives or a request comes:
  // no response shown, no beat to send, no line ready to answer.
  bool Quiet() const { return !hit_valid_ && !del_valid_ && !held_ && unsent_ == 0 && done_ == 0; }

  void Eval(const Req& r1, const Req& r2, bool resp_ready) {
    c_.out_take = c_.deliver = c_.ready1 = c_.ready2 = c_.accept = c_.accept2 = false;
    c_.hit = c_.m_take = false;
    c_.send_valid = mem_valid();
    c_.send_idx = c_.send_valid ? SendIdx() : -1;
    if (!r1.valid && !r2.valid && valid_ == 0 && !hit_valid_ && !del_valid_) return;
    const uint64_t free_mask = all_mshrs_ & ~valid_;
    const int free_idx = free_mask ? __builtin_ctzll(free_mask) : -1;
    const int done_idx = done_ ? __builtin_ctzll(done_) : -1;
    int join_idx = -1, join2_idx = -1;
    bool any_match = false, any_match2 = false;
    for (uint64_t v = valid_; v; v &= v - 1) {
      const int m = __builtin_ctzll(v);
      const Mshr& s = mshr_[m];
      const bool joinable = !((done_ >> m) & 1) && s.cnt < targets_;
      if (r1.valid && s.key == r1.key) {
        any_match = true;
        if (joinable && join_idx < 0) join_idx = m;
      }
      if (r2.valid && s.key == r2.key) {
        any_match2 = true;
        if (joinable && join2_idx < 0) join2_idx = m;
      }
    }
    const bool lookup_hit = r1.valid && Present(r1.key), lookup2_hit = r2.valid && Present(r2.key);
    c_.out_take = resp_valid() && resp_ready;
    const bool hit_free = !hit_valid_ || (c_.out_take && !del_valid_);
    const bool del_free = !del_valid_ || c_.out_take;
    c_.deliver = done_idx >= 0 && del_free && !(hit_valid_ && !del_valid_ && !resp_ready);
    c_.done_idx = done_idx;
    if (r1.valid) {
      const bool hit_ok = lookup_hit && hit_free;
      const bool join_ok = !lookup_hit && join_idx >= 0;
      const bool alloc_ok = !lookup_hit && !any_match && free_idx >= 0;
      c_.ready1 = hit_ok || join_ok || alloc_ok;
      c_.accept = c_.ready1;
      if (!c_.ready1) ++ev_.wait;
      if (!lookup_hit && any_match && join_idx < 0) ++ev_.wait_inflight;
      if (!lookup_hit && !any_match && free_idx < 0) ++ev_.wait_mshr;
      c_.hit = c_.accept && lookup_hit;
      if (c_.accept && !lookup_hit) {
        c_.m_take = true;
        c_.m_join = join_ok;
        c_.m_join_idx = join_idx;
        c_.m = r1;
      }
    }
    if (r2.valid && miss_port_ && !c_.m_take) {
      const bool join2_ok = !lookup2_hit && join2_idx >= 0;
      const bool alloc2_ok = !lookup2_hit && !any_match2 && free_idx >= 0;
      c_.ready2 = join2_ok || alloc2_ok;
      c_.accept2 = c_.ready2;
      if (c_.accept2) {
        c_.m_take = true;
        c_.m_join = join2_ok;
        c_.m_join_idx = join2_idx;
        c_.m = r2;
      }
    }
    c_.free_idx = free_idx;
    if (c_.hit) {
      ++ev_.hit;
      c_.hit_tag = r1.tag;
    }
    if (c_.m_take) ++ev_.miss;
    if (c_.m_take && c_.m_join) ++ev_.merge;
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
      hit_tag_ = c_.hit_tag;
    }
    if (c_.m_take) {
      if (c_.m_join) {
        Mshr& s = mshr_[c_.m_join_idx];
        s.tags.push_back(c_.m.tag);
        ++s.cnt;
      } else {
        const int f = c_.free_idx;
        Mshr& s = mshr_[f];
        s.key = c_.m.key;
        s.addr = c_.m.addr;
        s.sent = s.got = 0;
        s.cnt = 1;
        s.out = 0;
        s.tags.assign(1, c_.m.tag);
        valid_ |= uint64_t{1} << f;
        unsent_ |= uint64_t{1} << f;
      }
    }
    if (mem_taken) {
      Mshr& s = mshr_[c_.send_idx];
      if (++s.sent == static_cast<uint32_t>(beats_)) unsent_ &= ~(uint64_t{1} << c_.send_idx);
    }
    if (resp_id >= 0) {
      const int m = resp_id / 4;
      Mshr& s = mshr_[m];
      s.got |= 1u << (resp_id % 4);
      if (s.got == (1u << beats_) - 1) done_ |= uint64_t{1} << m;
    }
    if (c_.deliver) {
      const int d = c_.done_idx;
      Mshr& s = mshr_[d];
      del_tag_ = s.tags[s.out];
      ++s.out;
      const size_t line = s.key & line_mask_;
      line_valid_[line] = 1;
      line_key_[line] = s.key;
      del_valid_ = true;
      if (s.out == s.cnt) {
        valid_ &= ~(uint64_t{1} << d);
        done_ &= ~(uint64_t{1} << d);
      }
    }
    held_ = c_.send_valid && !mem_taken;
    held_idx_ = c_.send_idx;
  }

  const Events& events() const { return ev_; }

 private:
  struct Mshr {
    uint64_t key = 0, addr = 0;
    uint32_t sent = 0, got = 0;
    int cnt = 0, out = 0;
    std::vector<uint64_t> tags;
  };
  struct Comb {
    Req m;
    uint64_t hit_tag = 0;
    bool out_take = false, deliver = false, ready1 = false, ready2 = false, accept = false, accept2 = false;
    bool hit = false, m_take = false, m_join = false, send_valid = false;
    int done_idx = -1, m_join_idx = -1, free_idx = -1, send_idx = -1;
  };

  bool Present(uint64_t key) const {
    const size_t line = key & line_mask_;
    return line_valid_[line] && line_key_[line] == key;
  }
  int SendIdx() const { return held_ ? held_idx_ : __builtin_ctzll(unsent_); }

  uint64_t line_mask_;
  int beats_, targets_;
  bool miss_port_;
  uint64_t all_mshrs_;
  std::vector<uint8_t> line_valid_;
  std::vector<uint64_t> line_key_;
  std::vector<Mshr> mshr_;
  uint64_t valid_ = 0, unsent_ = 0, done_ = 0;  // miss registers: in use, beats to send, line in
  bool hit_valid_ = false, del_valid_ = false, held_ = false;
  uint64_t hit_tag_ = 0, del_tag_ = 0;
  int held_idx_ = 0;
  Comb c_;
  Events ev_;
};

constexpr int kBitRayIn = PerfBit("ray_in"), kBitRayOut = PerfBit("ray_out"), kBitBusy = PerfBit("busy"),
              kBitTravBusy = PerfBit("trav_busy"), kBitTravLeaf = PerfBit("trav_leaf"),
              kBitListBusy = PerfBit("list_busy"), kBitIsectBusy = PerfBit("isect_busy");

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
  // Every node a path visits, decoded once: inner (kInner) or a leaf's count
  // and first list entry.
  constexpr uint32_t kInner = 0xFFFFFFFFu;
  uint32_t max_node = 0;
  for (const auto& p : paths) {
    for (uint32_t n : p) max_node = std::max(max_node, n);
  }
  std::vector<uint32_t> node_count(max_node + 1u, kInner), node_first(max_node + 1u, 0);
  std::vector<uint8_t> decoded(max_node + 1u, 0);
  for (const auto& p : paths) {
    for (uint32_t i : p) {
      if (decoded[i]) continue;
      decoded[i] = 1;
      const img::Node n = image.node(i);
      if (n.IsLeaf()) {
        node_count[i] = n.Count();
        node_first[i] = n.FirstEntry();
      }
    }
  }
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
  ThreadSet mreq(3);
  std::vector<ThreadSet> in_set(8, ThreadSet(threads));  // the threads in each state
  for (int t = 0; t < threads; ++t) in_set[kFree].Set(t);
  // The state changes of this cycle, applied at the clock edge (one per thread at most).
  std::vector<std::pair<int, State>> moves;
  const auto Move = [&moves](int t, State to_state) { moves.emplace_back(t, to_state); };
  std::array<uint64_t, 8> in_state{};  // threads per state
  in_state[kFree] = static_cast<uint64_t>(threads);
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
  std::vector<int> retired, leaf_done;
  uint64_t cycle = 0;
  for (;; ++cycle) {
    // Cycles in which nothing can change (every thread waits on a pipeline or
    // the memory, no cache has anything to show or send) are skipped to the
    // next event; their thread-state and busy counts still accrue.
    // LEAF: EXIT once the tests issued and returned (registered counts) are
    // both zero; skipped cycles change no thread, so this holds after a skip.
    leaf_done.clear();
    for (int t = in_set[kLeaf].Lowest(); t >= 0; t = in_set[kLeaf].NextFrom(t + 1)) {
      if (th[t].remaining == 0 && th[t].outstanding == 0) leaf_done.push_back(t);
    }
    const bool quiet = !record_valid && in_state[kFetch] == 0 && in_state[kExit] == 0 && in_state[kDone] == 0 &&
                       !(in_state[kFree] > 0 && next_ray < rays.size()) && leaf_done.empty() && !list_req_valid &&
                       jobs.empty() && jobs_in.empty() && node.Quiet() && list.Quiet() && tri.Quiet();
    if (quiet) {
      uint64_t next_event = memory.next_ready_cycle();
      for (const Pipe* pipe : {&clip_pipe, &trav_pipe, &isect_pipe}) {
        if (!pipe->empty()) next_event = std::min(next_event, pipe->front().first);
      }
      if (next_event != UINT64_MAX && next_event > cycle) {
        const uint64_t skip = next_event - cycle;
        for (int k = 0; k < 8; ++k) out.result.thread_states[k] += in_state[k] * skip;
        if (in_state[kFree] != static_cast<uint64_t>(threads)) perf[kBitBusy] += skip;
        cycle = next_event;
      }
    }
    // The memory's beat of this cycle, routed by {cache, register, beat}.
    MemoryResponse resp;
    int resp_cache = -1, resp_id = -1;
    if (memory.Respond(cycle, &resp)) {
      resp_cache = resp.tag >> 8;
      resp_id = resp.tag & 0xFF;
    }
    // The registered states, as sets (kept up to date by the moves below).
    const int alloc = in_set[kFree].Lowest();
    for (int t : leaf_done) Move(t, kExit);
    for (int k = 0; k < 8; ++k) out.result.thread_states[k] += in_state[k];
    if (in_state[kFree] != static_cast<uint64_t>(threads)) ++perf[kBitBusy];
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
    if (alloc >= 0 && next_ray < rays.size()) {
      th[alloc].ray = static_cast<uint32_t>(next_ray++);
      th[alloc].cursor = 0;
      Move(alloc, kSetup);
      clip_pipe.emplace_back(cycle + lat_clip, alloc);
      ++perf[kBitRayIn];
    }
    // Setup and clip done: into FETCH, or DONE when the ray misses the box.
    while (!clip_pipe.empty() && clip_pipe.front().first == cycle) {
      const int t = clip_pipe.front().second;
      clip_pipe.pop_front();
      Move(t, paths[th[t].ray].empty() ? kDone : kFetch);
    }
    while (!trav_pipe.empty() && trav_pipe.front().first == cycle) {
      Move(trav_pipe.front().second, kFetch);
      trav_pipe.pop_front();
    }
    // Retired tests (isect_valid) this cycle.
    retired.clear();
    while (!isect_pipe.empty() && isect_pipe.front().first == cycle) {
      retired.push_back(isect_pipe.front().second);
      isect_pipe.pop_front();
    }

    // Node fetches: two arbiters, the second offered to the miss-only port.
    ThreadSet& fetching = in_set[kFetch];
    const int f1 = fetch_arb.Pick(fetching);
    if (f1 >= 0) fetching.Reset(f1);
    const int f2 = fetch2_arb.Pick(fetching);
    if (f1 >= 0) fetching.Set(f1);
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
    if (node.accept1()) Move(f1, kWaitNode);
    if (node.accept2()) Move(f2, kWaitNode);
    if (node_fire) {
      Thread& t = th[node_tag];
      const uint32_t i = paths[t.ray][t.cursor];
      ++t.cursor;
      if (node_count[i] == kInner) {
        Move(node_tag, kTrav);
        trav_pipe.emplace_back(cycle + lat_trav, node_tag);
        ++perf[kBitTravBusy];
      } else {
        ++perf[kBitTravLeaf];
        if (node_count[i] > 0) {
          Move(node_tag, kLeaf);
          t.remaining = node_count[i];
          jobs_in.emplace_back(cycle + 1, Job{node_tag, node_first[i], node_count[i]});
        } else {
          Move(node_tag, kExit);
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
    mreq.Clear();
    if (node.mem_valid()) mreq.Set(0);
    if (list.mem_valid()) mreq.Set(1);
    if (tri.mem_valid()) mreq.Set(2);
    const int g = mem_arb.Pick(mreq);
    mem_arb.Ack(g);
    Cache* caches[3] = {&node, &list, &tri};
    if (g >= 0) memory.Request(caches[g]->mem_addr(), static_cast<uint16_t>(g << 8 | caches[g]->mem_id()), cycle);

    // Leaf exits and records out.
    const int ex = exit_arb.Pick(in_set[kExit]);
    exit_arb.Ack(ex);
    if (ex >= 0) Move(ex, th[ex].cursor >= paths[th[ex].ray].size() ? kDone : kFetch);
    const int o = out_arb.Pick(in_set[kDone]);
    out_arb.Ack(o);
    if (o >= 0) {
      Move(o, kFree);
      record_valid = true;
    }

    // LEAF: the counters of tests issued and returned.
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
    for (const auto& [t, to_state] : moves) {
      in_set[th[t].state].Reset(t);
      in_set[to_state].Set(t);
      --in_state[th[t].state];
      ++in_state[to_state];
      th[t].state = to_state;
    }
    moves.clear();
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
