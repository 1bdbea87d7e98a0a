#!/usr/bin/env python3
"""Checks that two records files hold the same cases in the same order with the same results.

Usage: compare_records.py EXPECTED.jsonl ACTUAL.jsonl

Timings are the only fields allowed to differ (they are measured, not computed): every key that
ends in "_seconds" (cpu_seconds, wall_seconds, each history entry's cpu_seconds, the solvers'
own *_seconds statistics, online cycles' predict/solve seconds) and cpu_seconds_repeats, at any
depth. Exit 0 when equal; 1 with the first differences on stderr otherwise.
"""
import json
import sys


def without_timings(value):
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items()
                if not (k.endswith("_seconds") or k == "cpu_seconds_repeats")}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


def read(path):
    with open(path, encoding="utf-8") as f:
        return [json.loads(line) for line in f if line.strip()]


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    expected, actual = read(sys.argv[1]), read(sys.argv[2])
    problems = []
    keys_e = [r["key"] for r in expected]
    keys_a = [r["key"] for r in actual]
    if keys_e != keys_a:
        missing = sorted(set(keys_e) - set(keys_a))
        extra = sorted(set(keys_a) - set(keys_e))
        problems.append(f"case keys differ: {len(keys_e)} expected, {len(keys_a)} found; "
                        f"missing {missing[:5]}, unexpected {extra[:5]}"
                        + ("" if missing or extra else " (same set, another order)"))
    for e, a in zip(expected, actual):
        e2, a2 = without_timings(e), without_timings(a)
        if e2 != a2:
            fields = sorted(k for k in set(e2) | set(a2) if e2.get(k) != a2.get(k))
            problems.append(f"{e['key']}: fields differ: {', '.join(fields)}")
    if not expected:
        problems.append(f"{sys.argv[1]}: no records")
    for p in problems[:10]:
        print("compare_records: " + p, file=sys.stderr)
    if not problems:
        print(f"compare_records: {len(expected)} records equal apart from timings")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
