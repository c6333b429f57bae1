#include "trace/output_file.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "common/error.h"

namespace kdrt {

OutputSet::~OutputSet() {
  for (const Pending& p : pending_) std::remove(p.tmp.c_str());
}

void OutputSet::Add(const std::string& path, const std::function<void(const std::string&)>& write) {
  // The temporary keeps the destination's extension: OpenImageIO picks the
  // file format from it.
  std::filesystem::path p(path);
  std::string tmp = (p.parent_path() / ("." + p.stem().string() + ".tmp" + std::to_string(getpid()) +
                                        p.extension().string()))
                        .string();
  pending_.push_back({tmp, path});
  write(tmp);
}

void OutputSet::Commit() {
  for (const Pending& p : pending_) {
    if (std::rename(p.tmp.c_str(), p.path.c_str()) != 0) {
      throw InputError(p.path, 0, "cannot write output file");
    }
  }
  pending_.clear();
}

void WriteFileAtomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  OutputSet set;
  set.Add(path, write);
  set.Commit();
}

}  // namespace kdrt
