#include "sim/fast_model.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "sim/fast_units.h"
#include "sim/ray_queue.h"
#include "sim/ring.h"
#include "sim/unit_latency.h"
#include "trace/tracer.h"

namespace kdrt::sim {
namespace {

using fast::Cache;
using fast::ListJob;
using fast::ListUnit;
using fast::RrArb;
using fast::ThreadSet;

// A memory request's tag: {cache, miss register, beat} (rt_mem_arb's
// {source, id}, 16 bits).
constexpr int kMemIdBits = 10;
static_assert(Cache::kMaxMshrs * 4 <= (1 << kMemIdBits) && (3 << kMemIdBits) < (1 << 16), "memory tag");

constexpr int kBitRayIn = PerfBit("ray_in"), kBitRayOut = PerfBit("ray_out"), kBitBusy = PerfBit("busy"),
              kBitTravBusy = PerfBit("trav_busy"), kBitTravLeaf = PerfBit("trav_leaf"),
              kBitListBusy = PerfBit("list_busy"), kBitIsectBusy = PerfBit("isect_busy"),
              kBitStallMem = PerfBit("stall_mem"), kBitStallStack = PerfBit("stall_stack"),
              kBitOverflow = PerfBit("overflow");

enum State : uint8_t { kFree, kSetup, kFetch, kWaitNode, kTrav, kLeaf, kExit, kDone };

// Node and list cache lines: NodeLineBeats = ListLineBeats = 2 beats
// (rt_core), named by address / kLineBytes.
constexpr uint64_t kLineBytes = 32;

// A list request's tag: the thread (rt_core allows at most 256), its first
// list entry and, with ListStream, how many entries from it the request names.
struct ListTag {
  static uint64_t Make(uint32_t thread, uint32_t entry, uint32_t count) {
    return uint64_t{count} << 40 | uint64_t{thread} << 32 | entry;
  }
  static uint32_t Entry(uint64_t tag) { return static_cast<uint32_t>(tag); }
  static uint64_t Thread(uint64_t tag) { return (tag >> 32) & 0xFF; }
  static uint32_t Count(uint64_t tag) { return static_cast<uint32_t>(tag >> 40); }
};

// A step of a ray's path: a node it fetches, decoded once, with its node
// cache key and, for a leaf, its list entries (count kInner: an inner node).
constexpr uint32_t kInner = 0xFFFFFFFFu;
struct Step {
  uint32_t key = 0;  // the node's 32-byte line (AddrWidth <= 32)
  uint32_t count = kInner, first = 0;
};

struct Thread {
  State state = kFree;
  uint32_t ray = 0;            // its ray's id
  const Step* next = nullptr;  // the path step fetched next (or being fetched)
  const Step* end = nullptr;   // the end of the ray's path
  uint32_t remaining = 0, outstanding = 0;
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

// Every ray's path from the reference traversal, decoded into steps.
struct RayPaths {
  std::vector<Step> steps;   // the paths in ray order: the rays in flight are neighbours
  std::vector<size_t> begin;  // ray r's steps are [begin[r], begin[r + 1])
};

// The reference traversal of every ray of `spec`: its hit, its counters
// (each ray's kept only with `keep_per_ray`: several cores' bounds need them),
// and its path (the nodes it fetches, each leaf's list entries).
RayPaths TraceReference(const FastSpec& spec, FastReference* ref, bool keep_per_ray) {
  const ImageView& image = *spec.image;
  const std::vector<Ray>& rays = *spec.rays;
  const CoreConfig& cfg = spec.config;
  const img::ImageLayout layout = image.layout();
  const img::Header& h = image.header();
  ref->hits.resize(rays.size());
  ref->overflow.assign(rays.size(), 0);
  if (keep_per_ray) ref->per_ray.assign(rays.size(), RayCounters{});
  std::vector<std::vector<uint32_t>> paths(rays.size());
  TraceOptions to;
  to.format = cfg.Format();
  to.trav_format = cfg.TravFormat();
  to.query = spec.query;
  // A path that ends on an inner node is a ray whose push met a full stack
  // (StackDepth below the tree's depth, --allow-overflow): its thread goes
  // from TRAV to DONE, and its record is the hit it had (rt_thread_fsm).
  to.stack_depth = cfg[kStackDepth];
  for (size_t i = 0; i < rays.size(); ++i) {
    RayCounters c;
    ref->hits[i] = TraceOne(image, rays[i], to, &c, &paths[i]);
    if (keep_per_ray) ref->per_ray[i] = c;
    ref->overflow[i] = c.overflows > 0;
    ref->overflows += c.overflows > 0;
    ref->totals += c;
  }
  // The paths decoded into steps, one array in ray order (a table by node
  // index costs a cache miss a fetch).
  uint32_t max_node = 0;
  size_t n_steps = 0;
  for (const auto& p : paths) {
    for (uint32_t n : p) max_node = std::max(max_node, n);
    n_steps += p.size();
  }
  std::vector<Step> nodes(max_node + 1u);
  std::vector<uint8_t> decoded(max_node + 1u, 0);
  RayPaths out;
  out.steps.reserve(n_steps);
  out.begin.assign(rays.size() + 1, 0);
  for (size_t r = 0; r < rays.size(); ++r) {
    for (uint32_t i : paths[r]) {
      if (!decoded[i]) {
        decoded[i] = 1;
        nodes[i].key = static_cast<uint32_t>((h.node_offset + layout.NodeBeatOffset(i)) / kLineBytes);
        const img::Node n = image.node(i);
        if (n.IsLeaf()) {
          nodes[i].count = n.Count();
          nodes[i].first = n.FirstEntry();
        }
      }
      out.steps.push_back(nodes[i]);
    }
    out.begin[r + 1] = out.steps.size();
    std::vector<uint32_t>().swap(paths[r]);
  }
  return out;
}

// The memory is asked for its beat only in the cycles it may have one ready
// when its token bucket comes out the same however the refill is split: with
// a bandwidth of whole 2^-20 bytes every sum is exact (and a sum too large to
// be exact is over the bucket's size anyway).
bool LazyMemory(const MemoryConfig& memory) {
  const double bw_units = std::ldexp(memory.bytes_per_cycle, 20);
  return bw_units == std::floor(bw_units) && bw_units < std::ldexp(1.0, 40);
}

// A core's port on the shared L2 (SharedL2::port without the virtual call).
class L2Port {
 public:
  L2Port(SharedL2& l2, int core) : l2_(&l2), core_(core) {}
  void Request(uint64_t addr, uint16_t tag, uint64_t cycle) { l2_->Request(core_, addr, tag, cycle); }
  bool Respond(uint64_t cycle, MemoryResponse* out) { return l2_->Respond(core_, cycle, out); }
  uint64_t next_ready_cycle() const { return l2_->next_ready_cycle(core_); }

 private:
  SharedL2* l2_;
  int core_;
};

// One rt_core, cycle by cycle, on a memory port `Mem` (the MemoryModel
// itself, or its port on the shared L2): Request, Respond and
// next_ready_cycle as MemoryModel has them. Rays come from a RayQueue as the
// RTL harness takes them (BeginCycle: a ray is taken when none is pending,
// and offered until a free thread accepts it).
template <class Mem>
class FastCore {
 public:
  // `lazy_memory`: `mem` needs to be asked for a beat only from its
  // next_ready_cycle() on.
  FastCore(const FastSpec& spec, const RayPaths& paths, const FastReference& ref, Mem& mem, RayQueue& queue,
           int index, bool lazy_memory)
      : paths_(paths), ref_(ref), mem_(mem), queue_(queue), index_(index), lazy_(lazy_memory),
        timeout_(spec.timeout), threads_(spec.config[kThreads]),
        // Node and list lines are named by address / kLineBytes, triangle
        // lines by triangle id / P.
        node_(spec.config[kNodeCacheLines], spec.config[kCacheWays], static_cast<int>(kLineBytes / kBeatBytes),
              spec.config[kCacheMshrs], spec.config[kCacheTargets], true, 0, kLineBytes),
        list_(spec.config[kListCacheLines], spec.config[kCacheWays], static_cast<int>(kLineBytes / kBeatBytes),
              spec.config[kCacheMshrs], spec.config[kCacheTargets], false, 0, kLineBytes,
              spec.config[kListPrefetch] > 0),
        tri_(spec.config[kTriCacheLines], spec.config[kCacheWays], spec.image->layout().TriangleLineBeats(),
             spec.config[kCacheMshrs], spec.config[kCacheTargets], false, spec.image->header().tri_offset,
             spec.image->layout().TriangleLineBytes()),
        th_(threads_), fetch_arb_(threads_), fetch2_arb_(threads_), exit_arb_(threads_), out_arb_(threads_),
        moves_(static_cast<size_t>(threads_)), since_(static_cast<size_t>(threads_), 0),
        clip_pipe_(threads_, true), trav_pipe_(threads_, true),
        list_unit_(static_cast<size_t>(threads_), spec.config[kListStream] != 0,
                   static_cast<uint32_t>(spec.config[kListPrefetch]), spec.image->header().list_offset, kLineBytes,
                   img::kListEntryBytes),
        stream_(spec.config[kListStream] != 0), lists_(spec.image->lists()), header_(spec.image->header()) {
    const CoreConfig& cfg = spec.config;
    // Ray setup followed by the clip, the traversal step and the triangle
    // test: the units' latencies as their benches check them.
    const fp::Format f = cfg.Format(), trav = cfg.TravFormat();
    lat_clip_ = latency::RaySetup(f, trav) + latency::Clip(f, trav);
    lat_trav_ = latency::Trav(f, trav);
    lat_isect_ = latency::Isect(f);
    // The pipelines take at most one thread a cycle: setup/clip and traversal
    // hold each thread at most once, intersection at most one test a cycle of
    // its latency.
    isect_pipe_ = Ring<Stage>(lat_isect_ + 1, true);
    in_set_.fill(ThreadSet(threads_));
    for (int t = 0; t < threads_; ++t) in_set_[kFree].Set(t);
    in_state_[kFree] = static_cast<uint64_t>(threads_);
    // The triangle cache's lines hold P records (img::ImageLayout): a line is
    // named by id / P.
    const img::ImageLayout layout = spec.image->layout();
    tri_per_line_ = static_cast<uint32_t>(layout.TrianglesPerLine());
  }

  // The RTL harness's Done(), checked before each cycle: no ray pending or in
  // flight, and none left in the queue for this core.
  bool Done() const { return !has_pending_ && in_flight_ == 0 && queue_.Exhausted(index_); }

  // Nothing in this core can change before its next event (NextEvent, or a
  // beat from its memory port): every thread waits on a pipeline or the
  // memory, no cache has anything to show or send, no ray is to be taken.
  bool Quiet() const {
    return !record_valid_ && in_state_[kFetch] == 0 && in_state_[kExit] == 0 && in_state_[kDone] == 0 &&
           !(has_pending_ ? in_state_[kFree] > 0 : !queue_.Exhausted(index_)) && n_leaf_done_ == 0 &&
           list_unit_.empty() && em_left_ == 0 && node_.Quiet() && list_.Quiet() && tri_.Quiet() && !Done();
  }
  // The first cycle a pipeline delivers (UINT64_MAX: none busy).
  uint64_t NextEvent() const {
    uint64_t next = UINT64_MAX;
    for (const Ring<Stage>* pipe : {&clip_pipe_, &trav_pipe_, &isect_pipe_}) {
      if (!pipe->empty()) next = std::min(next, pipe->front().cycle);
    }
    return next;
  }
  // Cycles [from, to) skipped while Quiet(): no progress, so a memory stall
  // whenever a cache waits on the memory (no thread is in EXIT, so no stack
  // stall).
  void Skip(uint64_t from, uint64_t to) {
    if (Busy() && (node_.MemWait() || list_.MemWait() || tri_.MemWait())) perf()[kBitStallMem] += to - from;
  }

  // One clock cycle (after Done() was false).
  // Not inlined into the drivers: profiles (callgrind --toggle-collect) then
  // find it by name; the call costs nothing against a cycle's work.
  __attribute__((noinline)) void Cycle(uint64_t cycle);

  // After the core's last cycle (`cycles` = the cycle Done() first held).
  void Finish(uint64_t cycles, RunOutcome* out) {
    // The counts of the last cycle's states.
    for (int t = 0; t < threads_; ++t) result_.thread_states[th_[t].state] += cycles - since_[t];
    if (Busy()) perf()[kBitBusy] += cycles - busy_since_;
    result_.cycles = cycles;
    const Cache::Events* ev[3] = {&node_.events(), &list_.events(), &tri_.events()};
    const char* names[3] = {"node", "list", "tri"};
    for (int k = 0; k < 3; ++k) {
      const std::string n = names[k];
      perf()[PerfBit(n + "_hit")] += ev[k]->hit;
      perf()[PerfBit(n + "_miss")] += ev[k]->miss;
      perf()[PerfBit(n + "_merge")] += ev[k]->merge;
      perf()[PerfBit(n + "_wait")] += ev[k]->wait;
      perf()[PerfBit(n + "_wait_inflight")] += ev[k]->wait_inflight;
      perf()[PerfBit(n + "_wait_mshr")] += ev[k]->wait_mshr;
    }
    perf()[PerfBit("list_prefetch")] += list_.events().prefetch;
    out->result = std::move(result_);
  }

 private:
  std::array<uint64_t, kPerfBits>& perf() { return result_.perf; }
  bool Busy() const { return in_state_[kFree] != static_cast<uint64_t>(threads_); }
  void Move(int t, State to_state) { moves_[n_moves_++] = {t, to_state}; }
  // A traversal step or a pop that goes on to thread t's next node: to
  // FETCH, or to EXIT again without a fetch when the node is an empty leaf
  // (its parent marks it; the path holds it, the counters do not).
  State GoOn(int t) {
    if (th_[t].next->count != 0) return kFetch;
    ++th_[t].next;
    return kExit;
  }

  const RayPaths& paths_;
  const FastReference& ref_;
  Mem& mem_;
  RayQueue& queue_;
  int index_;
  bool lazy_;
  uint64_t timeout_;
  int threads_;
  uint64_t lat_clip_ = 0, lat_trav_ = 0, lat_isect_ = 0;
  Cache node_, list_, tri_;
  std::vector<Thread> th_;
  RrArb fetch_arb_, fetch2_arb_, exit_arb_, out_arb_;
  int exit_chosen_ = -1;  // the leaf exit's choice of the previous cycle: it exits in this one
  int mem_last_ = 2;  // the memory arbiter's last grant (rt_rr_arb over the three caches)
  // The threads in each state (the ray input and the arbiters pick from FREE,
  // FETCH, EXIT and DONE), kept up to date by the moves below.
  std::array<ThreadSet, 8> in_set_;
  std::array<uint64_t, 8> in_state_{};  // threads per state
  // The state changes of this cycle, applied at the clock edge (one per
  // thread at most).
  std::vector<std::pair<int, State>> moves_;
  size_t n_moves_ = 0;
  // The thread-state and busy counts accrue at the clock edges that change
  // them: a thread's cycles in a state when it leaves it, the busy cycles
  // when the core goes idle (and both at the end).
  std::vector<uint64_t> since_;  // in th_[t].state since this cycle
  uint64_t busy_since_ = 0;
  Ring<Stage> clip_pipe_, trav_pipe_, isect_pipe_{1, true};
  // rt_list_unit (its queue holds a job per thread at most).
  ListUnit list_unit_;
  // ListStream: a request names the job's entries in one list line (at
  // most 8; its count rides in its ListTag), and rt_mem_system's
  // line register hands them to the triangle cache one a cycle: the next
  // entry, how many are left (0: empty) and whose they are.
  bool stream_ = false;
  uint32_t em_entry_ = 0, em_left_ = 0;
  uint64_t em_thread_ = 0;
  // The harness's side: the ray offered (ray_valid_i), the rays in flight.
  bool has_pending_ = false;
  size_t pending_ray_ = 0;
  uint64_t in_flight_ = 0;
  bool record_valid_ = false;  // rt_hit_out's register: a record leaves this cycle
  uint32_t record_ray_ = 0;
  uint64_t last_record_ = 0;
  const uint32_t* lists_;
  const img::Header& header_;
  uint32_t tri_per_line_ = 1;
  // LEAF -> EXIT once the tests issued and returned (registered counts) are
  // both zero. Only a test issued or retired can make them so, at most one of
  // each a cycle: the threads found at one clock edge move in the next cycle.
  std::array<int, 2> leaf_done_{};
  int n_leaf_done_ = 0;
  HarnessResult result_;
};

template <class Mem>
void FastCore<Mem>::Cycle(uint64_t cycle) {
  // The harness's next ray (BeginCycle): taken when none is pending.
  if (!has_pending_) has_pending_ = queue_.Take(index_, &pending_ray_);
  // The memory's beat of this cycle, routed by {cache, register, beat}.
  MemoryResponse resp;  // (its data is not used)
  int resp_cache = -1, resp_id = -1;
  if ((!lazy_ || mem_.next_ready_cycle() <= cycle) && mem_.Respond(cycle, &resp)) {
    resp_cache = resp.tag >> kMemIdBits;
    resp_id = resp.tag & ((1 << kMemIdBits) - 1);
  }
  const int alloc = has_pending_ ? in_set_[kFree].Lowest() : -1;
  for (int k = 0; k < n_leaf_done_; ++k) Move(leaf_done_[k], kExit);
  // A record leaves the core (hit_valid_o): the harness takes it.
  auto& perf = result_.perf;
  if (record_valid_) {
    ++perf[kBitRayOut];
    result_.ray_ids.push_back(record_ray_);
    result_.hit_count += ref_.hits[record_ray_].IsHit();
    result_.overflows += ref_.overflow[record_ray_];
    queue_.Returned();
    last_record_ = cycle;
  }
  if (cycle - last_record_ > timeout_) {
    throw std::runtime_error("fast model: no hit record for " + std::to_string(timeout_) + " cycles");
  }

  // Ray in: the lowest free thread takes the harness's ray.
  if (alloc >= 0) {
    th_[alloc].ray = static_cast<uint32_t>(pending_ray_);
    th_[alloc].next = paths_.steps.data() + paths_.begin[pending_ray_];
    th_[alloc].end = paths_.steps.data() + paths_.begin[pending_ray_ + 1];
    has_pending_ = false;
    // The harness counts a ray taken before a record returned in the same
    // cycle (EndCycle).
    if (++in_flight_ > result_.max_in_flight) result_.max_in_flight = in_flight_;
    Move(alloc, kSetup);
    clip_pipe_.push({cycle + lat_clip_, alloc});
    ++perf[kBitRayIn];
  }
  if (record_valid_) {
    --in_flight_;
    record_valid_ = false;
  }
  // Setup and clip done: into FETCH, or DONE when the ray misses the box.
  const bool clip_out = !clip_pipe_.empty() && clip_pipe_.front().cycle == cycle;
  if (clip_out) {
    const int t = clip_pipe_.front().thread;
    clip_pipe_.pop();
    Move(t, th_[t].next == th_[t].end ? kDone : kFetch);
  }
  const bool trav_out = !trav_pipe_.empty() && trav_pipe_.front().cycle == cycle;
  if (trav_out) {
    const int t = trav_pipe_.front().thread;
    trav_pipe_.pop();
    const bool overflow = th_[t].next == th_[t].end;  // the push met a full stack
    Move(t, overflow ? kDone : GoOn(t));
    if (overflow) ++perf[kBitOverflow];
  }
  // The test retired this cycle (isect_valid), if any.
  int retired = -1;
  if (!isect_pipe_.empty() && isect_pipe_.front().cycle == cycle) {
    retired = isect_pipe_.front().thread;
    isect_pipe_.pop();
  }

  // The memory arbiter, from the registered state: one beat a cycle, round
  // robin over the caches (the first requester after the last grant). The
  // caches' steps below then take it at their clock edges.
  const bool mem_wait = node_.MemWait() || list_.MemWait() || tri_.MemWait();
  Cache* caches[3] = {&node_, &list_, &tri_};
  const unsigned mreq = node_.mem_valid() | list_.mem_valid() << 1 | tri_.mem_valid() << 2;
  const int g = kMemPick[mem_last_][mreq];
  if (g >= 0) {
    mem_last_ = g;
    mem_.Request(caches[g]->mem_addr(), static_cast<uint16_t>(g << kMemIdBits | caches[g]->mem_id()), cycle);
    ++result_.mem_requests;
  }

  // Node fetches: two arbiters, the second offered to the miss-only port.
  ThreadSet& fetching = in_set_[kFetch];
  const int f1 = in_state_[kFetch] > 0 ? fetch_arb_.Pick(fetching) : -1;
  Cache::Req n1, n2;
  int f2 = -1;
  if (f1 >= 0) {
    fetching.Reset(f1);
    f2 = fetch2_arb_.Pick(fetching);
    fetching.Set(f1);
    n1.valid = true;
    n1.key = th_[f1].next->key;
    n1.tag = static_cast<uint64_t>(f1);
  }
  if (f2 >= 0) {
    n2.valid = true;
    n2.key = th_[f2].next->key;
    n2.tag = static_cast<uint64_t>(f2);
  }
  // The node response (registered) fires: the units are always ready.
  const bool node_fire = node_.resp_valid();
  const int node_tag = node_fire ? static_cast<int>(node_.resp_tag()) : -1;
  const unsigned node_taken = node_.Step(n1, n2, true, g == 0, resp_cache == 0 ? resp_id : -1);
  fetch_arb_.Ack(f1);
  fetch2_arb_.Ack(f2);
  if (node_taken & 1u) Move(f1, kWaitNode);
  if (node_taken & 2u) Move(f2, kWaitNode);
  ListJob new_job{};  // a leaf's job for the list unit's FIFO
  bool has_new_job = false;
  bool trav_in = false;
  if (node_fire) {
    Thread& t = th_[node_tag];
    const Step& n = *t.next;
    ++t.next;
    if (n.count == kInner) {
      trav_in = true;
      Move(node_tag, kTrav);
      trav_pipe_.push({cycle + lat_trav_, node_tag});
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
  if (list_unit_.req_valid()) {
    lr = {true, list_unit_.req_addr() / kLineBytes,
          ListTag::Make(static_cast<uint32_t>(list_unit_.req_job().thread), list_unit_.req_entry(),
                        list_unit_.req_count())};
  }
  Cache::Req trq;
  if (stream_) {
    if (em_left_ > 0) trq = {true, lists_[em_entry_] / tri_per_line_, em_thread_};
  } else if (list_.resp_valid()) {
    const uint64_t tag = list_.resp_tag();
    // The triangle cache's tag: the thread (the RTL's tag also has the id,
    // which only the datapath uses).
    trq = {true, lists_[ListTag::Entry(tag)] / tri_per_line_, ListTag::Thread(tag)};
  }
  const bool tri_fire = tri_.resp_valid();
  const int tri_thread = tri_fire ? static_cast<int>(tri_.resp_tag()) : -1;
  const bool tri_taken = tri_.Step(trq, Cache::Req{}, true, g == 2, resp_cache == 2 ? resp_id : -1) & 1u;
  const bool list_resp_ready = stream_ ? (em_left_ == 0 || (tri_taken && em_left_ == 1)) : tri_taken;
  const bool list_resp_fire = list_.resp_valid() && list_resp_ready;
  const uint64_t list_resp_tag = list_resp_fire ? list_.resp_tag() : 0;
  // The prefetcher's line (rt_list_unit g_prefetch), from the registered
  // state.
  Cache::Req pfr;
  if (list_unit_.pf_valid()) pfr = {true, list_unit_.pf_addr() / kLineBytes, 0};
  const unsigned list_taken_bits =
      list_.Step(lr, pfr, list_resp_ready, g == 1, resp_cache == 1 ? resp_id : -1);
  const bool list_taken = (list_taken_bits & 1u) != 0;
  const bool pf_fire = pfr.valid && (list_taken_bits & 2u) != 0;
  if (stream_) {
    if (tri_taken) {
      ++em_entry_;
      --em_left_;
    }
    if (list_resp_fire) {
      em_entry_ = ListTag::Entry(list_resp_tag);
      em_thread_ = ListTag::Thread(list_resp_tag);
      em_left_ = ListTag::Count(list_resp_tag);
    }
  }
  const bool list_fire = lr.valid && list_taken;
  // rt_perf_events' list_busy: an entry requested or one answered (its
  // triangle taken by the triangle cache).
  const bool entry_fire = trq.valid && tri_taken;
  if (list_fire || entry_fire) ++perf[kBitListBusy];
  if (tri_fire) {
    isect_pipe_.push({cycle + lat_isect_, tri_thread});
    ++perf[kBitIsectBusy];
  }

  // Leaf exits and records out. The leaf exit chooses among the threads in
  // EXIT but the one it chose in the previous cycle, which exits in this one
  // (rt_leaf_exit: the choice's top entry is read and registered first).
  const int ex = exit_chosen_;
  if (ex >= 0) Move(ex, th_[ex].next == th_[ex].end ? kDone : GoOn(ex));
  int chosen = -1;
  if (in_state_[kExit] > (ex >= 0 ? 1u : 0u)) {
    if (ex >= 0) in_set_[kExit].Reset(ex);
    chosen = exit_arb_.Pick(in_set_[kExit]);
    if (ex >= 0) in_set_[kExit].Set(ex);
  }
  exit_arb_.Ack(chosen);
  exit_chosen_ = chosen;
  const int o = in_state_[kDone] > 0 ? out_arb_.Pick(in_set_[kDone]) : -1;
  out_arb_.Ack(o);
  if (o >= 0) {
    Move(o, kFree);
    record_valid_ = true;
    record_ray_ = th_[o].ray;
  }

  // rt_perf_events' stalls from this cycle's registered state and moves: a
  // memory stall when a thread is busy, nothing progresses and a cache
  // waits on the memory; a stack stall when a thread in EXIT is neither
  // exiting nor chosen to exit next.
  // (The units and the harness are always ready: no backpressure.)
  const bool any_progress = trav_in || list_fire || entry_fire || tri_fire || ex >= 0 || o >= 0 || alloc >= 0 ||
                            clip_out || trav_out || retired >= 0;
  if (Busy() && !any_progress && mem_wait) ++perf[kBitStallMem];
  if (in_state_[kExit] > (ex >= 0 ? 1u : 0u) + (chosen >= 0 ? 1u : 0u)) ++perf[kBitStallStack];

  // LEAF: the counters of tests issued and returned.
  if (tri_fire) {
    --th_[tri_thread].remaining;
    ++th_[tri_thread].outstanding;
  }
  if (retired >= 0) --th_[retired].outstanding;

  // The clock edge (the caches' edges were in their steps).
  // rt_list_unit: the request register, the prefetcher and the job FIFO (a
  // leaf's job enters it at this edge, seen from the next cycle).
  list_unit_.Edge(list_fire, pf_fire, has_new_job ? &new_job : nullptr);
  if (n_moves_ > 0) {
    const bool was_busy = Busy();
    for (size_t k = 0; k < n_moves_; ++k) {
      const auto [t, to_state] = moves_[k];
      const State from = th_[t].state;
      result_.thread_states[from] += cycle + 1 - since_[t];
      since_[t] = cycle + 1;
      in_set_[from].Reset(t);
      in_set_[to_state].Set(t);
      --in_state_[from];
      ++in_state_[to_state];
      th_[t].state = to_state;
    }
    if (Busy() != was_busy) {
      if (was_busy) perf[kBitBusy] += cycle + 1 - busy_since_;
      busy_since_ = cycle + 1;
    }
    n_moves_ = 0;
  }
  // The leaves over at this edge, to EXIT in the next cycle (a thread that
  // issued a test this cycle has one outstanding: it is never found twice).
  const auto leaf_over = [this](int t) {
    return th_[t].state == kLeaf && th_[t].remaining == 0 && th_[t].outstanding == 0;
  };
  n_leaf_done_ = 0;
  if (tri_fire && leaf_over(tri_thread)) leaf_done_[n_leaf_done_++] = tri_thread;
  if (retired >= 0 && leaf_over(retired)) leaf_done_[n_leaf_done_++] = retired;
}

// The progress line of a long run (kdrt sim --progress, or stderr a
// terminal): rays returned, cycles and simulated cycles per second, every
// half second, looked at every 2^16 loop iterations.
class Progress {
 public:
  Progress(bool on, const RayQueue& queue) : on_(on), queue_(queue), start_(std::chrono::steady_clock::now()) {
    last_ = start_;
  }
  void Step(uint64_t cycle) {
    if (!on_ || (++iterations_ & 0xFFFF) != 0) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::milliseconds(500)) return;
    last_ = now;
    Print(cycle, false);
  }
  void Done(uint64_t cycles) {
    if (on_ && std::chrono::steady_clock::now() - start_ >= std::chrono::milliseconds(500)) Print(cycles, true);
  }

 private:
  void Print(uint64_t cycle, bool final_line) {
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::fprintf(stderr, "\rsim (fast): %zu/%zu rays, %llu cycles, %.1f Mcycles/s%s", queue_.returned(),
                 queue_.count(), static_cast<unsigned long long>(cycle), secs > 0 ? cycle / secs * 1e-6 : 0.0,
                 final_line ? "\n" : "");
    std::fflush(stderr);
  }
  bool on_;
  const RayQueue& queue_;
  uint64_t iterations_ = 0;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace

RunOutcome RunFastModel(const FastSpec& spec, RayCounters* reference_totals,
                        std::vector<RayCounters>* reference_per_ray) {
  FastReference ref;
  const RayPaths paths = TraceReference(spec, &ref, reference_per_ray != nullptr);
  if (reference_totals) *reference_totals = ref.totals;
  if (reference_per_ray) *reference_per_ray = std::move(ref.per_ray);
  // The memory's timing only: the model reads no data, so the memory holds
  // no image (a beat reads zeros, and costs no cache miss on the host). The
  // image must fit all the same, as for the RTL.
  MemoryModel memory(spec.memory);
  memory.CheckFits(spec.image->size());
  // The simulation's own time, as the RTL harness counts it (without the
  // reference traversal, which both pay).
  const auto start = std::chrono::steady_clock::now();
  RayQueue queue(spec.rays->size(), 1, spec.rays->size(), spec.order);
  FastCore<MemoryModel> core(spec, paths, ref, memory, queue, 0, LazyMemory(spec.memory));
  Progress progress(spec.progress, queue);
  uint64_t cycle = 0;
  for (;; ++cycle) {
    progress.Step(cycle);
    // Cycles in which nothing can change are skipped to the next event.
    if (core.Quiet()) {
      const uint64_t next_event = std::min(memory.next_ready_cycle(), core.NextEvent());
      if (next_event != UINT64_MAX && next_event > cycle) {
        core.Skip(cycle, next_event);
        cycle = next_event;
      }
    }
    if (core.Done()) break;
    core.Cycle(cycle);
  }
  progress.Done(cycle);
  RunOutcome out;
  core.Finish(cycle, &out);
  out.result.hits = std::move(ref.hits);
  out.result.overflow = std::move(ref.overflow);
  out.mem_bytes_read = memory.bytes_read();
  out.mem_requests = memory.requests();
  out.mem_max_outstanding = memory.max_outstanding();
  out.result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

SystemOutcome RunFastCores(const FastSpec& spec, int cores, const L2Config& l2_config, size_t chunk,
                           FastReference* reference) {
  FastReference& ref = *reference;
  ref = FastReference{};
  const RayPaths paths = TraceReference(spec, &ref, true);
  MemoryModel memory(spec.memory);
  memory.CheckFits(spec.image->size());
  // The L2 reads no data either: its beats are zeros.
  const std::vector<uint8_t> no_data;
  SharedL2 l2(l2_config, memory, no_data, cores);
  const bool lazy = LazyMemory(spec.memory);
  const auto start = std::chrono::steady_clock::now();
  RayQueue queue(spec.rays->size(), cores, chunk, spec.order);
  std::vector<L2Port> ports;
  ports.reserve(static_cast<size_t>(cores));
  std::vector<std::unique_ptr<FastCore<L2Port>>> core;
  for (int k = 0; k < cores; ++k) {
    ports.emplace_back(l2, k);
    // The L2's answers to a core wait in its queue with their cycle: asking
    // from next_ready_cycle() on is exact.
    core.push_back(std::make_unique<FastCore<L2Port>>(spec, paths, ref, ports[k], queue, k, true));
  }
  std::vector<uint64_t> done_at(static_cast<size_t>(cores), UINT64_MAX);
  int running = cores;
  SystemOutcome out;
  Progress progress(spec.progress, queue);
  for (uint64_t cycle = 0;; ++cycle) {
    progress.Step(cycle);
    // Cycles in which no running core can change and nothing reaches the L2
    // are skipped to the next event.
    bool quiet = true;
    uint64_t next_event = memory.next_ready_cycle();
    for (int k = 0; k < cores && quiet; ++k) {
      if (done_at[k] != UINT64_MAX) continue;
      quiet = core[k]->Quiet();
      next_event = std::min({next_event, core[k]->NextEvent(), ports[k].next_ready_cycle()});
    }
    if (quiet && next_event != UINT64_MAX && next_event > cycle) {
      for (int k = 0; k < cores; ++k) {
        if (done_at[k] == UINT64_MAX) core[k]->Skip(cycle, next_event);
      }
      cycle = next_event;
    }
    // The L2 takes the memory's beat of this cycle before any core asks it
    // (as the first core's Respond does in the SystemC system).
    if (!lazy || memory.next_ready_cycle() <= cycle) l2.Advance(cycle);
    // The cores in the SystemC kernel's order of their clock methods (the
    // order they were made in): a core that is done stops at its clock edge.
    for (int k = 0; k < cores; ++k) {
      if (done_at[k] != UINT64_MAX) continue;
      if (core[k]->Done()) {
        done_at[k] = cycle;
        --running;
        continue;
      }
      core[k]->Cycle(cycle);
    }
    if (running == 0) {
      out.cycles = cycle;
      break;
    }
  }
  progress.Done(out.cycles);
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (int k = 0; k < cores; ++k) {
    RunOutcome c;
    core[k]->Finish(done_at[k], &c);
    c.result.wall_seconds = out.wall_seconds;
    c.mem_bytes_read = memory.bytes_read();
    c.mem_requests = memory.requests();
    c.mem_max_outstanding = memory.max_outstanding();
    out.cores.push_back(std::move(c));
  }
  out.mem_bytes_read = memory.bytes_read();
  out.mem_requests = memory.requests();
  out.mem_max_outstanding = memory.max_outstanding();
  out.l2 = l2.stats();
  out.l2_config = l2_config;
  return out;
}

}  // namespace kdrt::sim
