#!/usr/bin/python3
"""Compare Google Benchmark results with the committed baseline of this machine.

    scripts/bench_compare.py                      # run build/bench/*_benchmark, compare
    scripts/bench_compare.py RUN.json [...]       # compare saved runs (--benchmark_out=RUN.json)
    scripts/bench_compare.py --record             # run and write the baseline of this machine
    scripts/bench_compare.py --self-test          # check the comparison on two fixed files

The baseline is bench/baselines/<machine>.json (one Google Benchmark JSON document holding the
benchmarks of every program, named after the CPU model and core count, as Ceres names its
per-machine results); --baseline FILE picks another. Each benchmark is compared by its median
(the "median" aggregate when the program reports aggregates, else the median over its iteration
runs) of CPU time, or of real time with --real-time. A benchmark more than --threshold (default
0.15, i.e. 15%) slower than the baseline is flagged and the exit code is 1; 0 when nothing is
slower, 2 for bad usage or unreadable files. Timings are not unit tests: run this on an idle
machine (docs/benchmarks.md, "Baseline and comparison").

Only the Python standard library is used (Debian's /usr/bin/python3).
"""

import argparse
import glob
import json
import os
import platform
import re
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
UNIT_NS = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}


def machine_name():
    """CPU model and logical core count as a file name, e.g. amd-epyc-7b13-2cpu."""
    model = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1]
                    break
    except OSError:
        pass
    slug = re.sub(r"\((r|tm)\)|cpu|processor|@.*$", " ", model.lower())
    slug = re.sub(r"[^a-z0-9]+", "-", slug).strip("-") or "unknown"
    return f"{slug}-{os.cpu_count() or 1}cpu"


def load(path):
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, ValueError) as e:
        raise SystemExit(f"bench_compare: cannot read {path}: {e}") from None
    if not isinstance(doc, dict) or not isinstance(doc.get("benchmarks"), list):
        raise SystemExit(f"bench_compare: {path}: not a Google Benchmark JSON document (no 'benchmarks' list)")
    return doc


def medians(doc, field):
    """{benchmark name: median time in ns} from one document."""
    aggregates, runs = {}, {}
    for b in doc["benchmarks"]:
        name = b.get("run_name") or b.get("name")
        if field not in b or name is None or b.get("error_occurred"):
            continue
        t = float(b[field]) * UNIT_NS.get(b.get("time_unit", "ns"), 1.0)
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                aggregates[name] = t
        else:
            runs.setdefault(name, []).append(t)
    out = {name: statistics.median(ts) for name, ts in runs.items()}
    out.update(aggregates)
    return out


def compare(base, new, threshold, field, out=sys.stdout):
    """Prints a table; returns the names of the benchmarks slower than the threshold."""
    b, n = medians(base, field), medians(new, field)
    slower = []
    print(f"{'benchmark':44} {'baseline':>12} {'now':>12} {'change':>8}", file=out)
    for name in sorted(set(b) | set(n)):
        if name not in n:
            print(f"{name:44} {b[name]:12.4g} {'(not run)':>12}", file=out)
            continue
        if name not in b:
            print(f"{name:44} {'(new)':>12} {n[name]:12.4g}", file=out)
            continue
        change = n[name] / b[name] - 1.0 if b[name] > 0 else 0.0
        flag = ""
        if change > threshold:
            slower.append(name)
            flag = "  SLOWER"
        print(f"{name:44} {b[name]:12.4g} {n[name]:12.4g} {100 * change:+7.1f}%{flag}", file=out)
    print(f"(times in ns, median {field}; flagged above +{100 * threshold:.0f}%)", file=out)
    return slower


def run_benchmarks(build_dir, pattern, repetitions):
    """Runs every matching benchmark program; returns one merged document."""
    programs = sorted(glob.glob(os.path.join(build_dir, "bench", "*_benchmark")))
    programs = [p for p in programs if re.search(pattern, os.path.basename(p))]
    if not programs:
        raise SystemExit(f"bench_compare: no benchmark programs matching '{pattern}' in {build_dir}/bench "
                         "(configure with Google Benchmark installed and build them)")
    merged = {"context": None, "benchmarks": []}
    with tempfile.TemporaryDirectory() as tmp:
        for prog in programs:
            out = os.path.join(tmp, os.path.basename(prog) + ".json")
            cmd = [prog, f"--benchmark_out={out}", "--benchmark_out_format=json",
                   f"--benchmark_repetitions={repetitions}"]
            print("running", " ".join(cmd[:1]), file=sys.stderr)
            if subprocess.run(cmd, stdout=subprocess.DEVNULL, check=False).returncode != 0:
                raise SystemExit(f"bench_compare: {prog} failed")
            doc = load(out)
            merged["context"] = merged["context"] or doc.get("context")
            merged["benchmarks"].extend(doc["benchmarks"])
    merged["context"] = dict(merged["context"] or {}, machine=machine_name())
    return merged


def self_test():
    """The comparison on two fixed files: identical runs pass, a 30% slower one is flagged."""
    data = os.path.join(ROOT, "bench", "baselines", "selftest")
    base, slow = load(os.path.join(data, "base.json")), load(os.path.join(data, "slow.json"))
    sink = open(os.devnull, "w", encoding="utf-8")
    checks = [
        (compare(base, base, 0.15, "cpu_time", sink) == [], "identical runs flagged"),
        (compare(base, slow, 0.15, "cpu_time", sink) == ["BM_T1Join/repeats:5"], "the slower median not flagged alone"),
        (compare(base, slow, 0.50, "cpu_time", sink) == [], "a 30% slowdown flagged at threshold 50%"),
        (compare(slow, base, 0.15, "cpu_time", sink) == [], "a speed-up flagged"),
        (medians(slow, "cpu_time")["BM_T2Plan/16"] == 1.5e6, "median of iteration runs (ms -> ns)"),
    ]
    sink.close()
    failed = [what for ok, what in checks if not ok]
    for what in failed:
        print("bench_compare self-test FAILED:", what, file=sys.stderr)
    print(f"bench_compare self-test: {len(checks) - len(failed)} of {len(checks)} checks passed")
    return 1 if failed else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="*", help="saved runs (Google Benchmark JSON); none: run the benchmarks")
    ap.add_argument("--baseline", help="baseline file (default bench/baselines/<machine>.json)")
    ap.add_argument("--threshold", type=float, default=0.15, help="flag a slowdown above this fraction (0.15)")
    ap.add_argument("--real-time", action="store_true", help="compare real (wall) time instead of CPU time")
    ap.add_argument("--build-dir", default=os.path.join(ROOT, "build"), help="build tree with bench/ (build)")
    ap.add_argument("--filter", default=".", help="regex on the program names to run (all)")
    ap.add_argument("--repetitions", type=int, default=3, help="--benchmark_repetitions of each program (3)")
    ap.add_argument("--record", action="store_true", help="write the run as the baseline instead of comparing")
    ap.add_argument("--self-test", action="store_true", help="check the comparison on two fixed files")
    args = ap.parse_args()
    if args.self_test:
        return self_test()
    if not (0 < args.threshold < 10) or args.repetitions < 1:
        ap.error("--threshold must be in (0, 10) and --repetitions >= 1")
    baseline = args.baseline or os.path.join(ROOT, "bench", "baselines", machine_name() + ".json")
    if args.runs:
        new = {"benchmarks": [b for path in args.runs for b in load(path)["benchmarks"]]}
    else:
        new = run_benchmarks(args.build_dir, args.filter, args.repetitions)
    if args.record:
        with open(baseline, "w", encoding="utf-8") as f:
            json.dump(new, f, indent=1)
            f.write("\n")
        print("wrote", os.path.relpath(baseline, ROOT))
        return 0
    if not os.path.exists(baseline):
        folder = os.path.dirname(baseline)
        known = sorted(f for f in os.listdir(folder) if f.endswith(".json")) if os.path.isdir(folder) else []
        print(f"bench_compare: no baseline {baseline} for this machine; record one with --record "
              f"or name one with --baseline (committed: {', '.join(known) or 'none'})", file=sys.stderr)
        return 2
    slower = compare(load(baseline), new, args.threshold, "real_time" if args.real_time else "cpu_time")
    if slower:
        print(f"{len(slower)} benchmark(s) slower than the baseline by more than {100 * args.threshold:.0f}%: "
              + ", ".join(slower), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
