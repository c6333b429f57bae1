// The scene as loaded from a file or made by a generator: a triangle soup
// with per-triangle surface colours and an optional NFF camera.
//
// Triangle numbering is part of kdrt's output contract: triangles are numbered
// in file order, and a polygon with n vertices becomes n-2 triangles fanned
// from its first vertex (v0,v1,v2), (v0,v2,v3), ... Zero-area triangles keep
// their number but are never hit (the builder leaves them out of the tree).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace kdrt {

// NFF viewing specification. `angle` (degrees) spans the centres of the first
// and last pixel columns (and rows, scaled by the aspect ratio); row 0 is the
// top of the image.
struct Camera {
  glm::vec3 from{0, 0, 1};
  glm::vec3 at{0, 0, 0};
  glm::vec3 up{0, 1, 0};
  float angle_deg = 45.0f;
  float hither = 0.0f;  // rays start at t = hither (direction normalised)
  int width = 512;
  int height = 512;
};

struct Triangle {
  glm::vec3 v0, v1, v2;
};

// The rest of an NFF `f` (fill) line: diffuse and specular weights and the
// Phong exponent (transmission and refraction are read and not used).
// Generators and OBJ/PLY/OFF files get the default.
struct Finish {
  float kd = 0.8f;
  float ks = 0.2f;
  float shine = 20.0f;
};

// An NFF `l` point light; without a colour, every light of the scene gets
// white / sqrt(number of lights), the SPD convention.
struct Light {
  glm::vec3 position{0, 0, 0};
  glm::vec3 color{1, 1, 1};
  bool has_color = false;
};

struct Scene {
  std::vector<Triangle> triangles;  // primitive id = index, file order
  std::vector<uint32_t> material;   // per triangle: index into colors (and finishes)
  std::vector<glm::vec3> colors;    // NFF `f` surface colours (default white)
  std::vector<Finish> finishes;     // NFF `f` finish, one per colour
  std::vector<Light> lights;        // NFF `l` lines, in file order
  std::optional<Camera> camera;     // from the file's `v` block, if any
  glm::vec3 background{0, 0, 0};
  std::string source;               // file name or generator description
  // Data of the file the loader left out ("file:line: what"): statements
  // kdrt does not read, values after the declared elements. The commands
  // print them as warnings and list them in their JSON "warnings".
  std::vector<std::string> warnings;
};

// At most this many camera rays per frame (8192 x 8192): the rays alone take
// 2 GiB. An NFF `resolution` or a --res beyond it is an input error.
constexpr long long kMaxCameraPixels = 1LL << 26;

// Loads NFF (.nff), OBJ, PLY or OFF (by extension). Throws InputError with
// file:line on malformed input, NaN/Inf coordinates, an empty scene or one
// whose triangles all have zero area.
Scene LoadScene(const std::string& path);

// How NFF spheres (`s`) and cones/cylinders (`c`) become triangles; see
// docs/scenes.md. A sphere gets sphere_segments slices around its z axis and
// max(2, sphere_segments / 2) stacks from pole to pole:
// 2 * segments * (stacks - 1) triangles. A cone gets cone_segments sides, two
// triangles each (one where a radius is zero), open ends as in NFF; with
// cone_aspect > 0 its sides are cut into bands along the axis so that no cell
// is more than cone_aspect times longer than wide (ConeBands).
struct LoadOptions {
  int sphere_segments = 16;  // 3 .. 4096
  int cone_segments = 16;    // 3 .. 4096
  double cone_aspect = 0;    // 0: one band from end to end; else at least 1
  // Refuse (InputError) data the reader would leave out, instead of a warning
  // in Scene::warnings.
  bool strict = false;
};

Scene LoadScene(const std::string& path, const LoadOptions& options);

// Twice the area is zero (exactly, in float arithmetic on the cross product):
// such triangles can never be hit by the watertight test.
bool IsDegenerate(const Triangle& t);

// The camera used when a scene has none: looks at the centre of the bounding
// box along -z from outside it, with a 45 degree field of view that frames
// the box (see camera.cpp for the exact rule).
Camera AutoCamera(const Scene& scene, int width, int height);

}  // namespace kdrt
