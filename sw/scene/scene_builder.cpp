#include "scene/scene_builder.h"

#include <cstring>

namespace kdrt {

namespace {

uint32_t Bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

}  // namespace

void SceneBuilder::SetColor(const glm::vec3& rgb) {
  if (material_valid_ && Bits(rgb.x) == Bits(color_.x) && Bits(rgb.y) == Bits(color_.y) &&
      Bits(rgb.z) == Bits(color_.z)) {
    return;
  }
  color_ = rgb;
  material_valid_ = false;
}

uint32_t SceneBuilder::CurrentMaterial() {
  if (material_valid_) return material_;
  // The table may already hold colours (e.g. a scene being extended), so
  // index it lazily the first time.
  if (index_.empty()) {
    for (size_t i = 0; i < scene_->colors.size(); ++i) {
      const glm::vec3& c = scene_->colors[i];
      index_.emplace(std::make_tuple(Bits(c.x), Bits(c.y), Bits(c.z)), static_cast<uint32_t>(i));
    }
  }
  auto key = std::make_tuple(Bits(color_.x), Bits(color_.y), Bits(color_.z));
  auto it = index_.find(key);
  if (it == index_.end()) {
    it = index_.emplace(key, static_cast<uint32_t>(scene_->colors.size())).first;
    scene_->colors.push_back(color_);
  }
  material_ = it->second;
  material_valid_ = true;
  return material_;
}

void SceneBuilder::AddTriangle(const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2) {
  uint32_t m = CurrentMaterial();
  scene_->triangles.push_back(Triangle{v0, v1, v2});
  scene_->material.push_back(m);
}

void SceneBuilder::AddFan(const glm::vec3* p, size_t n) {
  for (size_t i = 1; i + 1 < n; ++i) AddTriangle(p[0], p[i], p[i + 1]);
}

}  // namespace kdrt
