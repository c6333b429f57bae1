#include "trace/rays_file.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>

#include "common/error.h"
#include "scene/text_fields.h"
#include "trace/output_file.h"

namespace kdrt {
namespace {

constexpr char kRaysMagic[8] = {'K', 'D', 'R', 'T', 'R', 'A', 'Y', 'S'};
constexpr uint32_t kRaysVersion = 2;
constexpr size_t kRaysHeaderBytesV1 = 16;
constexpr size_t kRaysHeaderBytes = 20;
constexpr size_t kRayBytes = 32;

uint32_t ReadU32(const char* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

}  // namespace

std::vector<Ray> ReadRaysFile(const std::string& path, Query* query) {
  // Missing, a directory or unreadable: an InputError naming the file.
  const std::string bytes = ReadWholeFile(path);
  if (bytes.size() < kRaysHeaderBytesV1 || std::memcmp(bytes.data(), kRaysMagic, 8) != 0) {
    throw InputError(path, 0, "not a kdrt ray file (expected magic KDRTRAYS)");
  }
  const uint32_t version = ReadU32(bytes.data() + 8);
  if (version != 1 && version != kRaysVersion) {
    throw InputError(path, 0, "ray file version " + std::to_string(version) + ", expected 1 or 2");
  }
  const size_t header = version == 1 ? kRaysHeaderBytesV1 : kRaysHeaderBytes;
  if (bytes.size() < header) throw InputError(path, 0, "ray file ends inside its header");
  const uint32_t query_word = version == 1 ? 0 : ReadU32(bytes.data() + 16);
  if (query_word > 1) {
    throw InputError(path, 0, "query " + std::to_string(query_word) + ": expected 0 (closest hit) or 1 (any hit)");
  }
  if (query) *query = query_word == 1 ? Query::kAny : Query::kClosest;
  const uint64_t count = ReadU32(bytes.data() + 12);
  if (bytes.size() != header + count * kRayBytes) {
    throw InputError(path, 0,
                     "header says " + std::to_string(count) + " rays (" + std::to_string(header + count * kRayBytes) +
                         " bytes) but the file has " + std::to_string(bytes.size()) + " bytes");
  }
  if (count == 0) throw InputError(path, 0, "ray file holds no rays");
  std::vector<Ray> rays(count);
  for (uint64_t i = 0; i < count; ++i) {
    float f[8];
    std::memcpy(f, bytes.data() + header + i * kRayBytes, sizeof(f));
    auto fail = [&](const std::string& what) {
      throw InputError(path, 0, "ray " + std::to_string(i) + ": " + what);
    };
    for (int k = 0; k < 6; ++k) {
      if (!std::isfinite(f[k])) fail(std::string(k < 3 ? "origin" : "direction") + " is NaN or infinite");
    }
    if (f[3] == 0 && f[4] == 0 && f[5] == 0) fail("direction is zero");
    if (std::isnan(f[6]) || std::isnan(f[7])) fail("tmin or tmax is NaN");
    if (f[6] < 0 || std::isinf(f[6])) fail("tmin must be finite and >= 0");
    if (f[7] < f[6]) fail("tmax is smaller than tmin");
    rays[i].o = {f[0], f[1], f[2]};
    rays[i].d = {f[3], f[4], f[5]};
    rays[i].tmin = f[6];
    rays[i].tmax = f[7];
  }
  return rays;
}

void WriteRaysFile(const std::string& path, const std::vector<Ray>& rays, Query query) {
  WriteFileAtomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw InputError(path, 0, "cannot create ray file");
    const uint32_t version = kRaysVersion, count = static_cast<uint32_t>(rays.size());
    const uint32_t query_word = query == Query::kAny ? 1 : 0;
    out.write(kRaysMagic, 8);
    out.write(reinterpret_cast<const char*>(&version), 4);
    out.write(reinterpret_cast<const char*>(&count), 4);
    out.write(reinterpret_cast<const char*>(&query_word), 4);
    for (const Ray& r : rays) {
      const float f[8] = {r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z, r.tmin, r.tmax};
      out.write(reinterpret_cast<const char*>(f), sizeof(f));
    }
    if (!out) throw InputError(path, 0, "write failed");
  });
}

}  // namespace kdrt
