// Pieces shared by the generators (not part of the public interface).
#pragma once

#include <glm/vec3.hpp>

#include "scene/scene.h"
#include "scene/scene_builder.h"

namespace kdrt::gen {

Scene GenerateRoom(int size);
Scene GenerateBalls(int size);
Scene GenerateRings(int size);
Scene GenerateTetra(int size);
Scene GenerateTree(int size);
Scene GenerateGears(int size);
Scene GenerateStrips(int size);
Scene GenerateHoops(int size, const LoadOptions& tessellation);

constexpr double kPi = 3.14159265358979323846;
constexpr int kDefaultResolution = 512;

// A camera that looks at the centre of the scene's bounds from direction
// `toward_eye` (any length), far enough that the bounding sphere fits in
// `angle_deg`.
Camera FramingCamera(const Scene& scene, const glm::dvec3& toward_eye, const glm::vec3& up,
                     double angle_deg);

// `v` rotated by `angle` radians around the unit `axis` (Rodrigues).
glm::dvec3 Rotate(const glm::dvec3& v, const glm::dvec3& axis, double angle);

}  // namespace kdrt::gen
