// "gears": flat, thick toothed gears on a cols x rows grid over a floor, y
// up, in the spirit of the SPD "gears" database. Every gear has N teeth (N a
// multiple of 4), pitch radius 1, trapezoidal teeth (4 outline vertices each:
// root, tip, tip, root) and no hole, so its outline is one concave polygon of
// 4N vertices. The top and bottom faces are that polygon, added whole with
// SceneBuilder::AddFan and so fanned from its first vertex (a tip corner of
// tooth 0) like every polygon kdrt reads: 4N - 2 triangles per face, most of
// them long slivers across the gear, and where the fan passes the teeth it
// makes triangles of both windings that overlap one another and cover parts
// of the gaps between the teeth (outside the outline). That is deliberate:
// it is the hard case for kd-tree construction (long, overlapping,
// coplanar triangles) and for reduced-precision traversal. Each outline edge
// also gets a side quad (two triangles).
//
// Neighbouring gears mesh: they stand 2 + clearance apart and every other one
// (checkerboard) is turned by half a tooth, so a tooth faces a gap along x
// and along z (hence N divisible by 4). The turned gears also stand a little
// higher, so gears whose tip circles overlap never have coplanar faces
// (diagonal neighbours, at the same height, are too far apart to overlap).
//
// Size mapping: 16N - 4 triangles per gear plus a 2-triangle floor. A first
// tooth count N0 = 4 round(0.7 size^(1/4)) (at least 8) gives the number of
// gears G = round(size / (16 N0 - 4)), laid out as cols = round(sqrt(G)) by
// rows = round(G / cols); then N is the multiple of 4 (8..4096) that brings the total nearest to
// `size`. Teeth grow as size^(1/4), gears as size^(3/4).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include <glm/geometric.hpp>

#include "scene/tessellate.h"
#include "scenes/gen/gen_common.h"

namespace kdrt::gen {

namespace {

constexpr long kMinTeeth = 8;
constexpr long kMaxTeeth = 4096;
constexpr long kFloorTriangles = 2;
constexpr double kThickness = 0.3;
constexpr double kLift = 0.1;  // turned gears stand this much higher

long GearTriangles(long teeth) { return 16 * teeth - 4; }

struct GearsLayout {
  long cols = 1, rows = 1, teeth = kMinTeeth;
};

GearsLayout ChooseLayout(int size) {
  GearsLayout l;
  const long first = std::max(kMinTeeth, 4 * std::lround(0.7 * std::pow(size, 0.25)));
  const long gears =
      std::max(1L, std::lround(static_cast<double>(size - kFloorTriangles) / GearTriangles(first)));
  l.cols = std::max(1L, std::lround(std::sqrt(static_cast<double>(gears))));
  l.rows = std::max(1L, std::lround(static_cast<double>(gears) / l.cols));
  const long count = l.cols * l.rows;
  // The tooth count whose total is nearest to `size` (the smaller on a tie).
  auto miss = [&](long teeth) {
    return std::labs(count * GearTriangles(teeth) + kFloorTriangles - size);
  };
  while (l.teeth + 4 <= kMaxTeeth && miss(l.teeth + 4) < miss(l.teeth)) l.teeth += 4;
  return l;
}

// The gear outline around the origin in the y = 0 plane, counter-clockwise
// seen from +y, starting at the first tip corner of tooth 0.
std::vector<glm::dvec3> GearOutline(long teeth, double turn) {
  const double pitch = 2.0 * kPi / teeth;
  const double height = 0.55 * pitch;  // tooth height, radial
  const double r_root = 1.0 - 0.5 * height, r_tip = 1.0 + 0.5 * height;
  const double half_root = 0.25 * pitch, half_tip = 0.12 * pitch;  // angular half-widths
  std::vector<glm::dvec3> p;
  p.reserve(4 * teeth);
  // Angle a measured from +x toward -z, so increasing a runs counter-clockwise
  // seen from +y.
  auto at = [](double r, double a) { return glm::dvec3(r * std::cos(a), 0.0, -r * std::sin(a)); };
  for (long k = 0; k < teeth; ++k) {
    const double c = turn + k * pitch;  // tooth centre line
    p.push_back(at(r_root, c - half_root));
    p.push_back(at(r_tip, c - half_tip));
    p.push_back(at(r_tip, c + half_tip));
    p.push_back(at(r_root, c + half_root));
  }
  // Start at the first tip corner: fanned from a vertex that sticks out, more
  // of the fan's slivers cross the gaps between the teeth near it.
  std::rotate(p.begin(), p.begin() + 1, p.end());
  return p;
}

// One gear: top face (+y), bottom face (-y), then one side quad per outline
// edge, all as polygons fanned from their first vertex.
void AddGear(SceneBuilder& b, const std::vector<glm::dvec3>& outline, const glm::dvec3& base) {
  const size_t n = outline.size();
  const glm::dvec3 up(0.0, kThickness, 0.0);
  std::vector<glm::vec3> top(n), bottom(n);
  for (size_t i = 0; i < n; ++i) {
    top[i] = glm::vec3(base + outline[i] + up);
    bottom[i] = glm::vec3(base + outline[i]);
  }
  b.AddFan(top.data(), n);
  // The bottom face runs the other way round from the same first vertex.
  std::vector<glm::vec3> reversed(n);
  reversed[0] = bottom[0];
  for (size_t i = 1; i < n; ++i) reversed[i] = bottom[n - i];
  b.AddFan(reversed.data(), n);
  for (size_t i = 0; i < n; ++i) {
    const size_t j = (i + 1) % n;
    const glm::vec3 quad[4] = {bottom[i], bottom[j], top[j], top[i]};
    b.AddFan(quad, 4);
  }
}

}  // namespace

Scene GenerateGears(int size) {
  const GearsLayout l = ChooseLayout(size);
  const double pitch = 2.0 * kPi / l.teeth;
  const double spacing = 2.0 + 0.1 * pitch;  // centre distance: a little clearance
  const std::vector<glm::dvec3> plain = GearOutline(l.teeth, 0.0);
  const std::vector<glm::dvec3> turned = GearOutline(l.teeth, 0.5 * pitch);
  const glm::vec3 colors[] = {{0.8f, 0.55f, 0.2f},  {0.6f, 0.62f, 0.68f}, {0.75f, 0.3f, 0.2f},
                              {0.3f, 0.5f, 0.75f},  {0.85f, 0.75f, 0.35f}, {0.4f, 0.6f, 0.35f}};

  Scene scene;
  scene.background = glm::vec3(0.08f, 0.09f, 0.12f);
  SceneBuilder b(&scene);
  const double x0 = -0.5 * spacing * (l.cols - 1), z0 = -0.5 * spacing * (l.rows - 1);
  for (long r = 0; r < l.rows; ++r) {
    for (long c = 0; c < l.cols; ++c) {
      const bool odd = (r + c) % 2 == 1;
      b.SetColor(colors[(r + 2 * c) % 6]);
      const glm::dvec3 base(x0 + c * spacing, odd ? kLift : 0.0, z0 + r * spacing);
      AddGear(b, odd ? turned : plain, base);
    }
  }
  scene.camera = FramingCamera(scene, {0.55, 1.1, 1.0}, glm::vec3(0, 1, 0), 45.0);
  const double ex = 0.5 * spacing * l.cols + 1.0, ez = 0.5 * spacing * l.rows + 1.0;
  b.SetColor(glm::vec3(0.55f, 0.55f, 0.55f));
  AddGrid(b, {-ex, -0.05, ez}, {2 * ex, 0, 0}, {0, 0, -2 * ez}, 1, 1);
  return scene;
}

}  // namespace kdrt::gen
