#!/usr/bin/env python3
"""The HardForm benchmark's table: Ipopt + Euler's CPU over the polish's, per gamma and seed.

    build/bin/ocpbench_kernels --benchmark_filter='HardForm(FamilyPolish|IpoptEuler)/' \
        --benchmark_repetitions=3 --benchmark_enable_random_interleaving=true \
        --benchmark_format=json > hardform.json
    python3 bench/kernels/hardform_ratios.py hardform.json

Per case (method, gamma, seed) the median of the repetitions' `cpu_s` counter (each solve's own
CPU time); per gamma the ratio Ipopt / polish of those medians on every seed, then their median
and minimum. Also per gamma: the polish's Newton steps (every grid's, a failed grid sequence's
included), fallbacks of its grid sequence, its
largest terminal violation, its J relative to Ipopt's (both judged by the common evaluator on the
Euler grid: J without penalty) and how many Ipopt solves converged.
"""
import json
import re
import statistics
import sys
from collections import defaultdict

NAME = re.compile(r"BM_HardForm(\w+)/g:(\d+)/seed:(\d+)")


def load(path):
    """{(method, g, seed): [run dicts]} of the benchmark's iteration rows (no aggregates)."""
    with open(path) as f:
        doc = json.load(f)
    runs = defaultdict(list)
    for b in doc["benchmarks"]:
        if b.get("run_type") != "iteration":
            continue
        m = NAME.match(b["name"])
        if m:
            runs[(m.group(1), int(m.group(2)), int(m.group(3)))].append(b)
    return runs


def median_of(rows, key):
    values = [r[key] for r in rows if key in r]
    return statistics.median(values) if values else float("nan")


def main(path, polish="FamilyPolish", ipopt="IpoptEuler"):
    runs = load(path)
    gammas = sorted({g for (_, g, _) in runs})
    print(f"| gamma | Ipopt / polish CPU: median, min (per seed) | polish CPU s (median) "
          f"| Ipopt CPU s (median) | Newton steps per seed | fallbacks | terminal violation (max) "
          f"| J rel. to Ipopt (per seed) | Ipopt converged |")
    print("|---|---|---|---|---|---|---|---|---|")
    for g in gammas:
        seeds = sorted(s for (m, gg, s) in runs if m == polish and gg == g)
        ratios, p_cpu, i_cpu, steps, fallbacks, rel, term, ipopt_ok = [], [], [], [], 0, [], [], 0
        for s in seeds:
            p, i = runs[(polish, g, s)], runs.get((ipopt, g, s))
            if not i:
                continue
            pc, ic = median_of(p, "cpu_s"), median_of(i, "cpu_s")
            ratios.append(ic / pc)
            p_cpu.append(pc)
            i_cpu.append(ic)
            # After a fallback newton_iterations counts the request grid's solve only: add the
            # failed sequence's steps.
            fallback = int(p[0].get("coarse_fallback", 0))
            failed = p[0].get("coarse_newton_iterations", 0) + p[0].get("fine_newton_iterations", 0)
            steps.append(int(p[0].get("newton_iterations", -1) + (failed if fallback else 0)))
            fallbacks += fallback
            rel.append((p[0]["J"] - i[0]["J"]) / abs(i[0]["J"]))
            term.append(max(r["terminal"] for r in p))
            ipopt_ok += int(all(r["converged"] == 1 for r in i))
        if not ratios:
            continue
        per_seed = ", ".join(f"{r:.1f}" for r in ratios)
        print(f"| 1e-{g} | {statistics.median(ratios):.1f}x, {min(ratios):.1f}x ({per_seed}) "
              f"| {statistics.median(p_cpu):.4f} | {statistics.median(i_cpu):.3f} "
              f"| {', '.join(map(str, steps))} | {fallbacks} | {max(term):.1e} "
              f"| {', '.join(f'{x:.1e}' for x in rel)} | {ipopt_ok}/{len(rel)} |")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: hardform_ratios.py BENCHMARK.json [POLISH_NAME [IPOPT_NAME]]")
    main(*sys.argv[1:])
