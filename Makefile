# deltamesh: thin wrapper over CMake. See README.md.
BUILD      ?= build
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
WERROR     ?= OFF
CMAKE_ARGS ?=
CLI        := $(BUILD)/bin/deltamesh

.PHONY: all deps configure build demo test bench check-long clean

all: build

deps:
	@scripts/install-deps.sh core

configure:
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DDELTAMESH_WERROR=$(WERROR) $(CMAKE_ARGS) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# Installs what is missing, builds, meshes a bundled example, prints
# statistics and writes a picture.
demo: deps build
	@mkdir -p out
	@$(BUILD)/bin/deltamesh-gen uniform 2000 --seed 7 > out/demo.node
	$(CLI) -V -C --svg out/demo.svg out/demo.node
	@echo "demo: mesh written to out/demo.1.node, out/demo.1.ele; picture: out/demo.svg"

test: deps build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -LE long

# Long soak and large-size runs, kept out of the default test run.
check-long: deps build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -L long

bench: deps
	@scripts/install-deps.sh bench || echo "bench: libcgal-dev not installed; CGAL peer skipped"
	@cmake -S . -B $(BUILD)-bench -DCMAKE_BUILD_TYPE=Release -DDELTAMESH_BENCH=ON -DDELTAMESH_TESTS=OFF >/dev/null
	@cmake --build $(BUILD)-bench -j $(JOBS)
	@bench/run.sh $(BUILD)-bench

clean:
	rm -rf $(BUILD) $(BUILD)-bench out
