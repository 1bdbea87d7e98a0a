#!/usr/bin/env python3
"""Writes the library suites: every registered problem but the paper's (they have their own
suites), every method family that may take it.

  python3 bench/suites/make_library.py build/bin/ocpbench > bench/suites/library.json
  python3 bench/suites/make_library.py --peers build/bin/ocpbench > bench/suites/library-peers.json

library.json (the main job's): per problem, one group in the hard terminal form:
  - Ipopt on euler, trapezoid, hermite-simpson and lgr (degree 3) at N = min(the problem's
    default N (`ocpbench describe problem P`), 100), the families a user compares first;
  - riccati-ip (the stage-structured interior point) on the Euler and trapezoid NLPs at the
    same N (not_applicable on the trapezoid where a problem has boundary constraints);
  - NLopt SLSQP on Hermite-Simpson at N = 20 where the problem has at most 6 states (SLSQP's
    dense quasi-Newton matrix grows with the square of the NLP's size);
  - hamiltonian-polish (on forward Euler, and on classical RK4: `scheme=rk4`) and
    indirect-newton at the same N: they say not_applicable where the problem has no closed-form Hamiltonian
    minimizer or uses a feature they do not take;
  - every discrete reference a peer published (trapezoid at its N, ...) in a scheme OCPBench
    has, as its own case, so
    the summary's "NLP vs peer" column checks OCPBench's transcription against it.
library-peers.json (a sweep): Ipopt on every peer's NLP at every published N, at tol 1e-10
(PEERS_NLP_TOL) with the options each reference names, and on Hermite-Simpson and
LGR at the problem's default N.
Methods that do not take a problem are recorded as not_applicable (with the reason), which
costs nothing, so the generator does not need to know the rules. Every case has a time limit
(MAIN_JOB_LIMIT_S, PEERS_LIMIT_S): a case that reaches it stops with its solver's time-limit status.
"""
import json
import re
import subprocess
import sys

SCHEMES = ["euler", "trapezoid", "hermite-simpson", "lgr"]


def describe(ocpbench, name):
    text = subprocess.run([ocpbench, "describe", "problem", name], check=True,
                          capture_output=True, text=True).stdout
    tags = re.search(r"^tags: (.*)$", text, re.M).group(1).split(", ")
    n = int(re.search(r"^default grid: N = (\d+)", text, re.M).group(1))
    nx = int(re.search(r"^sizes: nx = (\d+)", text, re.M).group(1))
    peers = [(m.group(2), int(m.group(3))) for m in
             re.finditer(r"^reference (\S+) = \S+ \((\S+) NLP at N = (\d+);", text, re.M)]
    # The Ipopt options a discrete reference's NLP needs: the indented line after it.
    peer_options = {}
    for m in re.finditer(r"^reference \S+ = \S+ \((\S+) NLP at N = (\d+);.*\n"
                         r"  ipopt options its NLP needs: (.*)$", text, re.M):
        peer_options[(m.group(1), int(m.group(2)))] = dict(
            item.split("=", 1) for item in m.group(3).split())
    return n, nx, peers, tags, peer_options


MAIN_JOB_N = 100       # the families' grid in the main job's suite (at most)
MAIN_JOB_PEER_N = 200  # the largest peer NLP the main job's suite checks
# The sweep solves each peer's NLP to Ipopt's tol 1e-10: at the default 1e-8 Ipopt stops up to
# 1.5e-6 from the NLP's optimum in J (jackson, insurance; results/notes/2026-12-07-library-
# rerun.md), too far for the 1e-8 match the check asks. The main job's suite keeps Ipopt's
# defaults, as for its other cases.
PEERS_NLP_TOL = 1e-10

# Every case has a time limit, so that one case cannot hold the suite: Ipopt on space-shuttle's
# LGR NLP (N = 100) ran 24 minutes towards its 3000 iterations before it was killed
# (docs/problems.md). The longest cases that end by themselves, glider's LGR NLP (3000
# iterations, 230 s) and space-shuttle's Euler NLP (1389 iterations: 88 s on 2026-12-06, 161 s
# on 2026-12-07, the same machine under another load), stay well inside it. A case that reaches
# it stops with its solver's time-limit status. Each solver names its limit its own way
# (NLopt's is wall time, so it depends on the machine's load).
MAIN_JOB_LIMIT_S = 600
PEERS_LIMIT_S = 600
TIME_LIMIT_OPTION = {
    "ipopt": "max_cpu_time",
    "riccati-ip": "max_cpu_time",
    "nlopt": "maxtime",
    "hamiltonian-polish": "max_cpu_seconds",
    "indirect-newton": "max_cpu_seconds",
}


def with_time_limit(method, seconds):
    method = dict(method)
    method["options"] = dict(method.get("options", {}))
    method["options"][TIME_LIMIT_OPTION[method["solver"]]] = seconds
    return method


def family_methods(n, nx):
    methods = [{"solver": "ipopt", "transcription": s, "N": n} for s in SCHEMES]
    methods.append({"solver": "riccati-ip", "transcription": "euler", "N": n})
    methods.append({"solver": "riccati-ip", "transcription": "trapezoid", "N": n})
    if nx <= 6:
        methods.append({"solver": "nlopt", "transcription": "hermite-simpson",
                        "algorithm": "LD_SLSQP", "N": 20})
    methods.append({"solver": "hamiltonian-polish", "N": n})
    # The family on classical RK4 with stage controls (order 4: on a smooth problem its J at
    # N = 100 is within 1e-8 of the optimum where Euler's is 1e-3 off), the descent then
    # projected Newton on the stage controls (results/notes/2026-12-07-family-rk4-polish.md).
    methods.append({"solver": "hamiltonian-polish", "N": n, "options": {"scheme": "rk4"}})
    methods.append({"solver": "indirect-newton", "N": n})
    return methods


def main():
    args = sys.argv[1:]
    peers_suite = bool(args) and args[0] == "--peers"
    if peers_suite:
        args = args[1:]
    ocpbench = args[0] if args else "build/bin/ocpbench"
    names = subprocess.run([ocpbench, "list", "problems"], check=True, capture_output=True,
                           text=True).stdout.split()
    schemes = subprocess.run([ocpbench, "list", "transcriptions"], check=True,
                             capture_output=True, text=True).stdout.split()
    groups = []
    for name in names:
        n, nx, peers, tags, peer_options = describe(ocpbench, name)
        if "paper" in tags:
            continue  # the paper's problems have their own suites (bench/suites/paper.json)
        # A peer's scheme OCPBench does not have (COPS' Gauss-Legendre) is left out.
        peers = [(scheme, n_peer) for scheme, n_peer in peers if scheme in schemes]
        if peers_suite:
            if not peers:
                continue
            methods = [{"solver": "ipopt", "transcription": s, "N": n}
                       for s in ("hermite-simpson", "lgr")]
        else:
            methods = family_methods(min(n, MAIN_JOB_N), nx)
            peers = [(scheme, n_peer) for scheme, n_peer in peers if n_peer <= MAIN_JOB_PEER_N]
        for scheme, n_peer in peers:
            case = {"solver": "ipopt", "transcription": scheme, "N": n_peer}
            if peers_suite:
                case["options"] = {"tol": PEERS_NLP_TOL,
                                   **peer_options.get((scheme, n_peer), {})}
            if case not in methods:
                methods.append(case)
        limit = PEERS_LIMIT_S if peers_suite else MAIN_JOB_LIMIT_S
        groups.append({"problem": name, "terminal": "hard", "keep_trajectory": False,
                       "methods": [with_time_limit(m, limit) for m in methods]})
    if peers_suite:
        suite = {
            "name": "library-peers",
            "description": (
                "The library's problems with a peer's published discrete optima: Ipopt on every "
                "such NLP (its scheme and N, up to CTBenchmarks' N = 2000) at tol 1e-10 (with the "
                "options a reference names, `ocpbench describe problem`) for the column 'NLP vs "
                "peer', and Ipopt on Hermite-Simpson and LGR at the problem's default N. A sweep: "
                "run sharded (docs/problems.md). Every case stops at 600 s (max_time). Written by "
                "bench/suites/make_library.py --peers."),
            "groups": groups,
        }
    else:
        suite = {
            "name": "library",
            "description": (
                "The reference library (docs/problems.md): every registered problem but the "
                "paper's, in the hard terminal form, with Ipopt on the four collocation schemes "
                "and riccati-ip (euler, trapezoid) at N = min(the problem's default N, 100), NLopt SLSQP "
                "(Hermite-Simpson, N = 20) on problems of at most 6 states, hamiltonian-polish "
                "(on Euler and on classical RK4: scheme=rk4) and indirect-newton (not_applicable where they do not take the problem), and "
                "Ipopt on each peer's published NLP up to N = 200 for the 'NLP vs peer' column "
                "(the larger ones: library-peers.json). Every case stops at 600 s (its solver's time limit). Written by "
                "bench/suites/make_library.py."),
            "groups": groups,
        }
    json.dump(suite, sys.stdout, indent=1)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
