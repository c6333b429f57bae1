// The physical cost of a simulated core: what scripts/synth-core.sh measured
// for exactly that configuration (every unit of rt_core synthesized on the
// OSU 0.18 um library and timed with OpenSTA, docs/simulator.md "Physical
// cost"), turned into rays per second and per mm^2 with the cycles the
// simulation counted, and the same scaled to smaller nodes.
//
// Results live in <phys dir>/<model key>/core.json, the key being the
// configuration that ran (CoreConfig::Key). Nothing here ever reports the
// figures of another configuration: no file, no physical block.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/core_params.h"

namespace kdrt::sim {

// $KDRT_PHYS_DIR when set and not empty (the tests point it at a temporary
// directory), else <build>/phys.
std::string PhysDir();
// <PhysDir()>/<key>/core.json.
std::string PhysPath(const CoreConfig& config);

// One node of Stillmaker & Baas, "Scaling equations for the accurate
// prediction of CMOS device performance from 180 nm to 7 nm", Integration 58
// (2017) 74-81, relative to its 180 nm node: the area factor is the paper's
// own (its table of area scaling factors between nodes, 180 nm row); the
// delay factor is the ratio of the paper's fitted delay polynomials (third
// order in Vdd, coefficients per node; high-performance models below 65 nm)
// at each node's nominal Vdd: 1.8 V at 180 nm.
struct NodeScale {
  int nm = 0;
  double vdd = 0;           // the nominal supply the delay factor is taken at
  double area = 1;          // multiply an area at 180 nm by this
  double delay = 1;         // multiply a delay at 180 nm by this
  int interpolated_from[2] = {0, 0};  // both 0 unless the paper has no such node
};
// 45, 28 and 7 nm. 28 nm is not a node of the paper: its factors are
// interpolated between the paper's 32 and 20 nm, linearly in log(factor)
// against log(node), and say so (interpolated_from).
std::vector<NodeScale> ScaledNodes();
// The paper's nodes used above (180, 45, 32, 20, 7 nm), for tests and docs.
std::vector<NodeScale> PaperNodes();

// The physical block of `kdrt sim`'s report from a core.json (`core`, read
// from `path`, for messages): library, clock and critical unit, area in mm^2,
// Mrays/s of one core at that clock (1e3 / clock_ns / cycles_per_ray, the
// core's own cycles per ray), Mrays/s per mm^2, the units, the estimated
// units, the notes, and "scaled" to 45, 28 and 7 nm. `config`: the
// configuration that ran; a core.json whose params differ is refused.
// Throws InputError naming `path` when a field is missing or malformed.
nlohmann::json PhysicalBlock(const nlohmann::json& core, const std::string& path, const CoreConfig& config,
                             double cycles_per_ray);

// What a synthesis was made from: FNV-1a (64 bits, 16 hex digits) of the
// source tree's rtl/*.sv in name order and scripts/sram_model.txt, each as its
// name, a 0 byte, its bytes and a 0 byte; scripts/synth_core.py writes the
// same into core.json as "sources_fnv1a64".
std::string SourcesHash();

// Reads and checks <PhysPath(config)> (InputError naming it when it is not
// JSON or not a core.json of `config`); a null json when there is none, or
// when it was made from other sources than this tree's (its
// sources_fnv1a64 is not SourcesHash(): the RTL or the SRAM model changed
// since, so its figures are another design's).
nlohmann::json ReadCoreJson(const CoreConfig& config);

// "physical: no synthesis of this configuration (<key>); run ..." for the
// table and stderr, or, when PhysPath(config) exists but was made from other
// sources, a line saying so.
std::string NoSynthesisLine(const CoreConfig& config);

// After ReadCoreJson returned null for `config`: whether its core.json is
// there all the same, made from other sources than this tree's.
bool HasSynthesisOfOtherSources(const CoreConfig& config);

// For --which: "synthesized", "none yet" or "made from other sources than
// this tree's" (`core`: what ReadCoreJson returned).
std::string SynthesisState(const CoreConfig& config, const nlohmann::json& core);

// The physical block as table lines (`physical` null: NoSynthesisLine).
void PrintPhysical(const nlohmann::json& physical, const CoreConfig& config, std::FILE* out);

// rt_core's parameters as scripts/synth-core.sh takes them: NAME=VALUE, one
// per row of sim/core_params.def.
std::vector<std::string> SynthParams(const CoreConfig& config);

// Runs scripts/synth-core.sh for `config` (minutes; its progress on stderr)
// into PhysPath's directory, after removing an earlier core.json, and checks
// what it wrote as ReadCoreJson does (a core.json that fails the check is
// removed). The script caches each synthesized unit; every configuration
// shares <PhysDir()>/units, so a rerun or a configuration with the same
// units takes them from there. `period_ns` > 0: the script's --period;
// `jobs` > 0: its --jobs. Returns the core.json, as ReadCoreJson reads it.
// Throws InputError when the script fails or writes no valid core.json; then
// there is no core.json. Also throws (keeping the core.json, a synthesis of
// the sources as they were when it started) when the tree's sources changed
// while it ran: RequireSynthesisOfThisTree.
nlohmann::json SynthesizeCore(const CoreConfig& config, double period_ns, int jobs = 0);

// Throws InputError, naming the file, when `config`'s core.json was made from
// other sources than this tree's (rtl/*.sv or scripts/sram_model.txt changed
// since; SourcesHash); nothing when it is this tree's or there is none.
void RequireSynthesisOfThisTree(const CoreConfig& config);

}  // namespace kdrt::sim
