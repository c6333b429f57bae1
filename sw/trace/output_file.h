// Output files appear whole or not at all: each is written to a temporary
// name beside its destination and renamed only once every output of a command
// has been written, so an error never leaves a partial file behind.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace kdrt {

class OutputSet {
 public:
  OutputSet() = default;
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;
  ~OutputSet();  // removes temporaries not yet committed

  // Calls write(tmp_path) now; the file becomes `path` on Commit().
  void Add(const std::string& path, const std::function<void(const std::string&)>& write);
  void Commit();

 private:
  struct Pending {
    std::string tmp, path;
  };
  std::vector<Pending> pending_;
};

// Convenience for a single file.
void WriteFileAtomically(const std::string& path, const std::function<void(const std::string&)>& write);

}  // namespace kdrt
