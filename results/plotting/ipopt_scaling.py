#!/usr/bin/env python3
"""Ipopt's NLP scaling over the library (results/notes/2026-12-07-ipopt-scaling.md).

  python3 results/plotting/ipopt_scaling.py suite bench/suites/library.json > /tmp/ipopt-scaling.json
  build/bin/ocpbench run /tmp/ipopt-scaling.json --out /tmp/ipopt-scaling --jobs 2
  python3 results/plotting/ipopt_scaling.py compare /tmp/ipopt-scaling/records.jsonl

`suite` keeps every Ipopt case of the library suite (its problems, schemes and N) twice, with
nlp_scaling_method gradient-based (Ipopt's default) and none, each limited to 120 s of CPU.
`compare` pairs the two cases of each (problem, scheme, N) and prints the status pairs, the
ratios of iterations and CPU where both converged, the largest objective differences, the
count within 1e-6 of a continuous reference, and the pairs where only one converged.
"""
import collections
import json
import statistics
import sys

SETTINGS = ("gradient-based", "none")


def make_suite(library_path):
    library = json.load(open(library_path))
    groups = []
    for group in library["groups"]:
        methods = []
        for method in group["methods"]:
            if method["solver"] != "ipopt":
                continue
            for scaling in SETTINGS:
                case = dict(method)
                case["options"] = {"max_cpu_time": 120, "nlp_scaling_method": scaling}
                methods.append(case)
        rest = {k: v for k, v in group.items() if k != "methods"}
        groups.append(dict(rest, methods=methods))
    return {"name": "ipopt-scaling",
            "description": "Ipopt's NLP scaling over the library's Ipopt cases: gradient-based "
                           "(the default) against none, 120 s each "
                           "(results/plotting/ipopt_scaling.py).",
            "groups": groups}


def continuous_error(record):
    ref = record.get("reference")
    if not ref or ref.get("scheme") != "continuous" or record.get("Jbar_fine") is None:
        return None
    return abs(record["Jbar_fine"] - ref["value"]) / max(abs(ref["value"]), 1e-300)


def compare(records_path):
    pairs = collections.defaultdict(dict)
    for line in open(records_path):
        r = json.loads(line)
        scaling = r.get("solver_options", {}).get("nlp_scaling_method")
        pairs[(r["problem"], r["transcription"], r["N"])][scaling] = r
    both = [(k, v) for k, v in pairs.items() if all(s in v for s in SETTINGS)]
    print(f"pairs: {len(both)}")
    statuses = collections.Counter()
    iterations, cpu, objective, solved, only_one = [], [], [], collections.Counter(), []
    for key, v in both:
        g, n = v["gradient-based"], v["none"]
        statuses[(g["status"], n["status"])] += 1
        if g["status"] == n["status"] == "converged":
            iterations.append(n["iterations"] / max(g["iterations"], 1))
            if g["cpu_seconds"] > 0.05 and n["cpu_seconds"] > 0.05:
                cpu.append(n["cpu_seconds"] / g["cpu_seconds"])
            diff = abs(g["objective"] - n["objective"]) / max(1.0, abs(g["objective"]))
            objective.append((diff, key, g["objective"], n["objective"],
                              g["iterations"], n["iterations"]))
            eg, en = continuous_error(g), continuous_error(n)
            if eg is not None and en is not None:
                solved[(eg <= 1e-6, en <= 1e-6)] += 1
        elif (g["status"] == "converged") != (n["status"] == "converged"):
            only_one.append((key, g["status"], n["status"], g["iterations"], n["iterations"]))
    print("status (gradient-based, none):")
    for pair, count in sorted(statuses.items(), key=lambda x: -x[1]):
        print(f"  {pair}: {count}")
    print(f"both converged: iterations none / gradient-based, median "
          f"{statistics.median(iterations):.2f} [{min(iterations):.2f}, {max(iterations):.2f}]")
    print(f"CPU none / gradient-based, median {statistics.median(cpu):.2f} "
          f"over {len(cpu)} pairs above 0.05 s")
    print("largest objective differences |f_g - f_n| / max(1, |f_g|) (f_g, f_n, iterations):")
    for diff, key, fg, fn, ig, inn in sorted(objective, reverse=True)[:10]:
        print(f"  {diff:.1e} {key} {fg!r} {fn!r} {ig} {inn}")
    print("within 1e-6 of the continuous reference (gradient-based, none):", dict(solved))
    print("converged with one setting only:")
    for row in only_one:
        print("  ", row)


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("suite", "compare"):
        sys.exit(__doc__)
    if sys.argv[1] == "suite":
        json.dump(make_suite(sys.argv[2]), sys.stdout, indent=1)
        sys.stdout.write("\n")
    else:
        compare(sys.argv[2])


if __name__ == "__main__":
    main()
