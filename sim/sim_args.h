// The options of `kdrt sim`. The front end (sw/tools/cmd_sim.cpp) and every
// model executable (sim/sim_main.cpp) register the very same options, so the
// front end can hand its arguments to the model unchanged.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/ray.h"
#include "scene/scene.h"
#include "sim/sim_config.h"
#include "tools/scene_setup.h"

namespace kdrt::sim {

struct SimArgs {
  cli::SceneArgs scene;
  std::string res;
  std::string out;
  std::string hits;
  std::string json;
  std::string format = "fp32";
  std::string rays;
  std::string camera;
  std::string trace;           // FST waveform
  int64_t trace_ray = -1;      // dump only while this ray is in flight
  uint32_t mem_latency = 20;
  double mem_bw = 16.0;
  uint64_t timeout = 1000000;  // cycles without a hit record
  ConfigOverrides overrides;
  bool progress = false;
  bool quiet = false;
  bool systemc = false;
  bool which_model = false;    // print the model choice and stop
  int64_t corrupt_reference = -1;  // test hook: falsify the reference of this ray
};

void AddSimOptions(CLI::App& cmd, SimArgs& args);

// Throws InputError on inconsistent options (e.g. --trace-ray without --trace).
void CheckSimArgs(const SimArgs& args);



}  // namespace kdrt::sim
