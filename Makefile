# The two commands a new user types: `make run` and `make test`.
# Both install missing Debian packages first (scripts/install-deps.sh), then build.
BUILD  ?= build
JOBS   ?= $(shell nproc)
MAKEFLAGS += --no-print-directory
CMAKE_FLAGS ?=

.PHONY: all deps configure build run test test-fast test-slow bench bench-peers format clean

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) > /dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# The main job. Until the study runner exists this is the settling demo.
run: build
	@$(BUILD)/study/ballast demo

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# Fast tests only (everything without the `slow` label).
test-fast: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -LE slow

test-slow: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -L slow

bench: build
	@$(BUILD)/tests/bench/ballast_bench --benchmark_counters_tabular=true

# Side by side with LAMMPS and YADE on the same settled beds (issue 7,
# docs/PERFORMANCE.md "Peers"): installs the two codes if missing, builds the beds
# once (cached in $(BUILD)/peers), checks the conventions, times every code and
# cross-checks the physics. Not part of `make test`: CI never installs the peers.
bench-peers: build
	@bash scripts/install-peers.sh
	@/usr/bin/python3 tests/bench/peers/bench_peers.py --ballast $(BUILD)/study/ballast \
	  --cases cases --cache $(BUILD)/peers $(PEERS_FLAGS)

format:
	@git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

clean:
	@rm -rf $(BUILD)
