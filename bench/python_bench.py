#!/usr/bin/python3
"""`import specula` against the C++ batch path (docs/python.md): each lobe over 10^7 float32
cosines from NumPy, per tier, beside `specula bench`'s streaming figure for the same lobe, tier
and lane type on one core, and NumPy's own c**n as a third column; then whole models over 2^20
(L, V) pairs of directions, m(l, v, out=…) from (N, 3) arrays, beside specula_bench's brdf_batch (the
same SIMD path over structure-of-arrays columns, one thread).

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python_bench.py --specula build/release/specula \
        --cpp-bench build/release/bench/specula_bench

The lobe of `specula bench` runs over a 256 MiB stream; here the array is 40 MB (also beyond any
cache) and the output is written into a preallocated array (out=), as the bench writes its own.
Timings are of this machine now: compare the ratios.
"""
import argparse
import json
import subprocess
import time

import numpy as np

import specula

LOBES = {"power": "phong", "schlick": "schlick", "gauss": "gauss", "log": "log"}


def best_seconds(work, repeats):
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        work()
        best = min(best, time.perf_counter() - start)
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--specula", default="build/release/specula", help="the CLI of the same build")
    parser.add_argument("--count", type=int, default=10**7, help="cosines per call (default 10^7)")
    parser.add_argument("--repeats", type=int, default=15)
    parser.add_argument("--n", type=float, default=20)
    parser.add_argument("--cpp-bench", default="build/release/bench/specula_bench",
                        help="specula_bench of the same build, for the BRDF rows ('' to skip them)")
    parser.add_argument("--json", help="also write the table as JSON here")
    options = parser.parse_args()

    bench = json.loads(subprocess.run([options.specula, "bench", "--format", "json", "--n", str(options.n)],
                                      check=True, capture_output=True, text=True).stdout)
    rng = np.random.default_rng(1)
    c = rng.uniform(0, 1, options.count).astype(np.float32)
    out = np.empty_like(c)
    numpy_ns = best_seconds(lambda: np.power(c, np.float32(options.n), out=out), options.repeats) / c.size * 1e9
    rows = []
    print(f"{options.count} float32 cosines, n = {options.n:g}, best of {options.repeats}; ns per value, one core")
    print(f"{'lobe':<10} {'tier':<6} {'C++ batch':>10} {'Python':>10} {'ratio':>7} {'NumPy c**n':>11}")
    for family, model_id in LOBES.items():
        m = specula.model(model_id, n=options.n)
        for tier in ("exact", "fast"):
            python_ns = best_seconds(lambda: m.lobe(c, tier=tier, out=out), options.repeats) / c.size * 1e9
            cpp_ns = bench["lobes"][family][tier]["float"]["ns_per_eval"]["stream"]
            rows.append({"lobe": model_id, "tier": tier, "cpp_ns": cpp_ns, "python_ns": python_ns,
                         "ratio": python_ns / cpp_ns, "numpy_pow_ns": numpy_ns})
            print(f"{model_id:<10} {tier:<6} {cpp_ns:>10.3f} {python_ns:>10.3f} {python_ns / cpp_ns:>7.2f} {numpy_ns:>11.3f}")
    if options.cpp_bench:
        rows += brdf_rows(options)
    if options.json:
        with open(options.json, "w", encoding="utf-8") as f:
            json.dump(rows, f, indent=2)


def hemisphere(rng, count):
    z, phi = rng.uniform(0, 1, count), rng.uniform(0, 2 * np.pi, count)
    r = np.sqrt(1 - z * z)
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=-1)


def brdf_rows(options):
    """m(l, v) over 2^20 direction pairs against specula_bench's brdf_batch/<model>/<tier> (its best
    of five repetitions)."""
    done = subprocess.run([options.cpp_bench, "--benchmark_filter=brdf_batch", "--benchmark_format=json",
                           "--benchmark_min_time=0.2", "--benchmark_repetitions=5"],
                          check=True, capture_output=True, text=True)
    cpp = {}  # the best repetition, as Python's best call
    for b in json.loads(done.stdout)["benchmarks"]:
        if b.get("run_type", "iteration") == "iteration":
            name = b["run_name"] if "run_name" in b else b["name"]
            cpp[name] = min(cpp.get(name, float("inf")), b["t_per_eval"] * 1e9)
    rng = np.random.default_rng(1)
    count = 1 << 20
    l, v = hemisphere(rng, count), hemisphere(rng, count)
    rows = []
    print(f"\n{count} direction pairs (L, V), N = +z, float64; ns per value, one core")
    print(f"{'model':<18} {'tier':<6} {'C++ batch':>10} {'Python':>10} {'ratio':>7}")
    for name, cpp_ns in cpp.items():
        _, model_id, tier = name.split("/")
        m = specula.model(model_id)
        out = np.empty(count)
        python_ns = best_seconds(lambda: m(l, v, tier=tier, out=out), options.repeats) / count * 1e9
        rows.append({"model": model_id, "tier": tier, "cpp_ns": cpp_ns, "python_ns": python_ns,
                     "ratio": python_ns / cpp_ns})
        print(f"{model_id:<18} {tier:<6} {cpp_ns:>10.3f} {python_ns:>10.3f} {python_ns / cpp_ns:>7.2f}")
    return rows


if __name__ == "__main__":
    main()
