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
  // A directory of files (a report page with its images): write(tmp_dir)
  // fills an empty temporary directory now; on Commit() it replaces `path`.
  // An existing `path` that is not a directory, or a non-empty directory
  // without `marker` in it (so not an earlier output of the same kind), is
  // refused with an InputError before anything is written.
  void AddDirectory(const std::string& path, const std::string& marker,
                    const std::function<void(const std::string&)>& write);
  void Commit();

 private:
  struct Pending {
    std::string tmp, path;
    bool directory = false;
  };
  std::vector<Pending> pending_;
};

// Throws InputError(path, 0, ...) unless a file could be created at `path`
// (its directory exists and is writable): commands call it for every output
// before they start work that takes minutes.
void CheckWritable(const std::string& path);

// The checks of AddDirectory, for commands that check before long work.
void CheckDirectoryOutput(const std::string& path, const std::string& marker);

// Convenience for a single file.
void WriteFileAtomically(const std::string& path, const std::function<void(const std::string&)>& write);

}  // namespace kdrt
