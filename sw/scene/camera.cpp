#include "scene/camera.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "common/error.h"

namespace kdrt {

namespace {

constexpr double kPi = 3.14159265358979323846;

bool Finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Tangent of the half angle divided by the number of pixel steps from the
// centre to the first column: the pitch on a plane at unit distance. With a
// single column the angle describes the rows instead; with a single pixel
// there is nothing to span.
double UnitPitch(double angle_deg, int width, int height) {
  int steps = width > 1 ? width - 1 : height - 1;
  if (steps == 0) return 0.0;
  return 2.0 * std::tan(angle_deg * kPi / 360.0) / steps;
}

}  // namespace

void ValidateCamera(const Camera& cam) {
  if (!Finite(cam.from) || !Finite(cam.at) || !Finite(cam.up) || !std::isfinite(cam.angle_deg) ||
      !std::isfinite(cam.hither)) {
    throw InputError("camera: NaN or Inf value");
  }
  if (cam.from == cam.at) throw InputError("camera: 'at' equals 'from'");
  glm::dvec3 view = glm::dvec3(cam.at) - glm::dvec3(cam.from);
  if (glm::cross(view, glm::dvec3(cam.up)) == glm::dvec3(0.0)) {
    throw InputError("camera: 'up' is zero or parallel to the view direction");
  }
  if (!(cam.angle_deg > 0.0f && cam.angle_deg < 180.0f)) {
    throw InputError("camera: angle must be in (0, 180) degrees");
  }
  if (cam.hither < 0.0f) throw InputError("camera: hither must not be negative");
  if (cam.width < 1 || cam.height < 1) throw InputError("camera: resolution must be at least 1x1");
}

CameraFrame MakeCameraFrame(const Camera& cam) {
  ValidateCamera(cam);
  CameraFrame f;
  f.from = glm::dvec3(cam.from);
  f.view = glm::dvec3(cam.at) - f.from;
  f.right = glm::normalize(glm::cross(f.view, glm::dvec3(cam.up)));
  f.up = glm::normalize(glm::cross(f.right, f.view));
  // Scale the unit-distance pitch to the plane through `at`.
  double pitch = UnitPitch(cam.angle_deg, cam.width, cam.height) * glm::length(f.view);
  f.pitch_x = pitch;
  f.pitch_y = pitch;
  f.width = cam.width;
  f.height = cam.height;
  f.hither = cam.hither;
  return f;
}

CameraRay PrimaryRay(const CameraFrame& f, int px, int py) {
  // Offsets from the image centre in pixel steps; exact halves in double.
  double sx = px - 0.5 * (f.width - 1);
  double sy = 0.5 * (f.height - 1) - py;
  glm::dvec3 dir = f.view + (sx * f.pitch_x) * f.right + (sy * f.pitch_y) * f.up;
  dir = glm::normalize(dir);
  CameraRay ray;
  ray.o = glm::vec3(f.from);
  ray.d = glm::vec3(static_cast<float>(dir.x), static_cast<float>(dir.y),
                    static_cast<float>(dir.z));
  ray.tmin = f.hither;
  return ray;
}

CameraRay PrimaryRay(const Camera& cam, int px, int py) {
  return PrimaryRay(MakeCameraFrame(cam), px, py);
}

// The automatic camera, declared in scene.h. Rule:
//   box    = axis-aligned bounds of all triangle vertices (degenerate ones too);
//   centre = box centre, radius R = half the box diagonal (a sphere that
//            holds the box; R = 1 for an empty or single-point box);
//   angle  = 45 degrees, up = +y, hither = 0, the given resolution;
//   t      = tangent of the half angle of the narrower image axis between
//            outer pixel centres (the 45 degree axis or the one scaled by the
//            aspect ratio);
//   from   = centre + (0, 0, R / sin(atan t)): on the +z side, looking along
//            -z, at the distance where the sphere just touches the
//            narrower field, so the whole box is inside the image.
Camera AutoCamera(const Scene& scene, int width, int height) {
  if (width < 1 || height < 1) throw InputError("camera: resolution must be at least 1x1");
  glm::dvec3 lo(0.0), hi(0.0);
  bool any = false;
  for (const Triangle& t : scene.triangles) {
    for (const glm::vec3* v : {&t.v0, &t.v1, &t.v2}) {
      if (!Finite(*v)) continue;
      glm::dvec3 p(*v);
      lo = any ? glm::min(lo, p) : p;
      hi = any ? glm::max(hi, p) : p;
      any = true;
    }
  }
  glm::dvec3 centre = 0.5 * (lo + hi);
  double radius = 0.5 * glm::length(hi - lo);
  if (!(radius > 0.0)) radius = 1.0;

  Camera cam;
  cam.angle_deg = 45.0f;
  cam.width = width;
  cam.height = height;
  cam.hither = 0.0f;
  cam.up = glm::vec3(0.0f, 1.0f, 0.0f);
  double pitch = UnitPitch(cam.angle_deg, width, height);
  double half_x = 0.5 * pitch * (width - 1);
  double half_y = 0.5 * pitch * (height - 1);
  double t = std::min(half_x > 0.0 ? half_x : half_y, half_y > 0.0 ? half_y : half_x);
  if (!(t > 0.0)) t = std::tan(22.5 * kPi / 180.0);  // a single pixel
  double distance = radius * std::sqrt(1.0 + t * t) / t;  // R / sin(atan t)
  cam.at = glm::vec3(centre);
  cam.from = glm::vec3(centre + glm::dvec3(0.0, 0.0, distance));
  if (!Finite(cam.from) || cam.from == cam.at) {
    // The box is too large (or too small) for a float camera outside it: say
    // which triangle spans it, as the scene has no camera of its own.
    size_t far = 0;
    double far_extent = -1.0;
    for (size_t i = 0; i < scene.triangles.size(); ++i) {
      const Triangle& t = scene.triangles[i];
      for (const glm::vec3* v : {&t.v0, &t.v1, &t.v2}) {
        const double e = glm::length(glm::dvec3(*v) - centre);
        if (e > far_extent) {
          far_extent = e;
          far = i;
        }
      }
    }
    char text[400];
    std::snprintf(text, sizeof text,
                  "no camera in the scene, and the automatic one does not fit in float: it would stand at "
                  "z = %g looking at z = %g (the bounding box spans %g; triangle %zu reaches %g from its "
                  "centre); give the scene a camera (NFF `v` block) or use --camera",
                  centre.z + distance, centre.z, 2.0 * radius, far, far_extent);
    throw InputError(scene.source, 0, text);
  }
  return cam;
}

}  // namespace kdrt
