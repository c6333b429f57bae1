#include "trace/frame.h"

#include <algorithm>
#include <cmath>

#include "fp/format.h"

namespace kdrt {
namespace {

constexpr fp::Format kF32 = fp::kFp32;

float Ldexp32(float x, int n) { return fp::FloatOf(fp::Ldexp(kF32, fp::BitsOf(x), n)); }

}  // namespace

Frame ChooseFrame(const Scene& world) {
  Frame f;
  if (world.triangles.empty()) return f;
  double lo[3], hi[3];
  for (int i = 0; i < 3; ++i) lo[i] = hi[i] = world.triangles[0].v0[i];
  for (const Triangle& t : world.triangles) {
    for (const glm::vec3* v : {&t.v0, &t.v1, &t.v2}) {
      for (int i = 0; i < 3; ++i) {
        lo[i] = std::min<double>(lo[i], (*v)[i]);
        hi[i] = std::max<double>(hi[i], (*v)[i]);
      }
    }
  }
  double reach = 0.0;
  for (int i = 0; i < 3; ++i) {
    f.origin[i] = static_cast<float>(0.5 * lo[i] + 0.5 * hi[i]);
    reach = std::max({reach, std::fabs(hi[i] - f.origin[i]), std::fabs(lo[i] - f.origin[i])});
  }
  if (reach > 0.0) {
    int e = 0;
    std::frexp(reach, &e);  // reach = m * 2^e, m in [0.5, 1)
    f.scale_log2 = std::clamp<int32_t>(kFrameReachLog2 - e, -kMaxFrameScaleLog2, kMaxFrameScaleLog2);
  }
  return f;
}

float ToFrame(float x, float origin, int32_t scale_log2) {
  return static_cast<float>(std::ldexp(static_cast<double>(x) - static_cast<double>(origin), scale_log2));
}

Scene ToFrame(const Scene& world, const Frame& frame) {
  Scene s = world;
  for (Triangle& t : s.triangles) {
    for (glm::vec3* v : {&t.v0, &t.v1, &t.v2}) {
      for (int i = 0; i < 3; ++i) (*v)[i] = ToFrame((*v)[i], frame.origin[i], frame.scale_log2);
    }
  }
  return s;
}

FramedRay ToFrame(const Ray& world, const Frame& frame) {
  return MapToFrame(
      world, frame,
      [](float a, float b) { return fp::FloatOf(fp::Sub(kF32, fp::BitsOf(a), fp::BitsOf(b))); }, Ldexp32);
}

float DistanceToWorld(float t, int32_t t_scale_log2) { return Ldexp32(t, t_scale_log2); }

}  // namespace kdrt
