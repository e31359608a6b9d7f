# pathlab — everyday commands. Each target first makes sure the Debian
# packages are installed (scripts/setup.sh is idempotent).
JOBS ?= $(shell nproc)
BUILD := build/release
# Wolf scene data: use ../shared/scenes when it sits beside the checkout.
SHARED_SCENES := $(abspath ../shared/scenes)
ifneq ($(wildcard $(SHARED_SCENES)/wolf/wolf.pmd),)
export PATHLAB_ASSETS ?= $(SHARED_SCENES)
endif

.PHONY: setup build python test demo bench fuzz sanitize format clean

setup:
	@scripts/setup.sh

# Profile-guided optimisation (PGO=0 turns it off): an instrumented pathlab is
# built in $(PGO_BUILD) and trained (scripts/pgo-train.sh) whenever a source
# changed, then the release build compiles with the profiles in $(PGO_DATA).
# Same images, about 10% less time per frame (docs/performance.md).
PGO ?= 1
PGO_BUILD := build/pgo-generate
PGO_DATA := $(abspath build/pgo-data)
PGO_SOURCES := $(shell find src -name '*.cpp' -o -name '*.h' -o -name '*.inc') CMakeLists.txt scripts/pgo-train.sh
ifeq ($(PGO),1)
RELEASE_OPTIONS := -DPATHLAB_PGO=use -DPATHLAB_PGO_DIR=$(PGO_DATA)
PGO_STAMP := $(PGO_DATA)/trained
else
RELEASE_OPTIONS := -DPATHLAB_PGO=
PGO_STAMP :=
endif

$(PGO_DATA)/trained: $(PGO_SOURCES)
	@cmake -S . -B $(PGO_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DPATHLAB_LTO=OFF \
	  -DPATHLAB_PGO=generate -DPATHLAB_PGO_DIR=$(PGO_DATA) >/dev/null
	@cmake --build $(PGO_BUILD) -j $(JOBS) --target pathlab
	@rm -rf $(PGO_DATA) && mkdir -p $(PGO_DATA)
	@scripts/pgo-train.sh $(PGO_BUILD)/pathlab
	@# Every release object was compiled with the old profile, and ninja does
	@# not track the profile files: clean, so that all of them use the new one.
	@if [ -f $(BUILD)/build.ninja ]; then cmake --build $(BUILD) --target clean >/dev/null; fi
	@touch $@

build: setup $(PGO_STAMP) scenes/pbrt/sky-sun.pfm scenes/pbrt/textured-bricks.png \
	scenes/pbrt/bump-normal-heights.png
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(RELEASE_OPTIONS) >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

# The environment map of scenes/pbrt/envmap-sun.pbrt, generated, not stored.
scenes/pbrt/sky-sun.pfm: scripts/make_sky_sun.py | setup
	@/usr/bin/python3 scripts/make_sky_sun.py $@

# The brick image map of scenes/pbrt/textured.pbrt, generated, not stored.
scenes/pbrt/textured-bricks.png: scripts/make_texture_png.py
	@/usr/bin/python3 scripts/make_texture_png.py $@

# The height and normal maps of scenes/pbrt/bump-normal.pbrt, generated, not stored.
scenes/pbrt/bump-normal-heights.png: scripts/make_bump_maps.py scripts/make_texture_png.py
	@/usr/bin/python3 scripts/make_bump_maps.py scenes/pbrt

# The Python module alone, into $(BUILD)/python/pathlab (docs/python.md);
# `make build` builds it with everything else, `make test` runs its pytest suite.
python: setup $(PGO_STAMP)
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(RELEASE_OPTIONS) >/dev/null
	@cmake --build $(BUILD) -j $(JOBS) --target pathlab_python

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

demo: build
	@$(BUILD)/pathlab study --preset seed -o out/seed --resume
	@$(BUILD)/pathlab report out/seed
	@echo "Report: $(abspath out/seed/report/index.html)"

bench: build
	@PATHLAB_SETUP_EXTRAS=bench scripts/setup.sh
	@$(BUILD)/pathlab bench --samplers
	@bench/vs_embree.sh 5 $(BUILD)/pathlab
	@$(BUILD)/pathlab_bench

# Fuzzing: libFuzzer targets (fuzz/) built with clang, ASan and UBSan, each run
# for FUZZ_SECONDS; fails when any target finds a crash.
FUZZ_SECONDS ?= 60
FUZZ_BUILD := build/fuzz
FUZZ_TARGETS := json_scene study_spec obj_mtl image ply pbrt

$(FUZZ_BUILD)/build.ninja: CMakeLists.txt
	@CC=clang-14 CXX=clang++-14 cmake -S . -B $(FUZZ_BUILD) -G Ninja \
	  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPATHLAB_FUZZ=ON "-DPATHLAB_SANITIZE=address;undefined" >/dev/null

fuzz: setup
	@PATHLAB_SETUP_EXTRAS=fuzz scripts/setup.sh
	@$(MAKE) --no-print-directory $(FUZZ_BUILD)/build.ninja
	@cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(addprefix fuzz_,$(FUZZ_TARGETS))
	@scripts/fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# Sanitizers: the unit tests under AddressSanitizer + UBSan (all but the
# browser tests), then the renderer's determinism tests under ThreadSanitizer.
ASAN_BUILD := build/asan
TSAN_BUILD := build/tsan
TSAN_TESTS := ^(Determinism\..*|RenderCli\.IdenticalBytesForOneTwoAndEightThreads)$$

$(ASAN_BUILD)/build.ninja: CMakeLists.txt
	@cmake -S . -B $(ASAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  "-DPATHLAB_SANITIZE=address;undefined" >/dev/null

$(TSAN_BUILD)/build.ninja: CMakeLists.txt
	@cmake -S . -B $(TSAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DPATHLAB_SANITIZE=thread >/dev/null

sanitize: setup
	@PATHLAB_SETUP_EXTRAS=sanitize scripts/setup.sh
	@$(MAKE) --no-print-directory $(ASAN_BUILD)/build.ninja $(TSAN_BUILD)/build.ninja
	@cmake --build $(ASAN_BUILD) -j $(JOBS) --target pathlab pathlab_tests \
	  $(addsuffix _replay,$(addprefix fuzz_,$(FUZZ_TARGETS)))
	@cd $(ASAN_BUILD) && UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure -j $(JOBS) -E '^(report_browser|view_browser)$$'
	@cmake --build $(TSAN_BUILD) -j $(JOBS) --target pathlab pathlab_tests
	@cd $(TSAN_BUILD) && TSAN_OPTIONS="halt_on_error=1 suppressions=$(abspath tests/tsan.supp)" \
	  ctest --output-on-failure -j $(JOBS) -R '$(TSAN_TESTS)'

format:
	@clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	@rm -rf build
