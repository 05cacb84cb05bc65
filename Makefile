# Glint: a thin wrapper over CMake. `make demo` and `make test` work on a fresh Debian 12 machine.
#
#   make deps    install the Debian packages the build needs (apt-get; root or sudo)
#   make weights fetch Open Image Denoise's weights for the network denoiser (denoise-weights/)
#   make build   configure and build (Release); the binary is build/glint
#   make demo    what the glint program needs, built alone, then render the built-in scene to glint.png
#   make test    deps + build + run every test (ctest)
#   make clean   remove the build directory
#   make web     the library in WebAssembly and the web page, into build-web/site (docs/web.md)
#   make serve   serve build-web/site on http://localhost:8167 with cross-origin isolation
#   make blender deps + build + install the Blender add-on into your Blender (docs/blender.md)
#   make bench   deps for the benchmarks (Embree, POV-Ray, Blender) + Release build in build-bench
#                + run bench/run.sh: Glint against Embree, POV-Ray and Cycles (docs/performance.md)

BUILD_DIR   ?= build
BUILD_TYPE  ?= Release
GLINT_WERROR ?= OFF
JOBS        ?= $(shell nproc 2>/dev/null || echo 2)

# Debian packages: compiler and build tools, then libraries (see docs/dependencies in README;
# libboost-iostreams-dev because Debian's FindOpenVDB.cmake requires it and libopenvdb-dev does
# not pull it in: cmake/dependencies.cmake),
# then the Python module (pybind11-dev, python3-dev, python3-numpy; docs/python.md) and its
# tests (python3-pytest), then what the other tests run: Open MPI (openmpi-bin, libopenmpi-dev)
# for glint-mpi and its tests, slurm-wlm and munge for a private single-node Slurm on localhost
# that runs contrib/slurm's scripts (tests/slurm/cluster_test.sh, about 9 s; docs/scale-out.md).
# curl and ca-certificates fetch the denoiser's weights (make weights: 95 MB, about 2 s).
# blender runs the Blender add-on's tests (blender/, about 580 MB with its libraries).
DEPS := g++ cmake make pkg-config curl ca-certificates libcli11-dev libstb-dev libpng-dev libwebp-dev libopenexr-dev \
        libtinyobjloader-dev libtinygltf-dev nlohmann-json3-dev libdraco-dev libmeshoptimizer-dev \
        libopenvdb-dev libboost-iostreams-dev pybind11-dev python3-dev python3-numpy \
        libgtest-dev libgmock-dev python3-pytest openmpi-bin libopenmpi-dev slurm-wlm munge blender

# `make demo`: only what the glint program needs, and only it is built (no test libraries, no
# MPI or Slurm, OpenVDB if it is there already): a first picture in minutes on a fresh machine.
# Tests, glint-mpi and VDB files are built when their packages are installed (`make test`).
DEMO_DEPS := g++ cmake make pkg-config curl ca-certificates libcli11-dev libstb-dev libpng-dev libwebp-dev libopenexr-dev \
             libtinyobjloader-dev libtinygltf-dev nlohmann-json3-dev libdraco-dev libmeshoptimizer-dev
installed = $(if $(shell for p in $(1); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | \
  grep -q 'ok installed' || echo no; done),OFF,ON)

# `make bench`: what the benchmark build and bench/run.sh need (no test libraries; Embree for
# the traversal comparison, POV-Ray for the whole renders, bc for bench/course_stats.sh,
# Blender for the path tracer against Cycles, bench/cycles/: about 580 MB with its libraries;
# draco and gltfpack, whose tools compress the 1M-triangle glTF for bench/mesh_stats.sh;
# Assimp for the PLY and STL readers against it, bench/mesh_load_stats.sh; python3-numpy for
# Blender's glTF importer, bench/cycles/gltf/).
BENCH_DIR  ?= build-bench
BENCH_DEPS := g++ cmake make pkg-config curl ca-certificates libcli11-dev libstb-dev libpng-dev libwebp-dev libopenexr-dev \
              libtinyobjloader-dev libtinygltf-dev nlohmann-json3-dev libdraco-dev \
              libmeshoptimizer-dev libopenvdb-dev libboost-iostreams-dev libembree-dev povray bc \
              blender draco gltfpack libassimp-dev python3-numpy

# `make web` and its tests (docs/web.md): Emscripten (Debian's 3.1.6, clang for WebAssembly),
# dpkg-dev (apt-get source unpacks the Debian sources of zlib and libpng that the web build
# compiles, web/tools/debian-sources.sh), the header-only libraries the library compiles against,
# Node.js and npm (the page's npm packages from web/package-lock.json, its bundler, the tests),
# and Chromium (the browser tests, driven by playwright-core from npm; it downloads no browser).
# Each is installed when its command or package is missing (Node.js may come from elsewhere).
WEB_DIR  ?= build-web
WEB_PORT ?= 8167
WEB_DEPS := emscripten:em++ dpkg-dev:dpkg-source nodejs:node npm:npm chromium:chromium \
            cmake:cmake make:make libstb-dev libtinyobjloader-dev libtinygltf-dev nlohmann-json3-dev

SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

FUZZ_DEPS := clang libclang-rt-14-dev cmake make pkg-config libcli11-dev libstb-dev libpng-dev libwebp-dev \
             libopenexr-dev libtinyobjloader-dev libtinygltf-dev nlohmann-json3-dev libdraco-dev \
             libmeshoptimizer-dev libopenvdb-dev libboost-iostreams-dev
FUZZ_SECONDS ?= 60

.PHONY: deps weights build demo test test-sanitize fuzz clean bench web web-deps serve blender

deps:
	@missing=""; \
	for p in $(DEPS); do dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'ok installed' || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "glint: installing missing Debian packages:$$missing"; \
	  export DEBIAN_FRONTEND=noninteractive; \
	  $(SUDO) apt-get install -y -q --no-install-recommends $$missing || \
	  { $(SUDO) apt-get update -q && $(SUDO) apt-get install -y -q --no-install-recommends $$missing; }; \
	fi

# Open Image Denoise's published weights, which the build embeds (denoise-weights/README.md):
# fetched once, checked against denoise-weights/SHA256SUMS.
weights:
	@denoise-weights/fetch.sh

$(BUILD_DIR)/CMakeCache.txt:
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DGLINT_WERROR=$(GLINT_WERROR)

# Everything: the tests, glint-mpi and OpenVDB (after `make deps`).
build: weights $(BUILD_DIR)/CMakeCache.txt
	cmake -S . -B $(BUILD_DIR) -DGLINT_WERROR=$(GLINT_WERROR) -DGLINT_BUILD_TESTS=ON \
	  -DGLINT_MPI=ON -DGLINT_OPENVDB=ON >/dev/null
	cmake --build $(BUILD_DIR) -j $(JOBS)

demo:
	@$(MAKE) --no-print-directory deps DEPS="$(DEMO_DEPS)"
	@$(MAKE) --no-print-directory weights
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DGLINT_WERROR=$(GLINT_WERROR) \
	  -DGLINT_BUILD_TESTS=$(call installed,libgtest-dev libgmock-dev) \
	  -DGLINT_MPI=$(call installed,libopenmpi-dev) \
	  -DGLINT_OPENVDB=$(call installed,libopenvdb-dev libboost-iostreams-dev) >/dev/null
	cmake --build $(BUILD_DIR) -j $(JOBS) --target glint
	./$(BUILD_DIR)/glint -o glint.png
	@echo "glint: demo render written to $(CURDIR)/glint.png"

# The web tests run too (tests/web/): the web build first, then the native build, told where it is.
# The Blender add-on, built with the module it bundles, installed and enabled in the user's
# Blender (its scripts/addons folder; blender/install.py).
blender: deps
	@$(MAKE) --no-print-directory build
	blender -b --python-exit-code 1 --python blender/install.py -- $(BUILD_DIR)/blender/glint_blender.zip

test: deps web-deps
	@$(MAKE) --no-print-directory web
	@$(MAKE) --no-print-directory build
	cmake -S . -B $(BUILD_DIR) -DGLINT_WEB_DIR=$(CURDIR)/$(WEB_DIR) >/dev/null
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# The unit, golden and CLI tests again, built with AddressSanitizer and UndefinedBehaviorSanitizer
# (plus float-cast-overflow, which GCC leaves out of -fsanitize=undefined). -O1 -g1 (line tables
# only) halves the compile time of -O2 -g, and reports still name functions, files and lines.
# Each test binary runs as two shards rather than one process per test case (tests/CMakeLists.txt).
# The integration tests (Slurm, MPI, the web page) are left to `make test`: they run the same
# code through other processes (Open MPI's own allocations would also trip the leak checker).
test-sanitize: deps weights
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DGLINT_TEST_SHARDS=2 \
	  -DGLINT_SANITIZE=address,undefined,float-cast-overflow -DGLINT_WERROR=$(GLINT_WERROR) \
	  -DGLINT_MPI=OFF
	cmake --build build-asan -j $(JOBS)
	cd build-asan && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --output-on-failure -j $(JOBS) -E '^(slurm|mpi|web)\.'

# Every libFuzzer harness for FUZZ_SECONDS (default 60) from the seed corpus (docs/robustness.md).
fuzz:
	@$(MAKE) --no-print-directory deps DEPS="$(FUZZ_DEPS)"
	cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
	  -DGLINT_BUILD_FUZZERS=ON -DGLINT_BUILD_TESTS=OFF -DGLINT_AVX2=OFF -DGLINT_MPI=OFF
	cmake --build build-fuzz -j $(JOBS)
	fuzz/run.sh build-fuzz $(FUZZ_SECONDS)

clean:
	rm -rf $(BUILD_DIR) build-asan build-fuzz $(WEB_DIR)

web-deps:
	@missing=""; \
	for d in $(WEB_DEPS); do p=$${d%%:*}; c=$${d#*:}; \
	  if [ "$$c" != "$$d" ]; then command -v $$c >/dev/null 2>&1 && continue; \
	  else dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'ok installed' && continue; fi; \
	  missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "glint: installing missing Debian packages:$$missing"; \
	  export DEBIAN_FRONTEND=noninteractive; \
	  $(SUDO) apt-get install -y -q --no-install-recommends $$missing || \
	  { $(SUDO) apt-get update -q && $(SUDO) apt-get install -y -q --no-install-recommends $$missing; }; \
	fi

# Two builds of the module, with threads (glint-mt) and without (glint-st), then the page:
# web/tools/build.mjs bundles it with the page's npm packages (npm ci, once per lock file) and
# assembles $(WEB_DIR)/site. NODE_PATH: Debian's Emscripten finds its JavaScript modules there.
web: web-deps weights
	web/tools/debian-sources.sh $(WEB_DIR)/debian
	@for v in mt st; do \
	  t=$$([ $$v = mt ] && echo ON || echo OFF); \
	  [ -f $(WEB_DIR)/$$v/CMakeCache.txt ] || NODE_PATH=/usr/share/nodejs emcmake cmake -S . \
	    -B $(WEB_DIR)/$$v -DCMAKE_BUILD_TYPE=Release -DGLINT_WERROR=$(GLINT_WERROR) \
	    -DGLINT_WEB_THREADS=$$t -DGLINT_WEB_DEBIAN_SOURCES=$(CURDIR)/$(WEB_DIR)/debian || exit 1; \
	  NODE_PATH=/usr/share/nodejs cmake --build $(WEB_DIR)/$$v -j $(JOBS) || exit 1; \
	done
	@[ web/node_modules/.package-lock.json -nt web/package-lock.json ] || \
	  (cd web && npm ci --no-audit --no-fund)
	node web/tools/build.mjs $(WEB_DIR)
	@echo "glint: the web page is in $(CURDIR)/$(WEB_DIR)/site; make serve serves it"

serve:
	node web/tools/serve.mjs $(WEB_DIR)/site --port $(WEB_PORT)

bench:
	@$(MAKE) --no-print-directory deps DEPS="$(BENCH_DEPS)"
	@$(MAKE) --no-print-directory weights
	cmake -S . -B $(BENCH_DIR) -DCMAKE_BUILD_TYPE=Release -DGLINT_BUILD_BENCH=ON \
	  -DGLINT_BUILD_TESTS=OFF -DGLINT_WERROR=$(GLINT_WERROR)
	cmake --build $(BENCH_DIR) -j $(JOBS)
	bench/run.sh $(BENCH_DIR)
