// The cores the end-to-end tests run the RTL on. fp32 runs on the default
// core. The other preset formats, and options whose outcome does not depend on
// how many rays are in flight, run on a small core whose model compiles and
// simulates several times faster; KDRT_LONG=1 runs every preset on the
// default core.
#pragma once

#include <cstdlib>
#include <string>
#include <vector>

namespace kdrt::testing {

inline bool LongRun() {
  const char* v = std::getenv("KDRT_LONG");
  return v && std::string(v) == "1";
}

// `kdrt sim` options for a core of 16 threads and 16 miss registers per
// cache, its other parameters the defaults. The widths the scene would
// otherwise size (stack, node and triangle indices, address) are pinned to
// the defaults so that every scene runs on the same model of a format
// (with_stack false: the caller sets the stack depth itself).
inline std::string SmallCore(bool with_stack = true) {
  return std::string(" --threads 16 --cache-mshrs 16 --node-idx-width 24 --tri-idx-width 24 --addr-width 28") +
         (with_stack ? " --stack-depth 32" : "");
}

// A core whose memory system is crowded: 16 threads, 8 miss registers of 2
// targets per cache, 16-line caches and the list prefetcher at 4 lines, so
// that misses meet full registers, lines in flight and evictions. The tests
// of the cache ways and of the prefetcher share its model.
// (list_prefetch: the prefetcher's depth, for a fast-model run beside it.)
inline std::string CrowdedMemoryCore(int list_prefetch = 4) {
  return " --threads 16 --cache-mshrs 8 --cache-targets 2 --list-prefetch " + std::to_string(list_prefetch) +
         " --node-cache-lines 16 "
         "--list-cache-lines 16 --tri-cache-lines 16 --node-idx-width 24 --tri-idx-width 24 --addr-width 28 "
         "--stack-depth 32";
}

// The core a preset runs on: the default core for fp32 (and for every preset
// with KDRT_LONG=1), else the small one.
inline std::string CoreFor(const std::string& format) { return format == "fp32" || LongRun() ? "" : SmallCore(); }

// The cores of the quick models the tests run on, as `kdrt sim` options:
// tests/sim/test_models.txt lists their models so that `make test` builds
// them before ctest runs (TestModels.ListIsTheTestsCores checks the list).
inline std::vector<std::string> TestModelCores() {
  return {
      "--format fp16" + SmallCore(),
      "--format bf16" + SmallCore(),
      "--format fp24" + SmallCore(),
      "--format fp16 --trav-format fp32" + SmallCore(),   // SimCli.WiderTraversalRunsInTheRtl
      "--format fp32 --image-format bf16" + SmallCore(),  // SimCli.NarrowerImageRunsInTheRtl
      "--format fp32" + CrowdedMemoryCore(),               // SimCli.AssociativeCaches, ListPrefetch...
      "--format fp32 --stack-depth 3 --allow-overflow" + SmallCore(false),  // SimCli.StackOverflow...
  };
}

}  // namespace kdrt::testing
