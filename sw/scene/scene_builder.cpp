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

SceneBuilder::Key SceneBuilder::KeyOf(const glm::vec3& rgb, const Finish& f) const {
  return Key{Bits(rgb.x), Bits(rgb.y), Bits(rgb.z), Bits(f.kd), Bits(f.ks), Bits(f.shine)};
}

void SceneBuilder::SetColor(const glm::vec3& rgb, const Finish& finish) {
  if (material_valid_ && KeyOf(rgb, finish) == KeyOf(color_, finish_)) return;
  color_ = rgb;
  finish_ = finish;
  material_valid_ = false;
}

uint32_t SceneBuilder::CurrentMaterial() {
  if (material_valid_) return material_;
  // The table may already hold colours (e.g. a scene being extended), so
  // index it lazily the first time.
  if (index_.empty()) {
    scene_->finishes.resize(scene_->colors.size());
    for (size_t i = 0; i < scene_->colors.size(); ++i) {
      index_.emplace(KeyOf(scene_->colors[i], scene_->finishes[i]), static_cast<uint32_t>(i));
    }
  }
  auto it = index_.find(KeyOf(color_, finish_));
  if (it == index_.end()) {
    it = index_.emplace(KeyOf(color_, finish_), static_cast<uint32_t>(scene_->colors.size())).first;
    scene_->colors.push_back(color_);
    scene_->finishes.push_back(finish_);
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
