# Glint: a thin wrapper over CMake. `make demo` and `make test` work on a fresh Debian 12 machine.
#
#   make deps    install the Debian packages the build needs (apt-get; root or sudo)
#   make build   configure and build (Release); the binary is build/glint
#   make demo    deps + build + render the built-in scene to glint.png
#   make test    deps + build + run every test (ctest)
#   make clean   remove the build directory
#   make bench   deps for the benchmarks (Embree, POV-Ray, Blender) + Release build in build-bench
#                + run bench/run.sh: Glint against Embree, POV-Ray and Cycles (docs/performance.md)

BUILD_DIR   ?= build
BUILD_TYPE  ?= Release
GLINT_WERROR ?= OFF
JOBS        ?= $(shell nproc 2>/dev/null || echo 2)

# Debian packages: compiler and build tools, then libraries (see docs/dependencies in README);
# Open MPI (openmpi-bin, libopenmpi-dev) for glint-mpi and its tests (docs/scale-out.md).
DEPS := g++ cmake make pkg-config libcli11-dev libstb-dev libpng-dev libopenexr-dev \
        libtinyobjloader-dev libtinygltf-dev nlohmann-json3-dev libdraco-dev libmeshoptimizer-dev \
        libgtest-dev libgmock-dev openmpi-bin libopenmpi-dev

# `make bench`: what the benchmark build and bench/run.sh need (no test libraries; Embree for
# the traversal comparison, POV-Ray for the whole renders, bc for bench/course_stats.sh,
# Blender for the path tracer against Cycles, bench/cycles/: about 580 MB with its libraries;
# draco and gltfpack, whose tools compress the 1M-triangle glTF for bench/mesh_stats.sh;
# Assimp for the PLY and STL readers against it, bench/mesh_load_stats.sh; python3-numpy for
# Blender's glTF importer, bench/cycles/gltf/).
BENCH_DIR  ?= build-bench
BENCH_DEPS := g++ cmake make pkg-config libcli11-dev libstb-dev libpng-dev libopenexr-dev \
              libtinyobjloader-dev libtinygltf-dev nlohmann-json3-dev libdraco-dev \
              libmeshoptimizer-dev libembree-dev povray bc blender draco gltfpack libassimp-dev \
              python3-numpy

SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

FUZZ_DEPS := clang libclang-rt-14-dev cmake make pkg-config libcli11-dev libstb-dev libpng-dev \
             libopenexr-dev libtinyobjloader-dev libtinygltf-dev nlohmann-json3-dev libdraco-dev \
             libmeshoptimizer-dev
FUZZ_SECONDS ?= 60

.PHONY: deps build demo test test-sanitize fuzz clean bench

deps:
	@missing=""; \
	for p in $(DEPS); do dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'ok installed' || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "glint: installing missing Debian packages:$$missing"; \
	  export DEBIAN_FRONTEND=noninteractive; \
	  $(SUDO) apt-get install -y -q --no-install-recommends $$missing || \
	  { $(SUDO) apt-get update -q && $(SUDO) apt-get install -y -q --no-install-recommends $$missing; }; \
	fi

$(BUILD_DIR)/CMakeCache.txt:
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DGLINT_WERROR=$(GLINT_WERROR)

build: $(BUILD_DIR)/CMakeCache.txt
	cmake -S . -B $(BUILD_DIR) -DGLINT_WERROR=$(GLINT_WERROR) >/dev/null
	cmake --build $(BUILD_DIR) -j $(JOBS)

demo: deps
	@$(MAKE) --no-print-directory build
	./$(BUILD_DIR)/glint -o glint.png
	@echo "glint: demo render written to $(CURDIR)/glint.png"

test: deps
	@$(MAKE) --no-print-directory build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# The unit, golden and CLI tests again, built with AddressSanitizer and UndefinedBehaviorSanitizer
# (plus float-cast-overflow, which GCC leaves out of -fsanitize=undefined). -O1 -g1 (line tables
# only) halves the compile time of -O2 -g, and reports still name functions, files and lines.
# Each test binary runs as two shards rather than one process per test case (tests/CMakeLists.txt).
test-sanitize: deps
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DGLINT_TEST_SHARDS=2 \
	  -DGLINT_SANITIZE=address,undefined,float-cast-overflow -DGLINT_WERROR=$(GLINT_WERROR)
	cmake --build build-asan -j $(JOBS)
	cd build-asan && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ctest --output-on-failure -j $(JOBS)

# Every libFuzzer harness for FUZZ_SECONDS (default 60) from the seed corpus (docs/robustness.md).
fuzz:
	@$(MAKE) --no-print-directory deps DEPS="$(FUZZ_DEPS)"
	cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
	  -DGLINT_BUILD_FUZZERS=ON -DGLINT_BUILD_TESTS=OFF -DGLINT_AVX2=OFF
	cmake --build build-fuzz -j $(JOBS)
	fuzz/run.sh build-fuzz $(FUZZ_SECONDS)

clean:
	rm -rf $(BUILD_DIR) build-asan build-fuzz

bench:
	@$(MAKE) --no-print-directory deps DEPS="$(BENCH_DEPS)"
	cmake -S . -B $(BENCH_DIR) -DCMAKE_BUILD_TYPE=Release -DGLINT_BUILD_BENCH=ON \
	  -DGLINT_BUILD_TESTS=OFF -DGLINT_WERROR=$(GLINT_WERROR)
	cmake --build $(BENCH_DIR) -j $(JOBS)
	bench/run.sh $(BENCH_DIR)
