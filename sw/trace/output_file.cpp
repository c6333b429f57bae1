#include "trace/output_file.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "common/error.h"

namespace kdrt {

namespace fs = std::filesystem;

OutputSet::~OutputSet() {
  for (const Pending& p : pending_) {
    std::error_code ec;
    fs::remove_all(p.tmp, ec);
  }
}

void OutputSet::Add(const std::string& path, const std::function<void(const std::string&)>& write) {
  // The temporary keeps the destination's extension: OpenImageIO picks the
  // file format from it.
  std::filesystem::path p(path);
  std::string tmp = (p.parent_path() / ("." + p.stem().string() + ".tmp" + std::to_string(getpid()) +
                                        p.extension().string()))
                        .string();
  pending_.push_back({tmp, path});
  try {
    write(tmp);
  } catch (const InputError& e) {
    // The message names the file the user asked for, not its temporary.
    std::string what = e.what();
    for (size_t at = what.find(tmp); at != std::string::npos; at = what.find(tmp, at + path.size())) {
      what.replace(at, tmp.size(), path);
    }
    throw InputError(what);
  }
}

void OutputSet::AddDirectory(const std::string& path, const std::string& marker,
                             const std::function<void(const std::string&)>& write) {
  CheckDirectoryOutput(path, marker);
  fs::path p = fs::path(path).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();  // "out/trade/"
  std::error_code ec;
  const fs::path tmp = p.parent_path() / ("." + p.filename().string() + ".tmp" + std::to_string(getpid()));
  fs::remove_all(tmp, ec);
  if (!fs::create_directory(tmp, ec)) throw InputError(path, 0, "cannot create a directory beside it: " + ec.message());
  pending_.push_back({tmp.string(), p.string(), true});
  write(tmp.string());
}

void OutputSet::Commit() {
  for (const Pending& p : pending_) {
    if (p.directory) {
      // The old directory moves aside first, so a failed rename leaves it.
      std::error_code ec;
      const std::string old = p.tmp + ".old";
      const bool had_old = fs::exists(p.path, ec);
      if (had_old && std::rename(p.path.c_str(), old.c_str()) != 0) {
        throw InputError(p.path, 0, "cannot replace the directory");
      }
      if (std::rename(p.tmp.c_str(), p.path.c_str()) != 0) {
        if (had_old) std::rename(old.c_str(), p.path.c_str());
        throw InputError(p.path, 0, "cannot write output directory");
      }
      if (had_old) fs::remove_all(old, ec);
      continue;
    }
    if (std::rename(p.tmp.c_str(), p.path.c_str()) != 0) {
      throw InputError(p.path, 0, "cannot write output file");
    }
  }
  pending_.clear();
}

void CheckDirectoryOutput(const std::string& path, const std::string& marker) {
  fs::path p = fs::path(path).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  std::error_code ec;
  if (fs::exists(p, ec)) {
    if (!fs::is_directory(p, ec)) throw InputError(path, 0, "exists and is not a directory");
    if (!fs::is_empty(p, ec) && !fs::exists(p / marker, ec)) {
      throw InputError(path, 0, "is a non-empty directory without " + marker + "; refusing to replace it");
    }
  }
  CheckWritable(p.string());
}

void CheckWritable(const std::string& path) {
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(path, 0, "cannot write: directory " + dir.string() + " does not exist");
  if (access(dir.c_str(), W_OK) != 0) throw InputError(path, 0, "cannot write: directory " + dir.string() + " is not writable");
}

void WriteFileAtomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  OutputSet set;
  set.Add(path, write);
  set.Commit();
}

}  // namespace kdrt
