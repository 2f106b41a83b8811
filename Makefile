# fluidbed: the two commands of the README quick start (make demo, make test) and their parts.
# Each target installs the Debian packages it needs when they are missing.

BUILD      ?= build
ASAN_BUILD ?= build-asan
JOBS       ?= $(shell nproc)
CMAKE_ARGS ?=

DEBS = build-essential cmake ninja-build pkg-config libeigen3-dev libtomlplusplus-dev libcli11-dev libfmt-dev \
       libspdlog-dev libhdf5-dev libgtest-dev libgmock-dev libbenchmark-dev libhypre-dev libopenmpi-dev openmpi-bin \
       zlib1g-dev python3 python3-numpy python3-matplotlib python3-vtk9 universal-ctags

.PHONY: all deps build test test-fast asan demo bench clean

all: build

deps:
	@missing=""; for p in $(DEBS); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "installing Debian packages:$$missing"; \
	  SUDO=""; [ "$$(id -u)" = 0 ] || SUDO=sudo; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq --no-install-recommends $$missing; \
	fi

$(BUILD)/build.ninja: | deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_ARGS)

build: deps $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)

$(ASAN_BUILD)/build.ninja: | deps
	cmake -S . -B $(ASAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Debug -DFLUIDBED_SANITIZE=ON -DFLUIDBED_BENCH=OFF

UNIT_TARGETS = $(patsubst tests/unit/%/,test_unit_%,$(sort $(dir $(wildcard tests/unit/*/*.cpp))))

# Unit and MPI tests under AddressSanitizer + UndefinedBehaviorSanitizer (only those test programs are built there).
asan: deps $(ASAN_BUILD)/build.ninja
	cmake --build $(ASAN_BUILD) -j $(JOBS) --target $(UNIT_TARGETS) test_mpi
	cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest -L 'unit|mpi' --output-on-failure -j $(JOBS)

# Every test of the Release build (unit, verification, cli, post), then the sanitizer build's unit tests.
test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 900
	$(MAKE) asan

test-fast: build
	cd $(BUILD) && ctest -L unit --output-on-failure -j $(JOBS)

# The paper's case(s) and the report.
demo: build
	bash post/demo.sh $(BUILD)/fluidbed

bench: build
	bash bench/run_cases.sh $(BUILD)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD)
