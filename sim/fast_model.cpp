#include "sim/fast_model.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/ring.h"
#include "trace/tracer.h"

namespace kdrt::sim {
namespace {

// A set of threads (up to 256, rt_core's limit) as bit words, held inline:
// the arbiters search these every cycle.
class ThreadSet {
 public:
  ThreadSet() = default;
  explicit ThreadSet(int n) : words_((n + 63) / 64) {}
  void Set(int i) { w_[i >> 6] |= uint64_t{1} << (i & 63); }
  void Reset(int i) { w_[i >> 6] &= ~(uint64_t{1} << (i & 63)); }
  // The lowest member at or above `from`, or -1.
  int NextFrom(int from) const {
    int k = from >> 6;
    if (k >= words_) return -1;
    uint64_t w = w_[k] & (~uint64_t{0} << (from & 63));
    for (;;) {
      if (w) return k * 64 + __builtin_ctzll(w);
      if (++k == words_) return -1;
      w = w_[k];
    }
  }
  int Lowest() const { return NextFrom(0); }

 private:
  int words_ = 4;
  std::array<uint64_t, 4> w_{};
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
// bit masks (rt_core allows at most 64): valid, beats left to send, line in,
// no room for another target.
class Cache {
 public:
  struct Req {
    bool valid = false;
    uint64_t key = 0, addr = 0, tag = 0;
  };
  struct Events {
    uint64_t hit = 0, miss = 0, merge = 0, wait = 0, wait_inflight = 0, wait_mshr = 0;
  };

  Cache(int lines, int ways, int line_beats, int mshrs, int targets, bool miss_port)
      : set_mask_(static_cast<uint64_t>(lines / ways) - 1), ways_(ways), way_bits_(__builtin_ctz(ways)),
        beats_(line_beats), targets_(targets), mshrs_(mshrs), miss_port_(miss_port),
        all_mshrs_(mshrs >= 64 ? ~uint64_t{0} : (uint64_t{1} << mshrs) - 1), lines_(lines, kNoLine),
        plru_(ways > 1 ? lines / ways : 0, 0), mshr_(mshrs), keys_(mshrs, 0),
        tags_(static_cast<size_t>(mshrs) * targets) {
    // The tree pseudo-LRU as tables: what a touch of each way clears and
    // sets, and the victim of each tree state (at most 2^15 for 16 ways).
    touch_clear_.assign(ways, 0);
    touch_set_.assign(ways, 0);
    for (int way = 0; way < ways; ++way) {
      for (int l = 0; l < way_bits_; ++l) {
        const int node = (1 << l) - 1 + (way >> (way_bits_ - l));
        const uint32_t bit = (static_cast<uint32_t>(way) >> (way_bits_ - 1 - l)) & 1u;
        touch_clear_[way] |= 1u << node;
        touch_set_[way] |= (bit ^ 1u) << node;
      }
    }
    victim_.assign(ways > 1 ? size_t{1} << (ways - 1) : 0, 0);
    for (size_t tree = 0; tree < victim_.size(); ++tree) {
      int way = 0;
      for (int l = 0; l < way_bits_; ++l) {
        const int node = (1 << l) - 1 + (way >> (way_bits_ - l));
        way |= static_cast<int>((tree >> node) & 1u) << (way_bits_ - 1 - l);
      }
      victim_[tree] = static_cast<uint8_t>(way);
    }
  }

  // Registered outputs, valid before Eval().
  bool resp_valid() const { return hit_valid_ | del_valid_; }
  uint64_t resp_tag() const { return del_valid_ ? del_tag_ : hit_tag_; }
  bool mem_valid() const { return held_ | (unsent_ != 0); }
  uint64_t mem_addr() const { return mshr_[SendIdx()].addr + 16u * mshr_[SendIdx()].sent; }
  int mem_id() const { return SendIdx() * 4 + static_cast<int>(mshr_[SendIdx()].sent); }

  // Nothing can happen here until a memory beat arrives or a request comes:
  // no response shown, no beat to send, no line ready to answer.
  bool Quiet() const { return !(hit_valid_ | del_valid_ | held_ | ((unsent_ | done_) != 0)); }
  // Waits for memory (rt_mem_system's mem_wait_o): a beat to send or a miss
  // register in use.
  bool MemWait() const { return held_ | ((unsent_ | valid_) != 0); }

  // `r2` is looked at only on the miss-only port (miss_port).
  void Eval(const Req& r1, const Req& r2, bool resp_ready) {
    c_.out_take = resp_valid() & resp_ready;
    // A filled line goes out through the delivery register when it is free
    // (or being emptied) and no stalled hit keeps the output.
    c_.deliver = (done_ != 0) & (!del_valid_ | c_.out_take) & !(hit_valid_ & !del_valid_ & !resp_ready);
    c_.ready1 = c_.ready2 = c_.hit = c_.m_take = false;
    // Most cycles of a cache bring no request: nothing to look up or match.
    if (r1.valid | (r2.valid & miss_port_)) EvalRequests(r1, r2);
  }
  // Requests taken this cycle (the caches are always ready when they take).
  bool accept1() const { return c_.ready1; }
  bool accept2() const { return c_.ready2; }

  // The clock edge: `mem_taken` (the arbiter took this cache's beat),
  // `resp_id` (>= 0: the memory's beat for {register, beat}).
  void Commit(bool mem_taken, int resp_id) {
    // Nothing to register: no response taken or made, no miss taken, no
    // beat offered (so none taken or held) and none come in.
    if (!(c_.out_take | c_.deliver | c_.hit | c_.m_take | mem_valid() | (resp_id >= 0))) return;
    CommitBusy(mem_taken, resp_id);
  }

  const Events& events() const { return ev_; }

 private:
  struct Mshr {
    uint64_t addr = 0;
    uint32_t sent = 0, got = 0;
    int cnt = 0, out = 0;
  };
  // An empty line's key: no request's (keys are line addresses or triangle
  // ids of at most 32 bits).
  static constexpr uint64_t kNoLine = ~uint64_t{0};
  // What Eval() decided, for Commit().
  struct Comb {
    Req m;
    uint64_t hit_tag = 0;
    bool out_take = false, deliver = false, ready1 = false, ready2 = false;
    bool hit = false, m_take = false, m_join = false;
    int m_join_idx = -1, free_idx = -1;
    int hit_way = 0;
    uint64_t hit_set = 0;
  };

  // The miss registers in use for `key`: those of its bucket whose key it is.
  uint64_t Matches(uint64_t key) const {
    uint64_t mask = 0;
    for (uint64_t v = bucket_[Bucket(key)] & valid_; v; v &= v - 1) {
      const int m = __builtin_ctzll(v);
      mask |= static_cast<uint64_t>(keys_[m] == key) << m;
    }
    return mask;
  }
  static size_t Bucket(uint64_t key) { return (key ^ (key >> 6)) & (kBuckets - 1); }

  void EvalRequests(const Req& r1, const Req& r2) {
    const bool use_r2 = r2.valid && miss_port_;
    const uint64_t free_mask = all_mshrs_ & ~valid_;
    const int free_idx = free_mask ? __builtin_ctzll(free_mask) : -1;
    // A request joins the lowest register of its line still taking targets
    // (not filled, not full).
    const uint64_t joinable = valid_ & ~done_ & ~full_;
    if (r1.valid) {
      // A present line is a hit whatever the miss registers hold.
      const int way = FindWay(r1.key);
      const bool lookup_hit = way >= 0;
      const uint64_t match = lookup_hit ? 0 : Matches(r1.key);
      const int join_idx = (match & joinable) ? __builtin_ctzll(match & joinable) : -1;
      const bool hit_free = !hit_valid_ || (c_.out_take && !del_valid_);
      const bool hit_ok = lookup_hit && hit_free;
      const bool join_ok = !lookup_hit && join_idx >= 0;
      const bool alloc_ok = !lookup_hit && !match && free_idx >= 0;
      c_.ready1 = hit_ok || join_ok || alloc_ok;
      if (!c_.ready1) ++ev_.wait;
      if (!lookup_hit && match && join_idx < 0) ++ev_.wait_inflight;
      if (!lookup_hit && !match && free_idx < 0) ++ev_.wait_mshr;
      c_.hit = c_.ready1 && lookup_hit;
      c_.hit_way = way;
      c_.hit_set = r1.key & set_mask_;
      if (c_.ready1 && !lookup_hit) {
        c_.m_take = true;
        c_.m_join = join_ok;
        c_.m_join_idx = join_idx;
        c_.m = r1;
      }
    }
    if (use_r2 && !c_.m_take) {
      const bool lookup2_hit = FindWay(r2.key) >= 0;
      const uint64_t match2 = lookup2_hit ? 0 : Matches(r2.key);
      const int join2_idx = (match2 & joinable) ? __builtin_ctzll(match2 & joinable) : -1;
      const bool join2_ok = !lookup2_hit && join2_idx >= 0;
      const bool alloc2_ok = !lookup2_hit && !match2 && free_idx >= 0;
      c_.ready2 = join2_ok || alloc2_ok;
      if (c_.ready2) {
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

  void CommitBusy(bool mem_taken, int resp_id) {
    // The registered state this cycle ran on, before this edge changes it.
    const bool send_valid = mem_valid();
    const int send_idx = send_valid ? SendIdx() : -1;
    const int done_idx = done_ ? __builtin_ctzll(done_) : -1;
    const int fill_way = c_.deliver ? FillWay(keys_[done_idx]) : 0;
    if (c_.out_take && del_valid_) {
      del_valid_ = false;
    } else if (c_.out_take) {
      hit_valid_ = false;
    }
    if (c_.hit) {
      hit_valid_ = true;
      hit_tag_ = c_.hit_tag;
      if (ways_ > 1) Touch(c_.hit_set, c_.hit_way);
    }
    if (c_.m_take) {
      const int idx = c_.m_join ? c_.m_join_idx : c_.free_idx;
      Mshr& s = mshr_[idx];
      if (!c_.m_join) {
        bucket_[Bucket(keys_[idx])] &= ~(uint64_t{1} << idx);
        keys_[idx] = c_.m.key;
        bucket_[Bucket(keys_[idx])] |= uint64_t{1} << idx;
        s.addr = c_.m.addr;
        s.sent = s.got = 0;
        s.cnt = 0;
        s.out = 0;
        valid_ |= uint64_t{1} << idx;
        unsent_ |= uint64_t{1} << idx;
      }
      tags_[static_cast<size_t>(idx) * targets_ + s.cnt] = c_.m.tag;
      if (++s.cnt == targets_) full_ |= uint64_t{1} << idx;
    }
    if (mem_taken) {
      Mshr& s = mshr_[send_idx];
      if (++s.sent == static_cast<uint32_t>(beats_)) unsent_ &= ~(uint64_t{1} << send_idx);
    }
    if (resp_id >= 0) {
      const int m = resp_id / 4;
      Mshr& s = mshr_[m];
      s.got |= 1u << (resp_id % 4);
      if (s.got == (1u << beats_) - 1) done_ |= uint64_t{1} << m;
    }
    if (c_.deliver) {
      const int d = done_idx;
      Mshr& s = mshr_[d];
      del_tag_ = tags_[static_cast<size_t>(d) * targets_ + s.out];
      ++s.out;
      const uint64_t set = keys_[d] & set_mask_;
      lines_[set * ways_ + fill_way] = keys_[d];
      if (ways_ > 1) Touch(set, fill_way);
      del_valid_ = true;
      if (s.out == s.cnt) {
        const uint64_t keep = ~(uint64_t{1} << d);
        valid_ &= keep;
        done_ &= keep;
        full_ &= keep;
      }
    }
    held_ = send_valid && !mem_taken;
    held_idx_ = send_idx;
  }

  // The way of the key's set that holds its line, or -1. Line set * ways + w
  // is way w of the set (rtl/rt_cache.sv).
  int FindWay(uint64_t key) const {
    if (ways_ == 1) return lines_[key & set_mask_] == key ? 0 : -1;
    const uint64_t* set = &lines_[(key & set_mask_) * ways_];
    for (int w = 0; w < ways_; ++w) {
      if (set[w] == key) return w;
    }
    return -1;
  }
  // The tree pseudo-LRU of a set: node n at level l is bit 2^l - 1 + n, and
  // a bit of 0 puts the victim in the lower half. A touch points every node
  // on the way's path away from it (the tables built in the constructor).
  void Touch(uint64_t set, int way) { plru_[set] = (plru_[set] & ~touch_clear_[way]) | touch_set_[way]; }
  int Victim(uint64_t set) const { return ways_ > 1 ? victim_[plru_[set]] : 0; }
  // Where a completed miss writes its line: the way that holds it already,
  // else the lowest invalid way, else the victim (of the registered state).
  int FillWay(uint64_t key) const {
    const uint64_t set = key & set_mask_;
    const uint64_t* lines = &lines_[set * ways_];
    int way = FindWay(key);
    if (way >= 0) return way;
    for (int w = ways_ - 1; w >= 0; --w) {
      if (lines[w] == kNoLine) way = w;
    }
    return way >= 0 ? way : Victim(set);
  }
  int SendIdx() const { return held_ ? held_idx_ : __builtin_ctzll(unsent_); }

  uint64_t set_mask_;
  int ways_, way_bits_;
  int beats_, targets_, mshrs_;
  bool miss_port_;
  uint64_t all_mshrs_;
  std::vector<uint64_t> lines_;  // each line's key, or kNoLine
  std::vector<uint32_t> plru_;   // a set's tree bits (ways > 1)
  std::vector<uint32_t> touch_clear_, touch_set_;
  std::vector<uint8_t> victim_;
  // The miss registers whose key falls in each bucket (a register is in the
  // bucket of the last key it took), so a lookup compares few keys.
  static constexpr size_t kBuckets = 64;
  std::array<uint64_t, kBuckets> bucket_{};
  std::vector<Mshr> mshr_;
  std::vector<uint64_t> keys_;  // each miss register's line
  std::vector<uint64_t> tags_;  // the merged requests of miss register m: [m * targets_, + cnt)
  // Miss registers: in use, beats to send, line in, targets full.
  uint64_t valid_ = 0, unsent_ = 0, done_ = 0, full_ = 0;
  bool hit_valid_ = false, del_valid_ = false, held_ = false;
  uint64_t hit_tag_ = 0, del_tag_ = 0;
  int held_idx_ = 0;
  Comb c_;
  Events ev_;
};

constexpr int kBitRayIn = PerfBit("ray_in"), kBitRayOut = PerfBit("ray_out"), kBitBusy = PerfBit("busy"),
              kBitTravBusy = PerfBit("trav_busy"), kBitTravLeaf = PerfBit("trav_leaf"),
              kBitListBusy = PerfBit("list_busy"), kBitIsectBusy = PerfBit("isect_busy"),
              kBitStallMem = PerfBit("stall_mem"), kBitStallStack = PerfBit("stall_stack"),
              kBitOverflow = PerfBit("overflow");

enum State : uint8_t { kFree, kSetup, kFetch, kWaitNode, kTrav, kLeaf, kExit, kDone };

// A step of a ray's path: a node it fetches, decoded once, with its node
// cache key and, for a leaf, its list entries (count kInner: an inner node).
constexpr uint32_t kInner = 0xFFFFFFFFu;
struct Step {
  uint32_t key = 0;  // the node's 32-byte line (AddrWidth <= 32)
  uint32_t count = kInner, first = 0;
};

struct Thread {
  State state = kFree;
  const Step* next = nullptr;  // the path step fetched next (or being fetched)
  const Step* end = nullptr;   // the end of the ray's path
  uint32_t remaining = 0, outstanding = 0;
};

struct Job {
  int thread;
  uint32_t first, count;
};

// The memory arbiter (rt_rr_arb over the node, list and triangle caches):
// the grant for [last grant][request bits], the first requester after the
// last grant, or -1.
constexpr int8_t kMemPick[3][8] = {
    {-1, 0, 1, 1, 2, 2, 1, 1}, {-1, 0, 1, 0, 2, 2, 2, 2}, {-1, 0, 1, 0, 2, 0, 1, 0}};

// A fixed-latency pipeline's result: the cycle it comes out and its thread.
struct Stage {
  uint64_t cycle;
  int thread;
};

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
  to.trav_format = cfg.TravFormat();
  to.query = spec.query;
  // A path that ends on an inner node is a ray whose push met a full stack
  // (StackDepth below the tree's depth, --allow-overflow): its thread goes
  // from TRAV to DONE, and its record is the hit it had (rt_thread_fsm).
  to.stack_depth = cfg[kStackDepth];
  RayCounters totals;
  for (size_t i = 0; i < rays.size(); ++i) {
    RayCounters c;
    out.result.hits[i] = TraceOne(image, rays[i], to, &c, &paths[i]);
    out.result.hit_count += out.result.hits[i].IsHit();
    out.result.overflow[i] = c.overflows > 0;
    out.result.overflows += c.overflows > 0;
    totals += c;
  }
  if (reference_totals) *reference_totals = totals;
  // The paths decoded into steps, one array in ray order: the rays in flight
  // are neighbours in it (a table by node index costs a cache miss a fetch).
  uint32_t max_node = 0;
  size_t n_steps = 0;
  for (const auto& p : paths) {
    for (uint32_t n : p) max_node = std::max(max_node, n);
    n_steps += p.size();
  }
  std::vector<Step> nodes(max_node + 1u);
  std::vector<uint8_t> decoded(max_node + 1u, 0);
  std::vector<Step> steps;
  steps.reserve(n_steps);
  std::vector<size_t> path_begin(rays.size() + 1, 0);
  for (size_t r = 0; r < rays.size(); ++r) {
    for (uint32_t i : paths[r]) {
      if (!decoded[i]) {
        decoded[i] = 1;
        nodes[i].key = static_cast<uint32_t>((h.node_offset + layout.NodeBeatOffset(i)) >> 5);
        const img::Node n = image.node(i);
        if (n.IsLeaf()) {
          nodes[i].count = n.Count();
          nodes[i].first = n.FirstEntry();
        }
      }
      steps.push_back(nodes[i]);
    }
    path_begin[r + 1] = steps.size();
    std::vector<uint32_t>().swap(paths[r]);
  }
  // The memory's timing only: the model reads no data, so the memory holds
  // no image (a beat reads zeros, and costs no cache miss on the host). The
  // image must fit all the same, as for the RTL.
  MemoryModel memory(spec.memory);
  memory.CheckFits(image.size());
  // The simulation's own time, as the RTL harness counts it (without the
  // reference traversal, which both pay).
  const auto start = std::chrono::steady_clock::now();

  const int threads = cfg[kThreads];
  const int m = cfg.Format().m;
  // Ray setup and clip (rt_ray_setup M + 8, rt_clip_unit 11) and the
  // traversal step (8); a wider traversal (TravE, TravM) has its reciprocal
  // divider (3 + TravM + 4) and one more stage in clip and traversal step
  // (rounding the cell ends outwards into the core's format).
  const bool mixed = cfg.TravFormat() != cfg.Format();
  const int setup = std::max(m + 8, mixed ? cfg.TravFormat().m + 7 : 0);
  const uint64_t lat_clip = static_cast<uint64_t>(setup) + 11 + (mixed ? 1 : 0);
  const uint64_t lat_trav = 8 + (mixed ? 1 : 0);
  const uint64_t lat_isect = static_cast<uint64_t>(m) + 34;
  const int node_beats = 2, list_beats = 2, tri_beats = layout.TriangleLineBeats();
  const int ways = cfg[kCacheWays];
  Cache node(cfg[kNodeCacheLines], ways, node_beats, cfg[kCacheMshrs], cfg[kCacheTargets], true);
  Cache list(cfg[kListCacheLines], ways, list_beats, cfg[kCacheMshrs], cfg[kCacheTargets], false);
  Cache tri(cfg[kTriCacheLines], ways, tri_beats, cfg[kCacheMshrs], cfg[kCacheTargets], false);
  Cache* caches[3] = {&node, &list, &tri};

  std::vector<Thread> th(threads);
  RrArb fetch_arb(threads), fetch2_arb(threads), exit_arb(threads), out_arb(threads);
  int mem_last = 2;  // the memory arbiter's last grant (rt_rr_arb over the three caches)
  // The threads in each state (the ray input and the arbiters pick from FREE,
  // FETCH, EXIT and DONE), kept up to date by the moves below.
  std::array<ThreadSet, 8> in_set;
  in_set.fill(ThreadSet(threads));
  for (int t = 0; t < threads; ++t) in_set[kFree].Set(t);
  std::array<uint64_t, 8> in_state{};  // threads per state
  in_state[kFree] = static_cast<uint64_t>(threads);
  // The state changes of this cycle, applied at the clock edge (one per thread
  // at most).
  std::vector<std::pair<int, State>> moves(static_cast<size_t>(threads));
  size_t n_moves = 0;
  const auto Move = [&moves, &n_moves](int t, State to_state) { moves[n_moves++] = {t, to_state}; };
  // The thread-state and busy counts accrue at the clock edges that change
  // them: a thread's cycles in a state when it leaves it, the busy cycles
  // when the core goes idle (and both at the end).
  std::vector<uint64_t> since(static_cast<size_t>(threads), 0);  // in th[t].state since this cycle
  uint64_t busy_since = 0;
  auto& perf = out.result.perf;
  const auto busy = [&in_state, threads] { return in_state[kFree] != static_cast<uint64_t>(threads); };
  // The pipelines take at most one thread a cycle: setup/clip and traversal
  // hold each thread at most once, intersection at most one test a cycle of
  // its latency.
  Ring<Stage> clip_pipe(threads, true), trav_pipe(threads, true), isect_pipe(lat_isect + 1, true);
  Ring<Job> jobs(threads, true);  // rt_list_unit's FIFO (a thread has one job at most)
  bool list_req_valid = false;
  Job list_job{};
  uint32_t list_k = 0;  // entries of list_job requested so far
  size_t next_ray = 0, received = 0;
  bool record_valid = false;  // rt_hit_out's register: a record leaves this cycle
  uint64_t last_record = 0;
  const uint32_t* lists = image.lists();
  // The triangle cache's lines hold P records (img::ImageLayout): a line is
  // named by id / P.
  const uint32_t tri_per_line = static_cast<uint32_t>(layout.TrianglesPerLine());
  const uint64_t tri_line_bytes = layout.TriangleLineBytes();

  // The memory is asked for its beat only in the cycles it may have one ready
  // when its token bucket comes out the same however the refill is split:
  // with a bandwidth of whole 2^-20 bytes every sum is exact (and a sum too
  // large to be exact is over the bucket's size anyway).
  const double bw_units = std::ldexp(spec.memory.bytes_per_cycle, 20);
  const bool lazy_memory = bw_units == std::floor(bw_units) && bw_units < std::ldexp(1.0, 40);
  // LEAF -> EXIT once the tests issued and returned (registered counts) are
  // both zero. Only a test issued or retired can make them so, at most one of
  // each a cycle: the threads found at one clock edge move in the next cycle.
  std::array<int, 2> leaf_done{};
  int n_leaf_done = 0;
  MemoryResponse resp;  // (its data is not used)
  uint64_t cycle = 0;
  for (;; ++cycle) {
    // Cycles in which nothing can change (every thread waits on a pipeline or
    // the memory, no cache has anything to show or send) are skipped to the
    // next event.
    const bool quiet = !record_valid && in_state[kFetch] == 0 && in_state[kExit] == 0 && in_state[kDone] == 0 &&
                       !(in_state[kFree] > 0 && next_ray < rays.size()) && n_leaf_done == 0 && !list_req_valid &&
                       jobs.empty() && node.Quiet() && list.Quiet() && tri.Quiet();
    if (quiet) {
      uint64_t next_event = memory.next_ready_cycle();
      for (const Ring<Stage>* pipe : {&clip_pipe, &trav_pipe, &isect_pipe}) {
        if (!pipe->empty()) next_event = std::min(next_event, pipe->front().cycle);
      }
      if (next_event != UINT64_MAX && next_event > cycle) {
        // Skipped cycles make no progress: a memory stall while a cache waits
        // on the memory (no thread is in EXIT here, so no stack stall).
        if (busy() && (node.MemWait() || list.MemWait() || tri.MemWait())) perf[kBitStallMem] += next_event - cycle;
        cycle = next_event;
      }
    }
    // The memory's beat of this cycle, routed by {cache, register, beat}.
    int resp_cache = -1, resp_id = -1;
    if ((!lazy_memory || memory.next_ready_cycle() <= cycle) && memory.Respond(cycle, &resp)) {
      resp_cache = resp.tag >> 8;
      resp_id = resp.tag & 0xFF;
    }
    const int alloc = next_ray < rays.size() ? in_set[kFree].Lowest() : -1;
    for (int k = 0; k < n_leaf_done; ++k) Move(leaf_done[k], kExit);
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
    if (alloc >= 0) {
      th[alloc].next = steps.data() + path_begin[next_ray];
      th[alloc].end = steps.data() + path_begin[next_ray + 1];
      ++next_ray;
      Move(alloc, kSetup);
      clip_pipe.push({cycle + lat_clip, alloc});
      ++perf[kBitRayIn];
    }
    // Setup and clip done: into FETCH, or DONE when the ray misses the box.
    const bool clip_out = !clip_pipe.empty() && clip_pipe.front().cycle == cycle;
    if (clip_out) {
      const int t = clip_pipe.front().thread;
      clip_pipe.pop();
      Move(t, th[t].next == th[t].end ? kDone : kFetch);
    }
    const bool trav_out = !trav_pipe.empty() && trav_pipe.front().cycle == cycle;
    if (trav_out) {
      const int t = trav_pipe.front().thread;
      trav_pipe.pop();
      const bool overflow = th[t].next == th[t].end;  // the push met a full stack
      Move(t, overflow ? kDone : kFetch);
      if (overflow) ++perf[kBitOverflow];
    }
    // The test retired this cycle (isect_valid), if any.
    int retired = -1;
    if (!isect_pipe.empty() && isect_pipe.front().cycle == cycle) {
      retired = isect_pipe.front().thread;
      isect_pipe.pop();
    }

    // Node fetches: two arbiters, the second offered to the miss-only port.
    ThreadSet& fetching = in_set[kFetch];
    const int f1 = in_state[kFetch] > 0 ? fetch_arb.Pick(fetching) : -1;
    Cache::Req n1, n2;
    int f2 = -1;
    if (f1 >= 0) {
      fetching.Reset(f1);
      f2 = fetch2_arb.Pick(fetching);
      fetching.Set(f1);
      n1.valid = true;
      n1.key = th[f1].next->key;
      n1.addr = n1.key << 5;
      n1.tag = static_cast<uint64_t>(f1);
    }
    if (f2 >= 0) {
      n2.valid = true;
      n2.key = th[f2].next->key;
      n2.addr = n2.key << 5;
      n2.tag = static_cast<uint64_t>(f2);
    }
    // The node response (registered) fires: the units are always ready.
    const bool node_fire = node.resp_valid();
    const int node_tag = node_fire ? static_cast<int>(node.resp_tag()) : -1;
    node.Eval(n1, n2, true);
    fetch_arb.Ack(f1);
    fetch2_arb.Ack(f2);
    if (node.accept1()) Move(f1, kWaitNode);
    if (node.accept2()) Move(f2, kWaitNode);
    Job new_job{};  // a leaf's job for the list unit's FIFO
    bool has_new_job = false;
    bool trav_in = false;
    if (node_fire) {
      Thread& t = th[node_tag];
      const Step& n = *t.next;
      ++t.next;
      if (n.count == kInner) {
        trav_in = true;
        Move(node_tag, kTrav);
        trav_pipe.push({cycle + lat_trav, node_tag});
        ++perf[kBitTravBusy];
      } else {
        ++perf[kBitTravLeaf];
        if (n.count > 0) {
          Move(node_tag, kLeaf);
          t.remaining = n.count;
          new_job = {node_tag, n.first, n.count};
          has_new_job = true;
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
      const uint32_t line = id / tri_per_line;
      trq = {true, line, h.tri_offset + uint64_t{line} * tri_line_bytes, (tag >> 32) << 32 | id};
    }
    const bool tri_fire = tri.resp_valid();
    const int tri_thread = tri_fire ? static_cast<int>(tri.resp_tag() >> 32) : -1;
    tri.Eval(trq, Cache::Req{}, true);
    list.Eval(lr, Cache::Req{}, tri.accept1());
    const bool list_fire = list_req_valid && list.accept1();
    // rt_perf_events' list_busy: an entry requested or one answered (its
    // triangle taken by the triangle cache).
    const bool entry_fire = trq.valid && tri.accept1();
    if (list_fire || entry_fire) ++perf[kBitListBusy];
    if (tri_fire) {
      isect_pipe.push({cycle + lat_isect, tri_thread});
      ++perf[kBitIsectBusy];
    }

    // The memory arbiter: one beat a cycle, round robin over the caches (the
    // first requester after the last grant).
    const unsigned mreq = node.mem_valid() | list.mem_valid() << 1 | tri.mem_valid() << 2;
    const int g = kMemPick[mem_last][mreq];
    if (g >= 0) {
      mem_last = g;
      memory.Request(caches[g]->mem_addr(), static_cast<uint16_t>(g << 8 | caches[g]->mem_id()), cycle);
    }

    // Leaf exits and records out.
    const int ex = in_state[kExit] > 0 ? exit_arb.Pick(in_set[kExit]) : -1;
    exit_arb.Ack(ex);
    if (ex >= 0) Move(ex, th[ex].next == th[ex].end ? kDone : kFetch);
    const int o = in_state[kDone] > 0 ? out_arb.Pick(in_set[kDone]) : -1;
    out_arb.Ack(o);
    if (o >= 0) {
      Move(o, kFree);
      record_valid = true;
    }

    // rt_perf_events' stalls from this cycle's registered state and moves: a
    // memory stall when a thread is busy, nothing progresses and a cache
    // waits on the memory; a stack stall when a thread in EXIT is not taken.
    // (The units and the harness are always ready: no backpressure.)
    const bool any_progress = trav_in || list_fire || entry_fire || tri_fire || ex >= 0 || o >= 0 || alloc >= 0 ||
                              clip_out || trav_out || retired >= 0;
    if (busy() && !any_progress && (node.MemWait() || list.MemWait() || tri.MemWait())) ++perf[kBitStallMem];
    if (in_state[kExit] > (ex >= 0 ? 1u : 0u)) ++perf[kBitStallStack];

    // LEAF: the counters of tests issued and returned.
    if (tri_fire) {
      --th[tri_thread].remaining;
      ++th[tri_thread].outstanding;
    }
    if (retired >= 0) --th[retired].outstanding;

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
      jobs.pop();
      list_k = 0;
      list_req_valid = true;
    }
    // A leaf's job enters the FIFO at this edge (seen from the next cycle).
    if (has_new_job) jobs.push(new_job);
    if (n_moves > 0) {
      const bool was_busy = busy();
      for (size_t k = 0; k < n_moves; ++k) {
        const auto [t, to_state] = moves[k];
        const State from = th[t].state;
        out.result.thread_states[from] += cycle + 1 - since[t];
        since[t] = cycle + 1;
        in_set[from].Reset(t);
        in_set[to_state].Set(t);
        --in_state[from];
        ++in_state[to_state];
        th[t].state = to_state;
      }
      if (busy() != was_busy) {
        if (was_busy) perf[kBitBusy] += cycle + 1 - busy_since;
        busy_since = cycle + 1;
      }
      n_moves = 0;
    }
    // The leaves over at this edge, to EXIT in the next cycle (a thread that
    // issued a test this cycle has one outstanding: it is never found twice).
    const auto leaf_over = [&th](int t) {
      return th[t].state == kLeaf && th[t].remaining == 0 && th[t].outstanding == 0;
    };
    n_leaf_done = 0;
    if (tri_fire && leaf_over(tri_thread)) leaf_done[n_leaf_done++] = tri_thread;
    if (retired >= 0 && leaf_over(retired)) leaf_done[n_leaf_done++] = retired;
  }
  // The counts of the last cycle's states (the cycle of the last record).
  for (int t = 0; t < threads; ++t) out.result.thread_states[th[t].state] += cycle + 1 - since[t];
  if (busy()) perf[kBitBusy] += cycle + 1 - busy_since;
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
