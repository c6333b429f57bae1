# kdrt_share_verilated_runtime(<target>): call after the target's verilate()
# calls. Drops the Verilator runtime sources verilate() added to the target
# and links the project's one copy (sim/runtime/CMakeLists.txt) instead.
function(kdrt_share_verilated_runtime target)
  get_target_property(srcs ${target} SOURCES)
  list(FILTER srcs EXCLUDE REGEX "^${VERILATOR_ROOT}/include/[a-z_]+\\.cpp$")
  set_property(TARGET ${target} PROPERTY SOURCES ${srcs})
  target_link_libraries(${target} PRIVATE kdrt_verilated)
endfunction()
