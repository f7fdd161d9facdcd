"""The binding's overhead per call on task T1 (docs/benchmarks.md): the same 64 joins as
bench/join_benchmark (lambda = 2, mu = 1, (theta, phi, psi) = (pi/3, 0.4, 0.1), targets at distance
0.05), timed from Python three ways: the keyword call pb.join(model=..., target=...), pb.join(problem,
options) with prebuilt objects and the native pb._join(problem, options), and the C++ figure from bench/join_benchmark
when its path is given. Prints medians of `--repetitions` runs of `--rounds` x 64 joins, in CPU time
(process time here, the benchmark's cpu_time there), so that a busy machine skews both alike.

    PYTHONPATH=build/python /usr/bin/python3 python/bench/join_overhead.py [--cxx build/bench/join_benchmark]
"""
import argparse
import json
import math
import statistics
import subprocess
import time

import plateball as pb


def median_us(fn, calls, repetitions):
    times = []
    for _ in range(repetitions):
        t0 = time.process_time()
        fn()
        times.append((time.process_time() - t0) / calls * 1e6)
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--rounds", type=int, default=40)
    parser.add_argument("--repetitions", type=int, default=5)
    parser.add_argument("--cxx", help="path of bench/join_benchmark, to time the C++ call on the same machine")
    args = parser.parse_args()
    model = pb.BallModel(2.0)
    start = pb.AngleState(math.pi / 3, 0.4, 0.1)
    targets = [(0.05 * math.cos(2 * math.pi * k / 64), 0.05 * math.sin(2 * math.pi * k / 64)) for k in range(64)]
    problems = [pb.JoinProblem(model=model, start=start, mu=1.0, target=t) for t in targets]
    options = pb.JoinOptions()
    calls = 64 * args.rounds

    def keyword_loop():
        for _ in range(args.rounds):
            for t in targets:
                pb.join(model=model, start=start, mu=1.0, target=t)

    def object_loop():
        for _ in range(args.rounds):
            for p in problems:
                pb._join(p, options)

    def wrapper_loop():
        for _ in range(args.rounds):
            for p in problems:
                pb.join(p, options)

    ok = sum(pb._join(p, options).status == "converged" for p in problems)
    result = {"joins_converged": ok, "python_object_call_us": median_us(object_loop, calls, args.repetitions),
              "python_join_objects_us": median_us(wrapper_loop, calls, args.repetitions),
              "python_keyword_call_us": median_us(keyword_loop, calls, args.repetitions)}
    if args.cxx:
        out = subprocess.run([args.cxx, "--benchmark_format=json", "--benchmark_repetitions=5",
                              "--benchmark_report_aggregates_only=true"], check=True, capture_output=True, text=True)
        rows = json.loads(out.stdout)["benchmarks"]
        median = next(r for r in rows if r.get("aggregate_name") == "median")
        result["cxx_us"] = median["cpu_time"]
        result["overhead_object_call_us"] = result["python_object_call_us"] - result["cxx_us"]
        result["overhead_join_objects_us"] = result["python_join_objects_us"] - result["cxx_us"]
        result["overhead_keyword_call_us"] = result["python_keyword_call_us"] - result["cxx_us"]
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
