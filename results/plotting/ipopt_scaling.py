#!/usr/bin/env python3
"""Ipopt's options over the library: every Ipopt case run once per setting, then compared.

  python3 results/plotting/ipopt_scaling.py suite bench/suites/library.json [SETTING ...] > S.json
  build/bin/ocpbench run S.json --out DIR --jobs 2
  python3 results/plotting/ipopt_scaling.py compare DIR/records.jsonl [SETTING ...]

A SETTING is `default` (Ipopt's own) or `name=value[,name=value]` (Ipopt options); the first is
the baseline every other one is compared with. Without settings: `nlp_scaling_method=
gradient-based` against `nlp_scaling_method=none` (results/notes/2026-12-07-ipopt-scaling.md).
The MUMPS study (results/notes/2026-12-07-ipopt-mumps-scaling.md) ran `default
mumps_permuting_scaling=0 mumps_scaling=0`.

`suite` keeps every Ipopt case of the library suite (its problems, schemes and N) once per
setting, each limited to 120 s of CPU. `compare` pairs each setting's case of a (problem,
scheme, N) with the baseline's and prints the status pairs, the ratios of iterations and CPU
where both converged, the largest objective differences, the count within 1e-6 of a continuous
reference, and the pairs where only one converged.
"""
import collections
import json
import statistics
import sys

DEFAULT_SETTINGS = ("nlp_scaling_method=gradient-based", "nlp_scaling_method=none")


def parse_setting(text):
    if text == "default":
        return {}
    return dict(item.split("=", 1) for item in text.split(","))


def make_suite(library_path, settings):
    library = json.load(open(library_path))
    groups = []
    for group in library["groups"]:
        methods = []
        for method in group["methods"]:
            if method["solver"] != "ipopt":
                continue
            for setting in settings:
                case = dict(method)
                case["options"] = {"max_cpu_time": 120, **parse_setting(setting)}
                methods.append(case)
        rest = {k: v for k, v in group.items() if k != "methods"}
        groups.append(dict(rest, methods=methods))
    return {"name": "ipopt-options",
            "description": "Ipopt over the library's Ipopt cases with the settings "
                           + ", ".join(settings) + "; 120 s each "
                           "(results/plotting/ipopt_scaling.py).",
            "groups": groups}


def continuous_error(record):
    ref = record.get("reference")
    if not ref or ref.get("scheme") != "continuous" or record.get("Jbar_fine") is None:
        return None
    return abs(record["Jbar_fine"] - ref["value"]) / max(abs(ref["value"]), 1e-300)


def setting_of(record, settings):
    # The case's own options (what the suite set), not the resolved solver_options: those list
    # every option with its value, defaults included, so `default` would match no case once a
    # setting names an option Ipopt's table resolves (tol, mu_strategy).
    options = record.get("options", {})
    for setting in settings:
        wanted = parse_setting(setting)
        names = set().union(*(parse_setting(s).keys() for s in settings))
        if all(str(options.get(k)) == str(v) for k, v in wanted.items()) and all(
                k in wanted for k in names if k in options):
            return setting
    return None


def compare_pair(both, base, other):
    statuses = collections.Counter()
    iterations, cpu, objective, solved, only_one = [], [], [], collections.Counter(), []
    for key, v in both:
        g, n = v[base], v[other]
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
            only_one.append((key, g["status"], n["status"], g["iterations"], n["iterations"],
                             round(g["cpu_seconds"], 2), round(n["cpu_seconds"], 2)))
    print(f"== {other} against {base}: {len(both)} pairs")
    print(f"status ({base}, {other}):")
    for pair, count in sorted(statuses.items(), key=lambda x: -x[1]):
        print(f"  {pair}: {count}")
    if iterations:
        print(f"both converged: iterations {other} / {base}, median "
              f"{statistics.median(iterations):.2f} [{min(iterations):.2f}, {max(iterations):.2f}]")
    if cpu:
        print(f"CPU {other} / {base}, median {statistics.median(cpu):.2f} "
              f"[{min(cpu):.2f}, {max(cpu):.2f}] over {len(cpu)} pairs above 0.05 s")
    print("largest objective differences |f_base - f_other| / max(1, |f_base|) "
          "(f_base, f_other, iterations):")
    for diff, key, fg, fn, ig, inn in sorted(objective, reverse=True)[:10]:
        print(f"  {diff:.1e} {key} {fg!r} {fn!r} {ig} {inn}")
    print(f"within 1e-6 of the continuous reference ({base}, {other}):", dict(solved))
    print("converged with one setting only (key, statuses, iterations, CPU):")
    for row in only_one:
        print("  ", row)


def compare(records_path, settings):
    cases = collections.defaultdict(dict)
    for line in open(records_path):
        r = json.loads(line)
        setting = setting_of(r, settings)
        if setting is not None:
            cases[(r["problem"], r["transcription"], r["N"])][setting] = r
    base = settings[0]
    for other in settings[1:]:
        both = [(k, v) for k, v in cases.items() if base in v and other in v]
        compare_pair(both, base, other)


def main():
    if len(sys.argv) < 3 or sys.argv[1] not in ("suite", "compare"):
        sys.exit(__doc__)
    settings = tuple(sys.argv[3:]) or DEFAULT_SETTINGS
    if sys.argv[1] == "suite":
        json.dump(make_suite(sys.argv[2], settings), sys.stdout, indent=1)
        sys.stdout.write("\n")
    else:
        compare(sys.argv[2], settings)


if __name__ == "__main__":
    main()
