#!/usr/bin/python3
"""Lowest-PI wins of one pipeline against every other, per test and bench, from bench.json files.

  bench_wins.py BENCH_DIR [BENCH_DIR ...] --pipeline P [--versus Q] [--among R1,R2,...]

BENCH_DIR holds a `casmap bench` output (bench.json), typically one per simulator seed. Per test
(T, TR, TP, TRP) and BENCH_DIR: the runs (courses) in which P has the lowest PI of all the
pipelines the bench scored (ties count as wins, as in the Scoreboard), the runs in which P kept
every pole, and which pipelines had the lowest PI where P did not. With --versus Q, the paired
difference PI(P) - PI(Q) over all runs of the test: mean, sample standard deviation and the
share of runs where P is lower; issue 10's goal (>= 14 of 16 wins in every test) needs P ahead
of every rival by well over one standard deviation of that difference. With --among, only
those pipelines are P's rivals (e.g. the paper's filters and the Kalman baselines: how P fares
against established mappers rather than against its own variants). Markdown on stdout.
Exit status 2 for bad input (a missing or unreadable bench.json, a pipeline it did not score),
naming the file.
"""
import argparse
import json
import math
import os
import sys
from collections import Counter

TESTS = ["T", "TR", "TP", "TRP"]


def fail(message):
    print(f"bench_wins.py: {message}", file=sys.stderr)
    sys.exit(2)


def load(directory, names):
    path = os.path.join(directory, "bench.json")
    try:
        with open(path, encoding="utf-8") as f:
            runs = json.load(f)["runs"]
        for r in runs:
            for n in names:
                if n not in r["filters"]:
                    fail(f"{path}: pipeline {n!r} not scored in run course {r['course']} "
                         f"{r['test']} (bench with --pipelines all or a list that has it)")
            _ = (r["test"], r["course"], [v["pi"] for v in r["filters"].values()])
    except (OSError, ValueError, KeyError, TypeError) as e:
        fail(f"{path}: not a readable bench.json ({e})")
    return runs


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dirs", nargs="+", metavar="BENCH_DIR")
    ap.add_argument("--pipeline", required=True, help="the pipeline whose wins are counted")
    ap.add_argument("--versus", help="a rival: paired PI difference per test")
    ap.add_argument("--among", help="comma-separated rivals (default: every scored pipeline)")
    args = ap.parse_args()
    rivals = [n for n in args.among.split(",") if n] if args.among is not None else None
    if rivals is not None and not rivals:
        fail("--among: no pipeline named")
    names = [args.pipeline] + ([args.versus] if args.versus else []) + (rivals or [])
    benches = [(d, load(d, names)) for d in args.dirs]
    p = args.pipeline
    against = "every scored pipeline" if rivals is None else ", ".join(rivals)
    print(f"Lowest-PI wins of {p} (ties count) against {against}; poles: runs with every pole "
          "kept.\n")
    print("| test | " + " | ".join(os.path.basename(os.path.normpath(d)) for d, _ in benches) +
          " | total | sets at >= 14/16 | every pole | beaten by |")
    print("|---" * (len(benches) + 5) + "|")
    diffs = {t: [] for t in TESTS}
    for test in TESTS:
        cells, wins, total, poles, beaten, sets = [], 0, 0, 0, Counter(), 0
        for _, runs in benches:
            w = n = 0
            for r in runs:
                if r["test"] != test:
                    continue
                f = r["filters"]
                if rivals is not None:
                    f = {k: v for k, v in f.items() if k == p or k in rivals}
                best = min(v["pi"] for v in f.values())
                n += 1
                if f[p]["pi"] <= best + 1e-12:
                    w += 1
                else:
                    beaten[min(f, key=lambda k: (f[k]["pi"], k))] += 1
                if f[p].get("poles_kept") == f[p].get("poles"):
                    poles += 1
                if args.versus:
                    diffs[test].append(f[p]["pi"] - f[args.versus]["pi"])
            cells.append(f"{w}/{n}" if n else "-")
            sets += n > 0 and 16 * w >= 14 * n  # the goal's share: 14 of 16 courses
            wins += w
            total += n
        if total == 0:
            continue
        who = ", ".join(f"{k} {v}" for k, v in sorted(beaten.items(), key=lambda kv: (-kv[1], kv[0])))
        with_runs = sum(c != "-" for c in cells)
        print(f"| {test} | " + " | ".join(cells) + f" | {wins}/{total} | {sets}/{with_runs} | "
              f"{poles}/{total} | "
              f"{who or '-'} |")
    if args.versus:
        print(f"\nPaired PI({p}) - PI({args.versus}) per run:\n")
        print("| test | runs | mean | sd | mean / sd | share below 0 |")
        print("|---|---|---|---|---|---|")
        for test in TESTS:
            x = diffs[test]
            if not x:
                continue
            mean = sum(x) / len(x)
            sd = math.sqrt(sum((v - mean) ** 2 for v in x) / (len(x) - 1)) if len(x) > 1 else 0.0
            ratio = f"{mean / sd:+.2f}" if sd > 0 else "-"
            below = sum(v < 0 for v in x) / len(x)
            print(f"| {test} | {len(x)} | {mean:+.4f} | {sd:.4f} | {ratio} | {below:.2f} |")


if __name__ == "__main__":
    main()
