// PLY and OFF through assimp. No post-processing steps are requested: in
// particular not aiProcess_Triangulate, so polygons are fanned here in file
// order (the numbering contract). Both formats hold one mesh with no node
// transforms, so meshes are read in index order.
#include <cmath>
#include <string>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include "common/error.h"
#include "scene/loaders.h"
#include "scene/mesh_check.h"
#include "scene/scene_builder.h"
#include "scene/text_fields.h"

namespace kdrt {

namespace {

bool Finite(const aiVector3D& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

Scene LoadWithAssimp(const std::string& path, bool is_ply) {
  {
    const std::string bytes = ReadWholeFile(path);
    if (is_ply) {
      CheckPly(path, bytes);
    } else {
      CheckOff(path, bytes);
    }
  }
  Assimp::Importer importer;
  const aiScene* ai = importer.ReadFile(path, 0);
  if (ai == nullptr) {
    std::string err = importer.GetErrorString();
    while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
    throw InputError(path, 0, "assimp: " + (err.empty() ? std::string("cannot read file") : err));
  }

  Scene scene;
  scene.source = path;
  SceneBuilder builder(&scene);
  std::vector<glm::vec3> polygon;
  for (unsigned m = 0; m < ai->mNumMeshes; ++m) {
    const aiMesh* mesh = ai->mMeshes[m];
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      if (!Finite(mesh->mVertices[v])) {
        throw InputError(path, 0, "vertex " + std::to_string(v) + " has a NaN or Inf coordinate");
      }
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices < 3) {
        throw InputError(path, 0,
                         "face " + std::to_string(f) + " has " + std::to_string(face.mNumIndices) +
                             " vertices (needs at least 3)");
      }
      polygon.clear();
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        unsigned vi = face.mIndices[k];
        if (vi >= mesh->mNumVertices) {
          throw InputError(path, 0,
                           "face " + std::to_string(f) + " has a vertex index out of range");
        }
        const aiVector3D& p = mesh->mVertices[vi];
        polygon.emplace_back(p.x, p.y, p.z);
      }
      builder.AddFan(polygon.data(), polygon.size());
    }
  }
  return scene;
}

}  // namespace kdrt
