// The command-line options of every scene-reading command: the scene and the
// kd-tree build options, bound straight to SceneSpec (setup/prepared_scene.h).
#pragma once

#include <CLI/CLI.hpp>

#include "setup/prepared_scene.h"

namespace kdrt::cli {

void AddSceneOptions(CLI::App& cmd, SceneSpec& spec);

}  // namespace kdrt::cli
