#!/usr/bin/env python3
"""`ocpbench report`'s command-line rules: bad input is one line naming the path and the rule,
exit 2, with nothing written; the site replaces only an earlier report, never an input; a
refused run leaves the previous site as it was; the compare view comes from BASE NEW or from
`ocpbench compare --json`."""
import argparse
import hashlib
import json
import os
import shutil
import subprocess
import sys


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def run(args, *command):
    return subprocess.run([args.ocpbench, *command], capture_output=True, text=True)


def expect_error(args, needle, *command):
    """Exit 2, one line on stderr that contains `needle`."""
    p = run(args, *command)
    lines = p.stderr.strip().splitlines()
    if p.returncode != 2 or len(lines) != 1 or needle not in lines[0]:
        fail(f"{' '.join(command)}: expected exit 2 and one line with {needle!r}, got "
             f"{p.returncode}: {p.stderr!r}")


def tree_digest(folder):
    h = hashlib.sha256()
    for root, dirs, files in sorted(os.walk(folder)):
        dirs.sort()
        for name in sorted(files):
            path = os.path.join(root, name)
            h.update(os.path.relpath(path, folder).encode())
            with open(path, "rb") as f:
                h.update(f.read())
    return h.hexdigest()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--ocpbench", required=True)
    parser.add_argument("--suite", required=True)
    parser.add_argument("--work", required=True)
    args = parser.parse_args()
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    w = lambda *p: os.path.join(args.work, *p)
    if run(args, "run", args.suite, "--out", w("base")).returncode != 0:
        fail("the suite did not run")
    shutil.copytree(w("base"), w("new"))

    # Bad input: exit 2, one line, nothing written.
    expect_error(args, "no such file or folder", "report", w("missing"), "--out", w("site"))
    os.makedirs(w("empty"))
    expect_error(args, "records.jsonl: no such file", "report", w("empty"), "--out", w("site"))
    os.makedirs(w("norecords"))
    open(w("norecords", "records.jsonl"), "w").close()
    expect_error(args, "no records", "report", w("norecords"), "--out", w("site"))
    if run(args, "run", args.suite, "--out", w("shards"), "--shard", "1/2").returncode != 0:
        fail("the shard did not run")
    expect_error(args, "not merged", "report", w("shards"), "--out", w("site"))
    shutil.copytree(w("base"), w("other"))
    with open(w("other", "suite.json"), "w") as f:
        json.dump({"suite": "another-suite", "records": 7}, f)
    expect_error(args, "mixed suites", "report", w("base"), w("other"), "--out", w("site"))
    expect_error(args, "got 3", "report", w("base"), w("new"), w("other"), "--out", w("site"))
    expect_error(args, "holds the input", "report", w("base"), "--out", w("base"))
    expect_error(args, "holds the input", "report", w("base"), "--out", args.work)
    os.makedirs(w("someone"))
    open(w("someone", "notes.txt"), "w").close()
    expect_error(args, "not a report of ocpbench", "report", w("base"), "--out", w("someone"))
    with open(w("damaged.jsonl"), "w") as f:
        f.write('{"key": "a", "status": 3}\n{"key": "b"}\n')
    expect_error(args, "damaged.jsonl:1", "report", w("damaged.jsonl"), "--out", w("site"))
    expect_error(args, "apply to BASE NEW only", "report", w("base"), "--cpu-ratio", "2",
                 "--out", w("site"))
    expect_error(args, "--out: required", "report", w("base", "records.jsonl"))
    # Loops of symbolic links as any path: refused by the same check as every command's.
    os.symlink("loop-b", w("loop-a"))
    os.symlink("loop-a", w("loop-b"))
    os.symlink("self", w("self"))
    for command in (["report", w("loop-a")], ["report", w("self")],
                    ["report", w("base"), "--out", w("loop-a")],
                    ["report", w("base"), "--out", w("self", "x")],
                    ["report", w("base"), "--compare-json", w("loop-b"), "--out", w("site")]):
        expect_error(args, "a loop of symbolic links", *command)
    if os.path.exists(w("site")):
        fail("a refused run wrote the site")

    # A good run, the default place DIR/report, and a second run over the first.
    p = run(args, "report", w("base"))
    if p.returncode != 0 or not os.path.isfile(w("base", "report", "index.html")):
        fail(f"report base: {p.returncode} {p.stderr}")
    p = run(args, "report", w("base"))
    if p.returncode != 0:
        fail(f"report base, again over its earlier report: {p.returncode} {p.stderr}")
    before = tree_digest(w("base", "report"))
    # A refused run keeps the earlier site whole, and leaves no temporary folder beside it.
    with open(w("new", "suite.json"), "w") as f:
        f.write("{not json")
    expect_error(args, "suite.json", "report", w("new"), "--out", w("base", "report"))
    if tree_digest(w("base", "report")) != before:
        fail("a refused run changed the earlier site")
    leftovers = [n for n in os.listdir(w("base")) if n.startswith(".report.")]
    if leftovers:
        fail(f"temporary folders left: {leftovers}")
    shutil.copy(w("base", "suite.json"), w("new", "suite.json"))

    # The compare view from BASE NEW and from compare's JSON.
    p = run(args, "report", w("base"), w("new"), "--out", w("site"))
    if p.returncode != 0 or not os.path.isfile(w("site", "compare.html")):
        fail(f"report base new: {p.returncode} {p.stderr}")
    p = run(args, "report", w("base"), w("new", "records.jsonl"), "--out", w("site4"))
    if p.returncode != 0 or not os.path.isfile(w("site4", "compare.html")):
        fail(f"report base new/records.jsonl (a records file names no suite): {p.stderr}")
    run(args, "compare", w("base"), w("new"), "--json", w("compare.json"))
    p = run(args, "report", w("new"), "--compare-json", w("compare.json"), "--out", w("site2"))
    if p.returncode != 0 or not os.path.isfile(w("site2", "compare.html")):
        fail(f"report new --compare-json: {p.returncode} {p.stderr}")
    expect_error(args, "mixed suites", "report", w("other"), "--compare-json", w("compare.json"),
                 "--out", w("site3"))
    expect_error(args, "--compare-json", "report", w("base"), w("new"), "--compare-json",
                 w("compare.json"), "--out", w("site3"))
    # An output folder named with a trailing separator, twice (the second replaces the first):
    # the site lands in that folder and no temporary or aside folder is left beside or in it.
    for attempt in range(2):
        p = run(args, "report", w("base"), "--out", w("slash") + os.sep)
        if p.returncode != 0 or not os.path.isfile(w("slash", "index.html")):
            fail(f"report --out slash/ (run {attempt + 1}): {p.returncode} {p.stderr}")
    leftovers = [n for n in os.listdir(args.work) + os.listdir(w("slash"))
                 if ".tmp-" in n or ".old-" in n]
    if leftovers:
        fail(f"--out with a trailing separator left: {leftovers}")
    print("report_cli: every rule held")


if __name__ == "__main__":
    main()
