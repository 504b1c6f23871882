# Two commands: `make run` (build Release, run the main job on the bundled demo nest) and
# `make test` (build, run the whole suite, then again under ASan + UBSan).
BUILD      ?= build
ASAN_BUILD ?= build-asan
OUT        ?= out
JOBS       ?= $(shell nproc)
CUTROUTE   := $(BUILD)/cutroute

.PHONY: all deps build run test test-release test-asan bench clean

all: build

deps:
	@scripts/install-deps

$(BUILD)/build.ninja: | deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)

run: build
	@mkdir -p $(OUT)
	$(CUTROUTE) demo $(OUT)/demo_nest.dxf
	$(CUTROUTE) inspect $(OUT)/demo_nest.dxf --json --svg $(OUT)/demo_nest.inspect.svg > $(OUT)/demo_nest.inspect.json
	$(CUTROUTE) optimize $(OUT)/demo_nest.dxf -o $(OUT)/demo_nest.ngc --report $(OUT)/demo_nest.json \
	  --svg $(OUT)/demo_nest.svg --html $(OUT)/demo_nest.html
	@echo "outputs in $(OUT)/: demo_nest.dxf .ngc .json .svg .html (and the drawing's inspect .json/.svg)"

test: test-release test-asan

test-release: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

$(ASAN_BUILD)/build.ninja: | deps
	cmake -S . -B $(ASAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCUTROUTE_SANITIZE=ON

test-asan: deps $(ASAN_BUILD)/build.ninja
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  CUTROUTE_SANITIZED=1 ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS)

bench: deps
	cmake -S . -B build-bench -G Ninja -DCMAKE_BUILD_TYPE=Release -DCUTROUTE_BUILD_BENCH=ON -DCUTROUTE_BUILD_TESTS=OFF
	cmake --build build-bench -j $(JOBS)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) build-bench $(OUT)
