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

namespace {

RTCRay ToEmbree(const Ray& ray) {
  RTCRay r;
  r.org_x = ray.o.x;
  r.org_y = ray.o.y;
  r.org_z = ray.o.z;
  r.dir_x = ray.d.x;
  r.dir_y = ray.d.y;
  r.dir_z = ray.d.z;
  r.tnear = ray.tmin;
  r.tfar = ray.tmax;
  r.time = 0;
  r.mask = 0xFFFFFFFFu;
  r.id = 0;
  r.flags = 0;
  return r;
}

}  // namespace

EmbreeScene::~EmbreeScene() {
  if (impl_->scene) rtcReleaseScene(impl_->scene);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

Hit EmbreeScene::Intersect(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray = ToEmbree(ray);
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

namespace {

// Fills an Embree SoA ray packet (RTCRay4/8/16) from rays[0..n); lanes past
// n are invalid.
template <int N, class RayN>
void FillPacket(const Ray* rays, int n, RayN* ray, int* valid) {
  for (int i = 0; i < N; ++i) {
    const Ray& r = rays[i < n ? i : 0];
    valid[i] = i < n ? -1 : 0;
    ray->org_x[i] = r.o.x;
    ray->org_y[i] = r.o.y;
    ray->org_z[i] = r.o.z;
    ray->dir_x[i] = r.d.x;
    ray->dir_y[i] = r.d.y;
    ray->dir_z[i] = r.d.z;
    ray->tnear[i] = r.tmin;
    ray->tfar[i] = r.tmax;
    ray->time[i] = 0;
    ray->mask[i] = 0xFFFFFFFFu;
    ray->id[i] = static_cast<unsigned>(i);
    ray->flags[i] = 0;
  }
}

template <int N, class RayHitN, class Fn>
void IntersectN(RTCScene scene, const Ray* rays, int n, Hit* out, Fn intersect) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  alignas(64) int valid[N];
  alignas(64) RayHitN rh;
  FillPacket<N>(rays, n, &rh.ray, valid);
  for (int i = 0; i < N; ++i) {
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  intersect(valid, scene, &context, &rh);
  for (int i = 0; i < n; ++i) {
    out[i] = Hit{};
    if (rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
    out[i].t = rh.ray.tfar[i];
    out[i].prim = rh.hit.primID[i];
    out[i].u = rh.hit.u[i];
    out[i].v = rh.hit.v[i];
  }
}

template <int N, class RayN, class Fn>
void OccludedN(RTCScene scene, const Ray* rays, int n, bool* out, Fn occluded) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  alignas(64) int valid[N];
  alignas(64) RayN ray;
  FillPacket<N>(rays, n, &ray, valid);
  occluded(valid, scene, &context, &ray);
  // Embree sets tfar to -inf on an occluded ray.
  for (int i = 0; i < n; ++i) out[i] = ray.tfar[i] < 0.0f;
}

}  // namespace

void EmbreeScene::IntersectPacket(const Ray* rays, int n, int width, Hit* out) const {
  if (width == 4) {
    IntersectN<4, RTCRayHit4>(impl_->scene, rays, n, out,
                              [](int* v, RTCScene s, RTCIntersectContext* c, RTCRayHit4* rh) { rtcIntersect4(v, s, c, rh); });
  } else if (width == 8) {
    IntersectN<8, RTCRayHit8>(impl_->scene, rays, n, out,
                              [](int* v, RTCScene s, RTCIntersectContext* c, RTCRayHit8* rh) { rtcIntersect8(v, s, c, rh); });
  } else {
    IntersectN<16, RTCRayHit16>(impl_->scene, rays, n, out, [](int* v, RTCScene s, RTCIntersectContext* c,
                                                              RTCRayHit16* rh) { rtcIntersect16(v, s, c, rh); });
  }
}

bool EmbreeScene::Occluded(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r = ToEmbree(ray);
  rtcOccluded1(impl_->scene, &context, &r);
  return r.tfar < 0.0f;
}

void EmbreeScene::OccludedPacket(const Ray* rays, int n, int width, bool* out) const {
  if (width == 4) {
    OccludedN<4, RTCRay4>(impl_->scene, rays, n, out,
                          [](int* v, RTCScene s, RTCIntersectContext* c, RTCRay4* r) { rtcOccluded4(v, s, c, r); });
  } else if (width == 8) {
    OccludedN<8, RTCRay8>(impl_->scene, rays, n, out,
                          [](int* v, RTCScene s, RTCIntersectContext* c, RTCRay8* r) { rtcOccluded8(v, s, c, r); });
  } else {
    OccludedN<16, RTCRay16>(impl_->scene, rays, n, out,
                            [](int* v, RTCScene s, RTCIntersectContext* c, RTCRay16* r) { rtcOccluded16(v, s, c, r); });
  }
}

}  // namespace kdrt
