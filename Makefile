# kdrt top-level targets: thin wrappers, as in lowRISC ibex.
#   make demo       render the default scene, simulate the RTL core on it and
#                   compare the hit buffers; then a shaded frame (primary and
#                   shadow rays) on both, compared byte for byte (installs what is missing)
#   make test       build and run every test (installs what is missing)
#   make test-long  the long variants (more random vectors, larger images),
#                   then make test-asan
#   make test-asan  the software tests and the mutated-input corpus built with
#                   AddressSanitizer and UBSan in build-asan/ (not in make test:
#                   a second build of the software, beyond the CI's time)
#   make lint       verilator --lint-only -Wall on the RTL
#   make synth      synthesis: cells, logic depth, OSU 0.18 um area and critical
#                   path per unit and format; the default core's clock and area
#   make bench      tracing and build speed against Embree
BUILD ?= build
JOBS ?= $(shell nproc)
DEMO_SCENE ?= scenes/simple.nff
# The RTL simulation of the demo (kdrt sim) runs at this resolution.
DEMO_SIM_RES ?= 128x128
KDRT := $(BUILD)/bin/kdrt

.PHONY: all deps demo-deps configure demo-configure build demo-build demo test test-long test-asan lint synth bench clean

all: build

deps:
	@bash scripts/install-deps.sh

demo-deps:
	@bash scripts/install-deps.sh --demo

# Configuring needs only the demo's packages. The demo's configuration leaves
# the tests out (KDRT_TESTS=OFF: no RTL bench is verilated); every other
# target turns them on, which configures again once. The models are compiled
# without GCC's profile (KDRT_MODEL_PGO=OFF: it no longer makes them faster,
# docs/simulator.md, "Model building and caching").
CMAKE_CONFIGURE = cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release

demo-configure: demo-deps
	@test -f $(BUILD)/build.ninja || $(CMAKE_CONFIGURE) -DKDRT_TESTS=OFF -DKDRT_MODEL_PGO=OFF

configure: deps
	@test -f $(BUILD)/build.ninja && grep -q '^KDRT_TESTS:BOOL=ON' $(BUILD)/CMakeCache.txt && \
	  grep -q '^KDRT_MODEL_PGO:BOOL=OFF' $(BUILD)/CMakeCache.txt || \
	  $(CMAKE_CONFIGURE) -DKDRT_TESTS=ON -DKDRT_MODEL_PGO=OFF

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# The demo builds only what it runs: the kdrt tool and the fp32 core model.
demo-build: demo-configure
	@cmake --build $(BUILD) -j $(JOBS) --target kdrt kdrt-sim-fp32

demo: demo-build
	@mkdir -p out
	@scene="$(DEMO_SCENE)"; set -e; set -x; \
	$(KDRT) render "$$scene" -o out/demo.png --hits out/demo-hits.exr --json out/demo.json; \
	$(KDRT) render "$$scene" --res $(DEMO_SIM_RES) -q -o out/demo-small.png --hits out/demo-small-hits.exr; \
	$(KDRT) sim "$$scene" --res $(DEMO_SIM_RES) -o out/demo-sim.png --hits out/demo-sim-hits.exr \
	  --json out/demo-sim.json; \
	$(KDRT) compare out/demo-small-hits.exr out/demo-sim-hits.exr; \
	$(KDRT) render "$$scene" --res $(DEMO_SIM_RES) --shade -q -o out/demo-shaded.png; \
	$(KDRT) sim "$$scene" --res $(DEMO_SIM_RES) --shade -o out/demo-sim-shaded.png --json out/demo-sim-shaded.json; \
	cmp out/demo-shaded.png out/demo-sim-shaded.png && echo "demo: the RTL's shaded frame is the reference's, byte for byte"

# The quick RTL models the tests run on (tests/sim/test_models.txt) are built
# with everything else, so that no test waits for one.
test: configure
	@cmake --build $(BUILD) -j $(JOBS) --target all kdrt-test-models
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

test-long: build
	KDRT_LONG=1 ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)
	@$(MAKE) --no-print-directory test-asan

# The software test binaries with ASan and UBSan; a finding aborts its binary
# (or the kdrt run a test makes, which the test reports), so any non-zero exit
# fails the target. Left out: sim_tests and trade_tests, which build and run
# Verilated core models, and the RTL unit benches (Verilator's code).
# ASAN_FUZZ_CASES: how many cases of the mutated-input sequence (N or
# FIRST-END; the 96 of make test when empty).
# intercept_tls_get_addr=0: Debian 12's LeakSanitizer (GCC 12) reads a bogus
# range for the dynamic TLS of a process whose threads have exited (glibc
# 2.36) and crashes in its leak check ("Tracer caught signal 11", e.g. kdrt
# sim on gears 5k); without the interception the check runs and finds nothing
# there, while use_tls=0 instead would report the TLS's blocks as leaks.
ASAN_BUILD ?= build-asan
ASAN_TESTS ?= scene_tests fuzz_tests accel_tests fp_tests trace_tests structures_tests
ASAN_FUZZ_CASES ?=
test-asan: deps
	@test -f $(ASAN_BUILD)/build.ninja && grep -q '^KDRT_MODEL_PGO:BOOL=OFF' $(ASAN_BUILD)/CMakeCache.txt || \
	  cmake -S . -B $(ASAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DKDRT_SANITIZE=ON -DKDRT_MODEL_PGO=OFF
	@cmake --build $(ASAN_BUILD) -j $(JOBS) --target kdrt $(ASAN_TESTS)
	@set -e; for t in $(ASAN_TESTS); do \
	  echo "test-asan: $$t"; \
	  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:intercept_tls_get_addr=0 \
	  UBSAN_OPTIONS=print_stacktrace=1:abort_on_error=1 \
	    $(if $(ASAN_FUZZ_CASES),KDRT_FUZZ_CASES=$(ASAN_FUZZ_CASES)) $(ASAN_BUILD)/tests/$$t; \
	done

lint: deps
	@bash scripts/lint.sh

synth: deps
	@bash scripts/synth.sh

bench: build
	@cmake --build $(BUILD) -j $(JOBS) --target kdrt_bench
	$(BUILD)/bin/kdrt_bench

clean:
	rm -rf $(BUILD) out
