#include "scenes/gen/generators.h"

#include "common/error.h"
#include "scene/tessellate.h"
#include "scenes/gen/gen_common.h"

namespace kdrt {

namespace {

struct GeneratorEntry {
  const char* name;
  const char* description;
  Scene (*make)(int size);
  // Instead of make, for a generator that tessellates as the NFF loader does.
  Scene (*make_tessellated)(int size, const LoadOptions& tessellation) = nullptr;
};

const GeneratorEntry kGenerators[] = {
    {"room", "closed Cornell-like room: coloured gridded walls, two boxes and a sphere",
     gen::GenerateRoom},
    {"balls", "sphereflake: a sphere with nine smaller spheres on it, recursively, over a floor",
     gen::GenerateBalls},
    {"rings", "tori in concentric pentagonal rings, alternately flat and upright, over a floor",
     gen::GenerateRings},
    {"tetra", "recursive Sierpinski tetrahedron over a floor", gen::GenerateTetra},
    {"tree", "branching tree of tapered cylinders with leaves at the tips", gen::GenerateTree},
    {"gears", "grid of meshing toothed gears, concave faces fanned into slivers, over a floor",
     gen::GenerateGears},
    {"strips", "pentagonal rings of long thin cylinder strips with spheres at the corners (SPD rings), over a floor",
     gen::GenerateStrips},
    {"hoops", "pyramid of clusters of six interlinked pentagonal hoops: NFF cylinders 50x longer than thick, one band of full-length slivers, with corner spheres (SPD rings)",
     nullptr, gen::GenerateHoops},
};

const GeneratorEntry& Find(const std::string& name) {
  for (const GeneratorEntry& g : kGenerators) {
    if (name == g.name) return g;
  }
  std::string known;
  for (const GeneratorEntry& g : kGenerators) {
    known += std::string(known.empty() ? "" : ", ") + g.name;
  }
  throw InputError("unknown scene generator '" + name + "' (known: " + known + ")");
}

}  // namespace

std::vector<std::string> GeneratorNames() {
  std::vector<std::string> names;
  for (const GeneratorEntry& g : kGenerators) names.emplace_back(g.name);
  return names;
}

std::string GeneratorDescription(const std::string& name) { return Find(name).description; }

Scene GenerateScene(const std::string& name, int size, const LoadOptions& tessellation) {
  const GeneratorEntry& g = Find(name);
  if (size < 1 || size > kMaxGeneratorSize) {
    throw InputError("generator '" + name + "': size " + std::to_string(size) + " is outside 1.." +
                     std::to_string(kMaxGeneratorSize));
  }
  if (!IsValidConeAspect(tessellation.cone_aspect)) {
    throw InputError("generator '" + name + "': " + kConeAspectRule);
  }
  Scene scene = g.make_tessellated != nullptr ? g.make_tessellated(size, tessellation) : g.make(size);
  scene.source = name + ":" + std::to_string(size);
  return scene;
}

}  // namespace kdrt
