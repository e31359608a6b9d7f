# pathlab — everyday commands. Each target first makes sure the Debian
# packages are installed (scripts/setup.sh is idempotent).
JOBS ?= $(shell nproc)
BUILD := build/release
# Wolf scene data: use ../shared/scenes when it sits beside the checkout.
SHARED_SCENES := $(abspath ../shared/scenes)
ifneq ($(wildcard $(SHARED_SCENES)/wolf/wolf.pmd),)
export PATHLAB_ASSETS ?= $(SHARED_SCENES)
endif

.PHONY: setup build test demo bench fuzz format clean

setup:
	@scripts/setup.sh

$(BUILD)/build.ninja: CMakeLists.txt
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null

build: setup $(BUILD)/build.ninja
	@cmake --build $(BUILD) -j $(JOBS)

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

demo: build
	@$(BUILD)/pathlab study --preset seed -o out/seed --resume
	@$(BUILD)/pathlab report out/seed
	@echo "Report: $(abspath out/seed/report/index.html)"

bench: build
	@PATHLAB_SETUP_EXTRAS=bench scripts/setup.sh
	@$(BUILD)/pathlab bench
	@$(BUILD)/pathlab_bench

format:
	@clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	@rm -rf build
