# deltamesh: thin wrapper over CMake. See README.md.
BUILD      ?= build
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
WERROR     ?= OFF
CMAKE_ARGS ?=
CLI        := $(BUILD)/bin/deltamesh

.PHONY: all deps configure build demo docs test bench check-long clean test-sanitize fuzz install web web-serve test-web

all: build

deps:
	@scripts/install-deps.sh core

configure:
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DDELTAMESH_WERROR=$(WERROR) $(CMAKE_ARGS) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# Installs what is missing, builds the command line only, and makes a
# quality mesh of the bundled plate (angles >= 30 degrees, areas <= 0.05):
# statistics on the terminal, the mesh in out/, and a picture.
demo: deps configure
	@cmake --build $(BUILD) -j $(JOBS) --target deltamesh_cli
	@mkdir -p out
	@cp examples/plate.poly out/plate.poly
	$(CLI) -pq30a0.05 -V -C --svg out/plate.svg out/plate.poly
	@echo "demo: mesh written to out/plate.1.node, out/plate.1.ele, out/plate.1.poly; picture: out/plate.svg"

# The command transcripts in README.md and docs/*.md rewritten with what the
# tools print now, and the pictures in docs/img rendered again from the SVGs
# those commands write (rsvg-convert). ctest's docs_transcripts fails when a
# quoted line is out of date.
docs: configure
	@cmake --build $(BUILD) -j $(JOBS) --target deltamesh_cli deltamesh-gen
	@python3 scripts/docs_transcripts.py --update --pictures --cli $(CLI) --gen $(BUILD)/bin/deltamesh-gen

# The tools, the library (headers, static library, CMake package) and the
# Python module; PREFIX defaults to /usr/local.
PREFIX ?=
install: build
	@cmake --install $(BUILD) $(if $(PREFIX),--prefix $(PREFIX))

test: deps build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -LE long

# Long soak and large-size runs, kept out of the default test run.
check-long: deps build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -L long

# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer
# ($(BUILD)-asan), then the thread-safety test under ThreadSanitizer
# ($(BUILD)-tsan). DELTAMESH_TEST_QUICK=1 makes slow tests use smaller
# inputs (tests honour it, see docs/robustness.md); "long" tests are skipped.
# (gcc's -Wmaybe-uninitialized gives false positives under ASan, in <regex>.)
# No Python bindings there: a sanitized extension module cannot be loaded into
# an ordinary python (the ASan runtime has to be first in the process; only
# LD_PRELOAD gets it there, see docs/python.md for that manual run), so ctest
# runs them in the normal build only (python/CMakeLists.txt skips them in any
# DELTAMESH_SANITIZE build too).
SAN_FLAGS := -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -Wno-maybe-uninitialized" \
             -DDELTAMESH_WERROR=$(WERROR) -DDELTAMESH_PYTHON=OFF
test-sanitize: deps
	@cmake -S . -B $(BUILD)-asan $(SAN_FLAGS) -DDELTAMESH_SANITIZE=address,undefined $(CMAKE_ARGS) >/dev/null
	@cmake --build $(BUILD)-asan -j $(JOBS)
	@cd $(BUILD)-asan && DELTAMESH_TEST_QUICK=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure -j $(JOBS) -LE long
	@cmake -S . -B $(BUILD)-tsan $(SAN_FLAGS) -DDELTAMESH_SANITIZE=thread $(CMAKE_ARGS) >/dev/null
	@cmake --build $(BUILD)-tsan -j $(JOBS) --target test_threads
	@DELTAMESH_TEST_QUICK=1 TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" $(BUILD)-tsan/bin/test_threads

# libFuzzer targets (clang) run FUZZ_SECONDS each; see scripts/fuzz.sh.
FUZZ_SECONDS ?= 60
fuzz:
	@FUZZ_SECONDS=$(FUZZ_SECONDS) scripts/fuzz.sh run

bench: deps
	@scripts/install-deps.sh bench || echo "bench: libcgal-dev not installed; CGAL peer skipped"
	@cmake -S . -B $(BUILD)-bench -DCMAKE_BUILD_TYPE=Release -DDELTAMESH_BENCH=ON -DDELTAMESH_TESTS=OFF -DDELTAMESH_PYTHON=OFF >/dev/null
	@cmake --build $(BUILD)-bench -j $(JOBS)
	@bench/run.sh $(BUILD)-bench

# The browser app (web/, docs/web.md): the command line compiled to
# WebAssembly with Debian's emscripten, and the static page, in
# $(WEB_BUILD)/site. Emscripten's tools run on node and need Debian's JS
# modules (acorn ...), which a node not from Debian does not see: NODE_PATH.
WEB_BUILD ?= build-web
WEB_PORT  ?= 8000
EMENV     := NODE_PATH=/usr/share/nodejs$(if $(NODE_PATH),:$(NODE_PATH))
web:
	@scripts/install-deps.sh web
	@$(EMENV) emcmake cmake -S . -B $(WEB_BUILD) -DCMAKE_BUILD_TYPE=Release -DDELTAMESH_TESTS=OFF \
	  -DDELTAMESH_PYTHON=OFF -DDELTAMESH_WERROR=$(WERROR) >/dev/null
	@$(EMENV) cmake --build $(WEB_BUILD) -j $(JOBS) --target deltamesh_site
	@echo "web: the page is in $(WEB_BUILD)/site (make web-serve: http://127.0.0.1:$(WEB_PORT)/)"

# Any static file server will do; this is Python's.
web-serve: web
	python3 -m http.server -d $(WEB_BUILD)/site -b 127.0.0.1 $(WEB_PORT)

# The page in headless chromium (puppeteer-core, tests/web): the example
# meshed in the page and by the CLI gives the same numbers, the trace
# replays to the final mesh, a broken file shows its file:line error, and
# docs/img/web-app.png is written.
test-web: web
	@scripts/install-deps.sh core browser
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DDELTAMESH_WERROR=$(WERROR) $(CMAKE_ARGS) >/dev/null
	@cmake --build $(BUILD) -j $(JOBS) --target deltamesh_cli
	@cd tests/web && npm ci --no-audit --no-fund --loglevel=error
	node tests/web/run.mjs --site $(WEB_BUILD)/site --cli $(CLI) --example examples/plate.poly \
	  --screenshot docs/img/web-app.png

clean:
	rm -rf $(BUILD) $(BUILD)-bench $(WEB_BUILD) out
