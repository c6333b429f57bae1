#include "scene/nff_writer.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

#include "common/error.h"

namespace kdrt {

namespace {

bool Finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void CheckWritable(const Scene& scene, const std::string& path) {
  if (scene.material.size() != scene.triangles.size() && !scene.material.empty()) {
    throw InputError(path, 0, "scene has a material list of the wrong length");
  }
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    const Triangle& t = scene.triangles[i];
    if (!Finite(t.v0) || !Finite(t.v1) || !Finite(t.v2)) {
      throw InputError(path, 0, "triangle " + std::to_string(i) + " has a NaN or Inf coordinate");
    }
    if (!scene.material.empty() && scene.material[i] >= scene.colors.size()) {
      throw InputError(path, 0, "triangle " + std::to_string(i) + " has no colour");
    }
  }
  for (const glm::vec3& c : scene.colors) {
    if (!Finite(c)) throw InputError(path, 0, "colour with a NaN or Inf component");
  }
  for (const Light& l : scene.lights) {
    if (!Finite(l.position) || !Finite(l.color)) throw InputError(path, 0, "light with a NaN or Inf component");
  }
  if (!Finite(scene.background)) throw InputError(path, 0, "background is NaN or Inf");
}

class TempFile {
 public:
  explicit TempFile(const std::string& path) : final_(path), temp_(path + ".tmpXXXXXX") {
    std::vector<char> name(temp_.begin(), temp_.end());
    name.push_back('\0');
    int fd = mkstemp(name.data());
    if (fd < 0) {
      throw InputError(path, 0, std::string("cannot create file: ") + std::strerror(errno));
    }
    temp_ = name.data();
    // mkstemp makes the file private; give it the permissions a plain
    // fopen would have.
    mode_t mask = umask(0);
    umask(mask);
    (void)fchmod(fd, 0666 & ~mask);
    file_ = fdopen(fd, "w");
    if (file_ == nullptr) {
      close(fd);
      std::remove(temp_.c_str());
      throw InputError(path, 0, "cannot open file for writing");
    }
  }
  ~TempFile() {
    if (file_ != nullptr) std::fclose(file_);
    if (!committed_) std::remove(temp_.c_str());
  }
  FILE* get() { return file_; }

  void Commit() {
    bool ok = std::fflush(file_) == 0 && !std::ferror(file_);
    ok = (std::fclose(file_) == 0) && ok;
    file_ = nullptr;
    if (!ok) throw InputError(final_, 0, "write error");
    if (std::rename(temp_.c_str(), final_.c_str()) != 0) {
      throw InputError(final_, 0, std::string("cannot rename into place: ") + std::strerror(errno));
    }
    committed_ = true;
  }

 private:
  std::string final_;
  std::string temp_;
  FILE* file_ = nullptr;
  bool committed_ = false;
};

void PutVec(FILE* f, const char* key, const glm::vec3& v) {
  std::fprintf(f, "%s %.9g %.9g %.9g\n", key, v.x, v.y, v.z);
}

}  // namespace

void WriteNff(const Scene& scene, const std::string& path) {
  CheckWritable(scene, path);
  TempFile out(path);
  FILE* f = out.get();
  std::string source = scene.source.empty() ? "(unnamed)" : scene.source;
  for (char& ch : source) {
    if (ch == '\n' || ch == '\r') ch = ' ';
  }
  std::fprintf(f, "# kdrt scene: %zu triangles, from %s\n", scene.triangles.size(),
               source.c_str());
  if (scene.camera) {
    const Camera& c = *scene.camera;
    std::fprintf(f, "v\n");
    PutVec(f, "from", c.from);
    PutVec(f, "at", c.at);
    PutVec(f, "up", c.up);
    std::fprintf(f, "angle %.9g\nhither %.9g\nresolution %d %d\n", c.angle_deg, c.hither, c.width,
                 c.height);
  }
  PutVec(f, "b", scene.background);
  for (const Light& l : scene.lights) {
    std::fprintf(f, "l %.9g %.9g %.9g", l.position.x, l.position.y, l.position.z);
    if (l.has_color) std::fprintf(f, " %.9g %.9g %.9g", l.color.x, l.color.y, l.color.z);
    std::fprintf(f, "\n");
  }
  bool have_fill = false;
  glm::vec3 current_color(0.0f);
  Finish current_finish;
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    const uint32_t m = scene.material.empty() ? 0 : scene.material[i];
    const glm::vec3 color = scene.material.empty() ? glm::vec3(1.0f) : scene.colors[m];
    const Finish finish = m < scene.finishes.size() ? scene.finishes[m] : Finish{};
    // Compare bit patterns so -0 and 0 are written as they are.
    if (!have_fill || std::memcmp(&color, &current_color, sizeof color) != 0 ||
        std::memcmp(&finish, &current_finish, sizeof finish) != 0) {
      std::fprintf(f, "f %.9g %.9g %.9g %.9g %.9g %.9g 0 1\n", color.x, color.y, color.z, finish.kd, finish.ks,
                   finish.shine);
      current_color = color;
      current_finish = finish;
      have_fill = true;
    }
    const Triangle& t = scene.triangles[i];
    std::fprintf(f, "p 3\n%.9g %.9g %.9g\n%.9g %.9g %.9g\n%.9g %.9g %.9g\n", t.v0.x, t.v0.y,
                 t.v0.z, t.v1.x, t.v1.y, t.v1.z, t.v2.x, t.v2.y, t.v2.z);
  }
  out.Commit();
}

}  // namespace kdrt
