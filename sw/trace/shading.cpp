#include "trace/shading.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "scene/camera.h"

namespace kdrt {
namespace {

// Ambient light: what a surface gets with every light blocked (times its
// ambient-occlusion visibility when AO rays are traced).
constexpr double kAmbient = 0.1;
// Secondary rays start this far (times the scene diagonal) off the surface,
// on the side the primary ray came from, so they do not hit their own
// triangle; shadow rays stop just short of the light.
constexpr double kOffset = 1e-4;
constexpr float kShadowTmax = 0.9999f;
// Ambient-occlusion rays reach this far (times the scene diagonal).
constexpr double kAoRadius = 0.1;
constexpr double kPi = 3.14159265358979323846;

// The scene box diagonal (1 for an empty or single-point box).
double Diagonal(const Scene& scene) {
  if (scene.triangles.empty()) return 1.0;
  glm::dvec3 lo(scene.triangles[0].v0), hi = lo;
  for (const Triangle& t : scene.triangles) {
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      lo = glm::min(lo, glm::dvec3(v));
      hi = glm::max(hi, glm::dvec3(v));
    }
  }
  const double d = glm::length(hi - lo);
  return d > 0 ? d : 1.0;
}

// splitmix64: a counter-based generator, so sample k of pixel i is the same
// number whatever else is drawn.
uint64_t Mix(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

double Uniform(uint32_t seed, uint32_t pixel, uint32_t sample, uint32_t dim) {
  const uint64_t h = Mix(Mix(Mix(seed) ^ pixel) ^ (uint64_t{sample} << 8 | dim));
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

// A cosine-weighted direction around unit normal n (Duff et al. 2017's
// orthonormal basis).
glm::dvec3 CosineDirection(const glm::dvec3& n, double r1, double r2) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z), b = n.x * n.y * a;
  const glm::dvec3 t(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const glm::dvec3 bt(b, sign + n.y * n.y * a, -n.y);
  const double phi = 2 * kPi * r1, r = std::sqrt(r2);
  return glm::normalize(t * (r * std::cos(phi)) + bt * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1 - r2)));
}

glm::vec3 ToFloat(const glm::dvec3& v) { return glm::vec3(v); }

}  // namespace

struct FrameShader::Surface {
  glm::dvec3 p;       // hit point from the barycentrics
  glm::dvec3 n;       // unit geometric normal, facing the ray's origin
  glm::dvec3 origin;  // where secondary rays start
  glm::dvec3 color;
  Finish finish;
};

std::vector<Light> ShadingLights(const Scene& scene) {
  if (!scene.lights.empty()) return scene.lights;
  const Camera cam = scene.camera ? *scene.camera : AutoCamera(scene, 512, 512);
  const CameraFrame f = MakeCameraFrame(cam);
  Light l;
  l.position = ToFloat(f.from + 0.25 * Diagonal(scene) * (f.up + f.right));
  return {l};
}

FrameShader::FrameShader(const Scene& scene, const ShadingOptions& options)
    : scene_(scene), options_(options), lights_(ShadingLights(scene)) {
  const float white = static_cast<float>(1.0 / std::sqrt(static_cast<double>(lights_.size())));
  for (const Light& l : lights_) intensity_.push_back(l.has_color ? l.color : glm::vec3(white));
  const double diagonal = Diagonal(scene);
  offset_ = static_cast<float>(kOffset * diagonal);
  ao_radius_ = static_cast<float>(kAoRadius * diagonal);
}

FrameShader::Surface FrameShader::SurfaceAt(const Ray& ray, const Hit& hit) const {
  Surface s;
  const Triangle& t = scene_.triangles[hit.prim];
  const glm::dvec3 v0(t.v0), e1 = glm::dvec3(t.v1) - v0, e2 = glm::dvec3(t.v2) - v0;
  s.p = v0 + e1 * static_cast<double>(hit.u) + e2 * static_cast<double>(hit.v);
  const glm::dvec3 d(ray.d), c = glm::cross(e1, e2);
  const double len = glm::length(c);
  s.n = len > 0 ? c / len : -glm::normalize(d);
  if (glm::dot(s.n, d) > 0) s.n = -s.n;
  s.origin = s.p + s.n * static_cast<double>(offset_);
  const uint32_t m = hit.prim < scene_.material.size() ? scene_.material[hit.prim] : 0;
  s.color = m < scene_.colors.size() ? glm::dvec3(scene_.colors[m]) : glm::dvec3(1.0);
  s.finish = m < scene_.finishes.size() ? scene_.finishes[m] : Finish{};
  return s;
}

std::vector<RayPass> FrameShader::SecondaryPasses(const std::vector<Ray>& primary,
                                                  const std::vector<Hit>& primary_hits) const {
  RayPass shadow{"shadow", Query::kAny, {}, {}, {}};
  RayPass ao{"ao", Query::kAny, {}, {}, {}};
  RayPass bounce{"bounce", Query::kClosest, {}, {}, {}};
  auto add = [](RayPass& pass, const glm::dvec3& o, const glm::dvec3& d, float tmax, size_t pixel, int sample) {
    pass.rays.push_back(Ray{ToFloat(o), ToFloat(d), 0.0f, tmax});
    pass.pixel.push_back(static_cast<uint32_t>(pixel));
    pass.sample.push_back(static_cast<uint16_t>(sample));
  };
  for (size_t i = 0; i < primary.size(); ++i) {
    if (!primary_hits[i].IsHit()) continue;
    const Surface s = SurfaceAt(primary[i], primary_hits[i]);
    const glm::vec3 o = ToFloat(s.origin);
    for (size_t l = 0; l < lights_.size(); ++l) {
      // Rays are built from the float origin the ray file will hold, so the
      // light is exactly at t = 1.
      const glm::vec3 to_light = lights_[l].position - o;
      if (glm::dot(glm::dvec3(to_light), s.n) <= 0 || to_light == glm::vec3(0.0f)) continue;
      add(shadow, s.origin, glm::dvec3(to_light), kShadowTmax, i, static_cast<int>(l));
    }
    for (int k = 0; k < options_.ao_samples; ++k) {
      const glm::dvec3 d = CosineDirection(s.n, Uniform(options_.seed, static_cast<uint32_t>(i), k, 0),
                                           Uniform(options_.seed, static_cast<uint32_t>(i), k, 1));
      add(ao, s.origin, d * static_cast<double>(ao_radius_), 1.0f, i, k);
    }
    if (options_.bounce) {
      const glm::dvec3 d = CosineDirection(s.n, Uniform(options_.seed, static_cast<uint32_t>(i), 0, 2),
                                           Uniform(options_.seed, static_cast<uint32_t>(i), 0, 3));
      add(bounce, s.origin, d, INFINITY, i, 0);
    }
  }
  std::vector<RayPass> passes;
  passes.push_back(std::move(shadow));
  if (options_.ao_samples > 0) passes.push_back(std::move(ao));
  if (options_.bounce) passes.push_back(std::move(bounce));
  return passes;
}

std::vector<float> FrameShader::Shade(const std::vector<Ray>& primary, const std::vector<Hit>& primary_hits,
                                      const std::vector<RayPass>& passes,
                                      const std::vector<std::vector<Hit>>& hits) const {
  std::vector<float> rgb(3 * primary.size());
  // Every pass lists its rays in primary-ray order: one cursor each.
  std::vector<size_t> cursor(passes.size(), 0);
  const glm::dvec3 background(scene_.background);
  for (size_t i = 0; i < primary.size(); ++i) {
    glm::dvec3 c = background;
    if (primary_hits[i].IsHit()) {
      const Surface s = SurfaceAt(primary[i], primary_hits[i]);
      const glm::dvec3 view = glm::normalize(glm::dvec3(primary[i].d));
      std::vector<uint8_t> lit(lights_.size(), 0);
      int ao_open = 0;
      glm::dvec3 indirect(0.0);
      for (size_t k = 0; k < passes.size(); ++k) {
        const RayPass& pass = passes[k];
        for (; cursor[k] < pass.rays.size() && pass.pixel[cursor[k]] == i; ++cursor[k]) {
          const size_t r = cursor[k];
          const Hit& h = hits[k][r];
          if (pass.name == "shadow") {
            lit[pass.sample[r]] = !h.IsHit();
          } else if (pass.name == "ao") {
            ao_open += !h.IsHit();
          } else if (pass.name == "bounce") {
            // Light from the sky (background) along the bounce, or the ambient
            // light the surface it hits reflects.
            indirect = h.IsHit() ? kAmbient * SurfaceAt(pass.rays[r], h).color : background;
          }
        }
      }
      const double visibility = options_.ao_samples > 0 ? static_cast<double>(ao_open) / options_.ao_samples : 1.0;
      c = kAmbient * visibility * s.color + static_cast<double>(s.finish.kd) * s.color * indirect;
      for (size_t l = 0; l < lights_.size(); ++l) {
        if (!lit[l]) continue;
        const glm::dvec3 to_light = glm::normalize(glm::dvec3(lights_[l].position) - s.p);
        const double diffuse = std::max(0.0, glm::dot(s.n, to_light));
        const glm::dvec3 half = glm::normalize(to_light - view);
        const double specular = std::pow(std::max(0.0, glm::dot(s.n, half)), static_cast<double>(s.finish.shine));
        c += glm::dvec3(intensity_[l]) *
             (static_cast<double>(s.finish.kd) * diffuse * s.color + static_cast<double>(s.finish.ks) * specular);
      }
    }
    for (int k = 0; k < 3; ++k) rgb[3 * i + k] = static_cast<float>(c[k]);
  }
  return rgb;
}

}  // namespace kdrt
