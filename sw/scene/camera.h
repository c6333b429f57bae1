// Primary rays for the NFF viewing model (see docs/scenes.md).
//
// `angle` is the horizontal angle between the rays through the centres of the
// first and last pixel columns. Pixels are square, so the vertical angle
// between the first and last row centres follows from height/width. Row 0 is
// the top of the image, column 0 the left. The image plane passes through
// `at`, so the centre of an odd-sized image looks exactly at `at`.
//
// Everything is computed in double and rounded once to float at the end, so
// a ray depends only on the camera and the pixel, never on the compiler's
// choice of instructions.
#pragma once

#include <glm/vec3.hpp>

#include "scene/scene.h"

namespace kdrt {

struct CameraRay {
  glm::vec3 o;     // == camera.from
  glm::vec3 d;     // unit length (rounded to float)
  float tmin;      // == camera.hither
};

// Throws InputError("camera: ...") if from == at, up is zero or parallel to
// the view direction, the angle is not in (0, 180) degrees, hither is
// negative, a size is < 1 or any value is not finite.
void ValidateCamera(const Camera& cam);

// The camera's orthonormal basis and pixel pitch, computed once per image.
struct CameraFrame {
  glm::dvec3 from, view;  // view = at - from (not normalised)
  glm::dvec3 right, up;   // unit vectors; right = view x up (normalised)
  double pitch_x, pitch_y;  // world offsets of one pixel step on the plane through `at`
  int width, height;
  float hither;
};
CameraFrame MakeCameraFrame(const Camera& cam);  // validates

// The ray through the centre of pixel (px, py). Pixels outside the image
// give the extrapolated ray (no error).
CameraRay PrimaryRay(const CameraFrame& frame, int px, int py);
CameraRay PrimaryRay(const Camera& cam, int px, int py);

}  // namespace kdrt
