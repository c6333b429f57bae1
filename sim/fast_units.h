// The fast model's units that have an RTL unit of their own, cycle for cycle:
// ThreadSet (the arbiters' request vectors), RrArb (rtl/rt_rr_arb.sv) and
// Cache (rtl/rt_cache.sv) and ListUnit (rtl/rt_list_unit.sv).
// sim/fast_model.cpp composes them into the core; the RTL benches run them in
// lock-step with the Verilated units (tests/rtl/cache_bench.cpp,
// rr_arb_bench.cpp, list_unit_bench.cpp), so that a divergence of the fast
// model from the RTL names the unit.
#ifndef KDRT_SIM_FAST_UNITS_H_
#define KDRT_SIM_FAST_UNITS_H_

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "sim/core_params.h"
#include "sim/ring.h"

namespace kdrt::sim::fast {

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
// rtl/rt_cache.sv): Step() is one cycle, the combinational part from the
// registered state and then the clock edge. Miss registers are tracked as
// 128-bit masks (`kdrt sim --cache-mshrs` allows at most kMaxMshrs, from
// sim/core_params.def; rt_cache has no limit): valid, beats left to send,
// line in, no room for another target.
class Cache {
 public:
  using Mask = unsigned __int128;
  static constexpr int kMaxMshrs = kCoreParams[kCacheMshrs].max;
  static_assert(kMaxMshrs <= 128, "the miss registers' masks are 128 bits");
  static int Ctz(Mask m) {
    const uint64_t lo = static_cast<uint64_t>(m);
    return lo ? __builtin_ctzll(lo) : 64 + __builtin_ctzll(static_cast<uint64_t>(m >> 64));
  }
  static Mask Bit(int i) { return Mask{1} << i; }

  // A request: its line's key (the line's address is base + key x line
  // bytes, made only when a miss register takes it) and its tag.
  struct Req {
    bool valid = false;
    uint64_t key = 0, tag = 0;
  };
  struct Events {
    uint64_t hit = 0, miss = 0, merge = 0, wait = 0, wait_inflight = 0, wait_mshr = 0, prefetch = 0;
  };

  Cache(int lines, int ways, int line_beats, int mshrs, int targets, bool miss_port, uint64_t base,
        uint64_t line_bytes, bool prefetch_port = false)
      : base_(base), line_bytes_(line_bytes), set_mask_(static_cast<uint64_t>(lines / ways) - 1), ways_(ways), way_bits_(__builtin_ctz(ways)),
        beats_(line_beats), targets_(targets), mshrs_(mshrs), miss_port_(miss_port), prefetch_port_(prefetch_port),
        all_mshrs_(mshrs >= kMaxMshrs ? ~Mask{0} : Bit(mshrs) - 1), lines_(lines, kNoLine),
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

  // Registered outputs, valid before Step().
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

  // One cycle of the cache: the combinational part from the registered
  // state (rtl/rt_cache.sv's request and response logic) and then the clock
  // edge, fused so that what the one decides stays in registers for the
  // other. `r2` is looked at only on the miss-only port (miss_port);
  // `resp_ready`: the response register is taken when valid; `mem_taken`:
  // the memory arbiter took this cache's beat (decided from the registered
  // mem_valid() before the step); `resp_id` (>= 0): the memory's beat for
  // {register, beat}. Returns the requests taken: bit 0 r1, bit 1 r2.
  unsigned Step(const Req& r1, const Req& r2, bool resp_ready, bool mem_taken, int resp_id) {
    const bool out_take = resp_valid() & resp_ready;
    // A filled line goes out through the delivery register when it is free
    // (or being emptied) and no stalled hit keeps the output.
    const bool deliver = (done_ != 0) & (!del_valid_ | out_take) & !(hit_valid_ & !del_valid_ & !resp_ready);
    const bool use_r2 = r2.valid & (miss_port_ | prefetch_port_);
    // Most cycles of a cache bring no request, and many nothing else: no
    // response taken or made, no beat offered (so none taken or held) and
    // none come in.
    if (!(r1.valid | use_r2 | out_take | deliver | mem_valid() | (resp_id >= 0))) return 0;
    return StepBusy(r1, r2, use_r2, out_take, deliver, mem_taken, resp_id);
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
  // The miss registers in use for `key`: those of its bucket whose key it is.
  Mask Matches(uint64_t key) const {
    Mask mask = 0;
    for (Mask v = bucket_[Bucket(key)] & valid_; v; v &= v - 1) {
      const int m = Ctz(v);
      mask |= static_cast<Mask>(keys_[m] == key) << m;
    }
    return mask;
  }
  static size_t Bucket(uint64_t key) { return (key ^ (key >> 6)) & (kBuckets - 1); }

  __attribute__((noinline)) unsigned StepBusy(const Req& r1, const Req& r2, bool use_r2, bool out_take,
                                              bool deliver, bool mem_taken, int resp_id) {
    // The combinational part.
    const Mask free_mask = all_mshrs_ & ~valid_;
    const int free_idx = free_mask ? Ctz(free_mask) : -1;
    // A request joins the lowest register of its line still taking targets
    // (not filled, not full).
    const Mask joinable = valid_ & ~done_ & ~full_;
    bool hit = false, m_take = false, m_join = false;
    int m_join_idx = -1, hit_way = 0;
    unsigned taken = 0;
    const Req* m = nullptr;
    if (r1.valid) {
      // A present line is a hit whatever the miss registers hold.
      const int way = FindWay(r1.key);
      const bool lookup_hit = way >= 0;
      const Mask match = lookup_hit ? 0 : Matches(r1.key);
      const int join_idx = (match & joinable) ? Ctz(match & joinable) : -1;
      const bool hit_free = !hit_valid_ || (out_take && !del_valid_);
      const bool hit_ok = lookup_hit && hit_free;
      const bool join_ok = !lookup_hit && join_idx >= 0;
      const bool alloc_ok = !lookup_hit && !match && free_idx >= 0;
      const bool ready1 = hit_ok || join_ok || alloc_ok;
      if (!ready1) {
        ++ev_.wait;
        if (!lookup_hit && match && join_idx < 0) ++ev_.wait_inflight;
        if (!lookup_hit && !match && free_idx < 0) ++ev_.wait_mshr;
      }
      hit = ready1 && lookup_hit;
      hit_way = way;
      if (ready1 && !lookup_hit) {
        m_take = true;
        m_join = join_ok;
        m_join_idx = join_idx;
        m = &r1;
      }
      taken = ready1 ? 1u : 0u;
    }
    // The prefetch port: a line present or in flight is dropped; a miss
    // takes a free register (none taken on r1) with no target.
    bool m_count0 = false;
    if (use_r2 && prefetch_port_) {
      const bool drop = FindWay(r2.key) >= 0 || Matches(r2.key) != 0;
      if (drop) {
        taken |= 2u;
      } else if (!m_take && free_idx >= 0) {
        m_take = true;
        m_join = false;
        m_count0 = true;
        m = &r2;
        taken |= 2u;
      }
    } else if (use_r2 && !m_take) {
      const bool lookup2_hit = FindWay(r2.key) >= 0;
      const Mask match2 = lookup2_hit ? 0 : Matches(r2.key);
      const int join2_idx = (match2 & joinable) ? Ctz(match2 & joinable) : -1;
      const bool join2_ok = !lookup2_hit && join2_idx >= 0;
      const bool alloc2_ok = !lookup2_hit && !match2 && free_idx >= 0;
      if (join2_ok || alloc2_ok) {
        m_take = true;
        m_join = join2_ok;
        m_join_idx = join2_idx;
        m = &r2;
        taken |= 2u;
      }
    }
    if (hit) ++ev_.hit;
    if (m_count0) ++ev_.prefetch;
    if (m_take && !m_count0) {
      ++ev_.miss;
      if (m_join) ++ev_.merge;
    }

    // The clock edge, from the registered state this cycle ran on.
    const bool send_valid = mem_valid();
    const int send_idx = send_valid ? SendIdx() : -1;
    const int done_idx = done_ ? Ctz(done_) : -1;
    const int fill_way = deliver ? FillWay(keys_[done_idx]) : 0;
    if (out_take && del_valid_) {
      del_valid_ = false;
    } else if (out_take) {
      hit_valid_ = false;
    }
    if (hit) {
      hit_valid_ = true;
      hit_tag_ = r1.tag;
      if (ways_ > 1) Touch(r1.key & set_mask_, hit_way);
    }
    if (m_take) {
      const int idx = m_join ? m_join_idx : free_idx;
      Mshr& s = mshr_[idx];
      if (!m_join) {
        bucket_[Bucket(keys_[idx])] &= ~Bit(idx);
        keys_[idx] = m->key;
        bucket_[Bucket(keys_[idx])] |= Bit(idx);
        s.addr = base_ + m->key * line_bytes_;
        s.sent = s.got = 0;
        s.cnt = 0;
        s.out = 0;
        valid_ |= Bit(idx);
        unsent_ |= Bit(idx);
      }
      if (!m_count0) {
        tags_[static_cast<size_t>(idx) * targets_ + s.cnt] = m->tag;
        if (++s.cnt == targets_) full_ |= Bit(idx);
      }
    }
    if (mem_taken) {
      Mshr& s = mshr_[send_idx];
      if (++s.sent == static_cast<uint32_t>(beats_)) unsent_ &= ~Bit(send_idx);
    }
    if (resp_id >= 0) {
      const int mi = resp_id / 4;
      Mshr& s = mshr_[mi];
      s.got |= 1u << (resp_id % 4);
      if (s.got == (1u << beats_) - 1) done_ |= Bit(mi);
    }
    if (deliver) {
      const int d = done_idx;
      Mshr& s = mshr_[d];
      const uint64_t set = keys_[d] & set_mask_;
      lines_[set * ways_ + fill_way] = keys_[d];
      if (ways_ > 1) Touch(set, fill_way);
      // A prefetch nobody joined (count 0) writes its line and is freed.
      if (s.cnt > 0) {
        del_tag_ = tags_[static_cast<size_t>(d) * targets_ + s.out];
        del_valid_ = true;
      }
      ++s.out;
      if (s.out >= s.cnt) {
        const Mask keep = ~Bit(d);
        valid_ &= keep;
        done_ &= keep;
        full_ &= keep;
      }
    }
    held_ = send_valid && !mem_taken;
    held_idx_ = send_idx;
    return taken;
  }

  // The way of the key's set that holds its line, or -1. Line set * ways + w
  // is way w of the set (rtl/rt_cache.sv).
  int FindWay(uint64_t key) const {
    if (ways_ == 1) return lines_[key & set_mask_] == key ? 0 : -1;
    const uint64_t* set = &lines_[(key & set_mask_) * ways_];
    if (ways_ == 4) {
      // The default, without a branch per way (a key is in one way at most).
      const unsigned m = static_cast<unsigned>(set[0] == key) | static_cast<unsigned>(set[1] == key) << 1 |
                         static_cast<unsigned>(set[2] == key) << 2 | static_cast<unsigned>(set[3] == key) << 3;
      return m ? __builtin_ctz(m) : -1;
    }
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
  int SendIdx() const { return held_ ? held_idx_ : Ctz(unsent_); }

  uint64_t base_, line_bytes_;
  uint64_t set_mask_;
  int ways_, way_bits_;
  int beats_, targets_, mshrs_;
  bool miss_port_;
  bool prefetch_port_;  // r2 takes prefetches (rt_cache PrefetchPort)
  Mask all_mshrs_;
  std::vector<uint64_t> lines_;  // each line's key, or kNoLine
  std::vector<uint32_t> plru_;   // a set's tree bits (ways > 1)
  std::vector<uint32_t> touch_clear_, touch_set_;
  std::vector<uint8_t> victim_;
  // The miss registers whose key falls in each bucket (a register is in the
  // bucket of the last key it took), so a lookup compares few keys.
  static constexpr size_t kBuckets = 64;
  std::array<Mask, kBuckets> bucket_{};
  std::vector<Mshr> mshr_;
  std::vector<uint64_t> keys_;  // each miss register's line
  std::vector<uint64_t> tags_;  // the merged requests of miss register m: [m * targets_, + cnt)
  // Miss registers: in use, beats to send, line in, targets full.
  Mask valid_ = 0, unsent_ = 0, done_ = 0, full_ = 0;
  bool hit_valid_ = false, del_valid_ = false, held_ = false;
  uint64_t hit_tag_ = 0, del_tag_ = 0;
  int held_idx_ = 0;
  Events ev_;
};

// A leaf's job for the list unit: its thread, first list entry and entries.
struct ListJob {
  int thread = 0;
  uint32_t first = 0, count = 0;
};

// rt_list_unit at the level of its registers: the job queue, the walker's
// request register and the prefetcher (the header comment of
// rtl/rt_list_unit.sv). Addresses are the entries' byte addresses,
// list_base + entry_bytes x entry, not cut to the RTL's AddrWidth.
class ListUnit {
 public:
  ListUnit(size_t jobs, bool stream, uint32_t prefetch, uint64_t list_base, uint64_t line_bytes, uint64_t entry_bytes)
      : jobs_(jobs, true), capacity_(jobs), stream_(stream), prefetch_(prefetch), base_(list_base),
        line_bytes_(line_bytes), entry_bytes_(entry_bytes) {}

  // Registered outputs, valid before Edge().
  bool job_ready() const { return jobs_.size() < capacity_; }
  bool req_valid() const { return req_valid_; }
  const ListJob& req_job() const { return job_; }
  uint32_t req_entry() const { return job_.first + k_; }
  uint64_t req_addr() const { return EntryAddr(req_entry()); }
  // The entries the request names: one, or (ListStream) the job's left in
  // the entry's line.
  uint32_t req_count() const {
    if (!stream_) return 1;
    const uint64_t addr = req_addr();
    const auto in_line = static_cast<uint32_t>((line_bytes_ - addr % line_bytes_) / entry_bytes_);
    return std::min(in_line, job_.count - k_);
  }
  // The prefetcher: at the job pf_off_ places behind the oldest queued one
  // (at most prefetch_ of them); its entry's address (the line it fetches:
  // / line bytes).
  bool pf_valid() const { return pf_off_ < jobs_.size() && pf_off_ < prefetch_; }
  uint64_t pf_addr() const { return EntryAddr(jobs_.at(pf_off_).first + pf_k_); }
  bool empty() const { return !req_valid_ && jobs_.empty(); }
  // list_base_i: stable while a job is queued or requested.
  void set_list_base(uint64_t list_base) { base_ = list_base; }

  // The clock edge: the request and the prefetch taken this cycle, and the
  // job pushed (nullptr: none; a job pushed is seen from the next cycle).
  void Edge(bool req_taken, bool pf_taken, const ListJob* pushed) {
    const bool queued = !jobs_.empty();
    const bool was_valid = req_valid_;
    uint32_t pf_next = 0;
    bool pf_job_done = false;
    if (pf_valid()) {
      const uint64_t addr = pf_addr();
      pf_next = pf_k_ + static_cast<uint32_t>((line_bytes_ - addr % line_bytes_) / entry_bytes_);
      pf_job_done = pf_next >= jobs_.at(pf_off_).count;
    }
    if (req_taken) {
      k_ += req_count();
      if (k_ == job_.count) req_valid_ = false;
    }
    // The prefetcher sees the queue as it was: a job leaves it when the
    // request register was empty this cycle.
    const bool pop = queued && !was_valid;
    if (pop && pf_off_ == 0) {
      pf_k_ = 0;  // the walker took its job: on to the next oldest
    } else {
      pf_off_ = pf_off_ + (pf_taken && pf_job_done ? 1 : 0) - (pop ? 1 : 0);
      if (pf_taken) pf_k_ = pf_job_done ? 0 : pf_next;
    }
    if (pop) {
      job_ = jobs_.front();
      jobs_.pop();
      k_ = 0;
      req_valid_ = true;
    }
    if (pushed != nullptr) jobs_.push(*pushed);
  }

 private:
  uint64_t EntryAddr(uint32_t entry) const { return base_ + uint64_t{entry} * entry_bytes_; }

  Ring<ListJob> jobs_;
  size_t capacity_;
  bool stream_;
  uint32_t prefetch_;
  uint64_t base_, line_bytes_, entry_bytes_;
  bool req_valid_ = false;
  ListJob job_{};
  uint32_t k_ = 0;  // entries of job_ requested so far
  size_t pf_off_ = 0;
  uint32_t pf_k_ = 0;
};

}  // namespace kdrt::sim::fast

#endif  // KDRT_SIM_FAST_UNITS_H_
