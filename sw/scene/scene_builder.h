// Appends triangles to a Scene while keeping its colour table free of
// duplicates, so every loader and generator numbers triangles and assigns
// colours the same way.
#pragma once

#include <cstdint>
#include <map>
#include <tuple>

#include <glm/vec3.hpp>

#include "scene/scene.h"

namespace kdrt {

class SceneBuilder {
 public:
  explicit SceneBuilder(Scene* scene) : scene_(scene) {}

  // Colour (and finish) for the triangles added from now on (white and the
  // default Finish until the first call).
  void SetColor(const glm::vec3& rgb, const Finish& finish = Finish{});

  void AddTriangle(const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2);

  // A polygon with n >= 3 vertices becomes n-2 triangles fanned from p[0]:
  // (p0,p1,p2), (p0,p2,p3), ... This order is the numbering contract.
  void AddFan(const glm::vec3* p, size_t n);

  Scene& scene() { return *scene_; }

 private:
  uint32_t CurrentMaterial();

  Scene* scene_;
  glm::vec3 color_{1.0f, 1.0f, 1.0f};
  Finish finish_;
  bool material_valid_ = false;
  uint32_t material_ = 0;
  // Keyed on the bit patterns, so -0 and 0 stay distinct and lookups are exact.
  using Key = std::tuple<uint32_t, uint32_t, uint32_t, uint32_t, uint32_t, uint32_t>;
  Key KeyOf(const glm::vec3& rgb, const Finish& f) const;
  std::map<Key, uint32_t> index_;
};

}  // namespace kdrt
