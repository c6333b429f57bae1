# Does rt_core elaborate with the Verilator options the simulation models are
# built with? Used by sim/CMakeLists.txt while configuring and by the test
# `core_elaboration_check` (tests/CMakeLists.txt), in script mode:
#
#   cmake -DVERILATOR=<verilator> -DSOURCES="<a.sv;b.sv;...>" -P cmake/core_elaborates.cmake
#
# exits non-zero and prints Verilator's messages when it does not.

# The options of every model build (sim/CMakeLists.txt, verilate()) that
# decide whether the design elaborates: Verilator 5.006 refuses a delayed
# array assignment in a loop it does not unroll (the per-thread loops, up to
# 256 threads), so a check without these passes designs the build rejects,
# and the other way round.
set(KDRT_CORE_ELAB_ARGS --unroll-count 1024 --unroll-stmts 1000000)

# kdrt_core_elaborates(<verilator> <sources> <ok var> <log var>)
function(kdrt_core_elaborates verilator sources ok_var log_var)
  execute_process(
    COMMAND ${verilator} --lint-only -Wno-fatal -Wno-lint -Wno-style ${KDRT_CORE_ELAB_ARGS}
            --top-module rt_core ${sources}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(rc EQUAL 0)
    set(${ok_var} TRUE PARENT_SCOPE)
  else()
    set(${ok_var} FALSE PARENT_SCOPE)
  endif()
  set(${log_var} "${out}" PARENT_SCOPE)
endfunction()

if(CMAKE_SCRIPT_MODE_FILE AND CMAKE_SCRIPT_MODE_FILE STREQUAL CMAKE_CURRENT_LIST_FILE)
  if(NOT VERILATOR OR NOT SOURCES)
    message(FATAL_ERROR "usage: cmake -DVERILATOR=<verilator> -DSOURCES=<a.sv;b.sv> -P core_elaborates.cmake")
  endif()
  kdrt_core_elaborates(${VERILATOR} "${SOURCES}" ok log)
  if(NOT ok)
    message(FATAL_ERROR "rt_core does not elaborate:\n${log}")
  endif()
  message(STATUS "rt_core elaborates")
endif()
