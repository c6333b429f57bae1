#include "oracle/embree_scene.h"

#include <embree3/rtcore.h>

#include <chrono>
#include <limits>
#include <stdexcept>
#include <string>

namespace kdrt {

struct EmbreeScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
};

EmbreeScene::EmbreeScene(const Scene& scene, int threads, bool robust) : impl_(std::make_unique<Impl>()) {
  const std::string config = "threads=" + std::to_string(threads) + ",set_affinity=0";
  impl_->device = rtcNewDevice(config.c_str());
  if (!impl_->device) throw std::runtime_error("embree: cannot create device");
  const auto start = std::chrono::steady_clock::now();
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  if (robust) rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_HIGH);
  const size_t n = scene.triangles.size();
  auto* verts = static_cast<float*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
  auto* index = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  for (size_t i = 0; i < n; ++i) {
    const Triangle& t = scene.triangles[i];
    const glm::vec3* v[3] = {&t.v0, &t.v1, &t.v2};
    for (int k = 0; k < 3; ++k) {
      for (int c = 0; c < 3; ++c) verts[9 * i + 3 * k + c] = (*v[k])[c];
      index[3 * i + k] = static_cast<unsigned>(3 * i + k);
    }
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(impl_->scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(impl_->scene);
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

EmbreeScene::~EmbreeScene() {
  if (impl_->scene) rtcReleaseScene(impl_->scene);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

Hit EmbreeScene::Intersect(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray.org_x = ray.o.x;
  rh.ray.org_y = ray.o.y;
  rh.ray.org_z = ray.o.z;
  rh.ray.dir_x = ray.d.x;
  rh.ray.dir_y = ray.d.y;
  rh.ray.dir_z = ray.d.z;
  rh.ray.tnear = ray.tmin;
  rh.ray.tfar = ray.tmax;
  rh.ray.time = 0;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &rh);
  Hit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.t = rh.ray.tfar;
  h.prim = rh.hit.primID;
  h.u = rh.hit.u;
  h.v = rh.hit.v;
  return h;
}

}  // namespace kdrt
