# The preset number formats, name:E:M: the one list that the prebuilt
# simulation models, the per-format RTL benches, lint, synthesis and the C++
# fp::Presets() (generated header <build>/generated/fp/presets.h) all use.
# scripts/lint.sh and scripts/synth.sh read the line below.
set(KDRT_PRESETS fp32:8:23 fp24:7:16 bf16:8:7 fp16:5:10)

# Writes <build>/generated/fp/presets.h: KDRT_PRESET_LIST(X) expands X(name, E, M).
function(kdrt_write_presets_header out)
  set(items "")
  foreach(p ${KDRT_PRESETS})
    string(REPLACE ":" ";" parts ${p})
    list(GET parts 0 name)
    list(GET parts 1 e)
    list(GET parts 2 m)
    string(APPEND items " \\\n  X(${name}, ${e}, ${m})")
  endforeach()
  file(CONFIGURE OUTPUT ${out} CONTENT "// Generated from cmake/presets.cmake: do not edit.
#pragma once
#define KDRT_PRESET_LIST(X)${items}
")
endfunction()
