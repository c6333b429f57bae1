#include "scenes/gen/gen_common.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace kdrt::gen {

Camera FramingCamera(const Scene& scene, const glm::dvec3& toward_eye, const glm::vec3& up,
                     double angle_deg) {
  glm::dvec3 lo(0.0), hi(0.0);
  bool any = false;
  for (const Triangle& t : scene.triangles) {
    for (const glm::vec3* v : {&t.v0, &t.v1, &t.v2}) {
      glm::dvec3 p(*v);
      lo = any ? glm::min(lo, p) : p;
      hi = any ? glm::max(hi, p) : p;
      any = true;
    }
  }
  glm::dvec3 centre = 0.5 * (lo + hi);
  double radius = 0.5 * glm::length(hi - lo);
  if (!(radius > 0.0)) radius = 1.0;
  double half = 0.5 * angle_deg * kPi / 180.0;
  Camera cam;
  cam.at = glm::vec3(centre);
  cam.from = glm::vec3(centre + glm::normalize(toward_eye) * (radius / std::sin(half)));
  cam.up = up;
  cam.angle_deg = static_cast<float>(angle_deg);
  cam.hither = 0.0f;
  cam.width = kDefaultResolution;
  cam.height = kDefaultResolution;
  return cam;
}

glm::dvec3 Rotate(const glm::dvec3& v, const glm::dvec3& axis, double angle) {
  double c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(axis, v) * s + axis * (glm::dot(axis, v) * (1.0 - c));
}

}  // namespace kdrt::gen
