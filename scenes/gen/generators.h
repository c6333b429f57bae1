// Procedural test scenes in the spirit of Eric Haines' Standard Procedural
// Databases (our own code and shapes, not a port). Every generator takes an
// approximate target triangle count `size` (1 .. kMaxGeneratorSize); the
// count it produces grows roughly in proportion, within the steps its
// recursion allows (docs/scenes.md lists the mapping). Output is fully
// deterministic, with a camera (512x512) and per-object colours.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace kdrt {

inline constexpr int kMaxGeneratorSize = 10000000;

// "room", "balls", "rings", "tetra", "tree", "gears", "strips", "hoops".
std::vector<std::string> GeneratorNames();

// A one-line description of the named generator; InputError if unknown.
std::string GeneratorDescription(const std::string& name);

// InputError on an unknown name or size outside 1..kMaxGeneratorSize. The
// generators that tessellate NFF primitives as the loader does (hoops) take
// the loader's tessellation options (LoadOptions::cone_aspect); the others
// ignore them.
Scene GenerateScene(const std::string& name, int size, const LoadOptions& tessellation = {});

}  // namespace kdrt
