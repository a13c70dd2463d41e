# The front door. `make report` and `make test` work on a fresh Debian 12 machine as root.
.PHONY: all deps build debug test report bench bench-fit hostile fuzz clean

all: build

deps:
	@scripts/install-deps

build: deps
	@cmake --preset release >/dev/null
	@cmake --build --preset release

debug: deps
	@cmake --preset debug >/dev/null
	@cmake --build --preset debug

# Each phase timed (scripts/check-times); the summary of where the time went is printed at the
# end, also when a phase fails (docs/testing.md); a test of the before-list (tests/names-before.txt)
# that did not run fails `make test`.
test: deps
	@status=0; \
	scripts/check-times run build/debug configure -- cmake --preset debug >/dev/null && \
	scripts/check-times run build/debug build -- cmake --build --preset debug && \
	scripts/check-times run build/debug test -- ctest --preset debug || status=$$?; \
	scripts/check-times report build/debug || [ $$status -ne 0 ] || status=1; exit $$status

report: deps
	@cmake --preset release >/dev/null
	@cmake --build --preset release --target specula_cli
	@build/release/specula report --out report

# The lobe benchmark (scalar libm against SIMD exact and fast, with the machine's limits; under a
# minute), the energy-table benchmark (cubature against Monte Carlo, a few minutes: the Monte Carlo
# side draws 2^33 samples), then the Google Benchmark timings of the library's other paths, and the
# random walk's time to a standard error of 1e-4 per cell on one core (docs/random-walk.md).
bench: build
	@build/release/bench/specula_lobe_bench
	@build/release/bench/specula_lut_bench
	@build/release/bench/specula_bench
	@build/release/bench/specula_render_bench
	@build/release/bench/specula_walk_bench

# Symbolic recovery (docs/fit.md): `specula fit` on Nguyen-1…12, Keijzer-1…15 and Livermore-1…23 as
# DSR specifies them, seeds 1 and 2, 20 s each (about 40 minutes on 2 cores), judged by SRBench's
# symbolic-solution criterion with SymPy; prints the table and the counts recovered per suite and in
# all (bench/fit/recovery.py).
bench-fit: deps
	@cmake --preset release >/dev/null
	@cmake --build --preset release --target specula_cli
	@/usr/bin/python3 bench/fit/recovery.py --specula build/release/specula

# The hostile test (bench/hostile): the release CLI and `specula serve` on loopback against
# malformed input, user models (files, inline, definition objects), every export compiled, M+ms of
# every model, kills, signals and slow or heavy clients; bounded (about 8 minutes on 2 cores), exit 1
# on any fault. docs/robustness.md states the rules it checks.
hostile: build
	@/usr/bin/python3 bench/hostile/run.py --specula build/release/specula

# The libFuzzer campaign (docs/fuzzing.md): the harnesses of fuzz/ built with clang-16 (ASan +
# UBSan), each run for 10^6 inputs or 150 s, then a table of executions, coverage and findings.
# SPECULA_FUZZ_TIME / SPECULA_FUZZ_RUNS change the budget per harness.
fuzz: deps
	@cmake --preset fuzz >/dev/null
	@cmake --build --preset fuzz
	@scripts/fuzz

clean:
	rm -rf build report
