// kdrt compare: two EXR hit buffers, bit for bit.
#include <cstdio>

#include "tools/commands.h"
#include "trace/hit_compare.h"
#include "trace/images.h"

namespace kdrt::cli {
namespace {

struct CompareArgs {
  std::string a, b;
};

int RunCompare(const CompareArgs& args) {
  int aw = 0, ah = 0, bw = 0, bh = 0;
  const std::vector<Hit> a = ReadHitBuffer(args.a, &aw, &ah);
  const std::vector<Hit> b = ReadHitBuffer(args.b, &bw, &bh);
  if (aw != bw || ah != bh) {
    std::printf("different sizes: %s is %dx%d, %s is %dx%d\n", args.a.c_str(), aw, ah, args.b.c_str(), bw, bh);
    return 1;
  }
  size_t differ = 0, first = a.size();
  for (size_t i = 0; i < a.size(); ++i) {
    if (SameBits(a[i], b[i])) continue;
    if (differ == 0) first = i;
    ++differ;
  }
  if (differ == 0) {
    std::printf("identical (%dx%d hit records)\n", aw, ah);
    return 0;
  }
  std::printf("%zu of %zu hit records differ; the first at pixel (%zu, %zu):\n  %s: %s\n  %s: %s\n", differ,
              a.size(), first % aw, first / aw, args.a.c_str(), HitText(a[first]).c_str(), args.b.c_str(),
              HitText(b[first]).c_str());
  return 1;
}

}  // namespace

Runner AddCompareCommand(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Compare two EXR hit buffers bit for bit: prints 'identical' or the first differing pixel");
  cmd->add_option("a", args->a, "First hit buffer (.exr)")->required();
  cmd->add_option("b", args->b, "Second hit buffer (.exr)")->required();
  return [cmd, args]() { return cmd->parsed() ? RunCompare(*args) : -1; };
}

}  // namespace kdrt::cli
