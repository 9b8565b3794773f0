# The two commands a new user types: `make run` and `make test`.
# Both install missing Debian packages first (scripts/install-deps.sh), then build.
BUILD  ?= build
JOBS   ?= $(shell nproc)
MAKEFLAGS += --no-print-directory
CMAKE_FLAGS ?=

.PHONY: all deps configure build run test test-fast test-slow test-sanitize test-slurm mutations bench bench-peers tradeoffs format clean

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) > /dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# The main job: the default study (spheres, Table 2 Samples 1 and 2 at smoke scale)
# into results/default.h5, its summary and the comparison with the paper's numbers,
# then the paper's figures from it as PNG files in results/. It builds only the
# `ballast` binary (the tests and benchmarks are make test's and make bench's). It is the demo: it replaces results/default.h5 each time.
# A study with failed runs (exit 3, listed in the table) still draws the figures of
# the others, and make run then ends with the study's status.
run: configure
	@cmake --build $(BUILD) -j $(JOBS) --target ballast
	@mkdir -p results
	@rm -rf results/default.h5 results/default.h5.parts
	@status=0; $(BUILD)/study/ballast study cases/default_study.json -o results/default.h5 || status=$$?; \
	  if [ $$status -ne 0 ] && [ $$status -ne 3 ]; then exit $$status; fi; \
	  echo; echo "Beside the paper (Lu & McDowell 2007), with the scale each run is at:"; \
	  /usr/bin/python3 scripts/compare.py results/default.h5 || exit $$?; echo; \
	  /usr/bin/python3 scripts/figures.py results/default.h5 --out results/ || exit $$?; \
	  exit $$status

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# Fast tests only (everything without the `slow` label).
test-fast: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -LE slow

test-slow: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -L slow

# The fast tests built with AddressSanitizer and UndefinedBehaviorSanitizer in a build
# folder of their own; any report of either fails the test it happens in. -O1 keeps
# the suite to a few minutes; frame pointers give readable stacks.
SANITIZE_FLAGS = -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all
test-sanitize: deps
	@cmake -S . -B $(BUILD)-sanitize -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="$(SANITIZE_FLAGS)" \
	  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" > /dev/null
	@cmake --build $(BUILD)-sanitize -j $(JOBS)
	@cd $(BUILD)-sanitize && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	  UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j $(JOBS) -LE slow

# scripts/slurm_study.sh on a real one-node Slurm (docs/CLUSTER.md):
# scripts/slurm_local_cluster.sh installs Debian's Slurm and munge if missing and starts
# them; tests/slurm/test_slurm_cluster.py submits a small study as 2 shards and a merge
# job, requeues one shard and cancels the other in the middle of a run, submits again,
# and compares the merged archive with the study run locally. The cluster is stopped
# afterwards whatever the outcome, and the test's status kept. Needs root; not part of
# `make test`. About 1.7 minutes on 2 cores, Slurm's install included.
test-slurm: build
	@status=0; \
	  { bash scripts/slurm_local_cluster.sh start && \
	    /usr/bin/python3 tests/slurm/test_slurm_cluster.py $(BUILD)/study/ballast; } || status=$$?; \
	  bash scripts/slurm_local_cluster.sh stop || [ $$status -ne 0 ] || status=1; \
	  exit $$status

# Each one-line engine mutation in tests/mutations.tsv must make its test fail
# (docs/TESTING.md); restores every file it touches. About 20 minutes on 2 cores.
mutations: build
	@/usr/bin/python3 tests/check_mutations.py --build $(BUILD)

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

# Speed against accuracy on the box test (docs/TRADEOFFS.md): the studies, tables and
# Pareto plots of Sample 1 and spheres, into docs/tradeoffs. SCALE=smoke (default,
# under half an hour), extended (smoke's and the variants it leaves out, sharing its
# archives) or full (the paper's box, overnight); an interrupted run resumes where it
# stopped.
TRADEOFF_SCALE = $(or $(SCALE),smoke)
tradeoffs: build
	@JOBS=$(JOBS) bash scripts/tradeoffs.sh $(TRADEOFF_SCALE) \
	  $(BUILD)/tradeoffs/$(subst extended,smoke,$(TRADEOFF_SCALE))

format:
	@git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

clean:
	@rm -rf $(BUILD)
