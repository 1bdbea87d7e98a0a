#!/usr/bin/python3
"""Markdown tables from a Google Benchmark JSON file of `ocpbench_kernels`.

    /usr/bin/python3 results/plotting/benchmark_tables.py results/benchmarks.json \
        --out results/benchmarks.md

One table per benchmark family (the name before the first '/'): arguments, wall and CPU time,
and every user counter the kernel reported. For a family that runs over a size argument (N, m,
...) the script also fits the growth exponent b of  CPU time ~ a size^b  by least squares on the
logarithms, the number the issues ask for ("it must be linear": b close to 1). Aggregates
(mean/median/stddev of --benchmark_repetitions) are reported as the median when present.
With results/callgrind.json (results/plotting/callgrind_counts.py) beside the JSON, the file
starts with the instruction counts of issue 20's figures next to times.
The output is generated: re-run this script, never edit it by hand.
"""
import argparse
import json
import math
import os
import sys
import tempfile

# Arguments that are problem sizes (named with ->ArgName in the kernels); an unnamed argument is
# an index (a problem, a variant) and gets no growth fit.
SIZE_ARGUMENTS = ("N", "m", "n", "nodes", "points")
UNIT_SECONDS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
STANDARD_KEYS = {
    "name", "family_index", "per_family_instance_index", "run_name", "run_type", "repetitions",
    "repetition_index", "threads", "iterations", "real_time", "cpu_time", "time_unit",
    "aggregate_name", "aggregate_unit", "label", "error_occurred", "error_message", "big_o",
    "rms", "complexity_n",
}


def fmt(x):
    if isinstance(x, str):
        return x
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    if x == 0:
        return "0"
    a = abs(x)
    if a >= 1e5 or a < 1e-3:
        return "%.3g" % x
    return "%.4g" % x


# Name parts Google Benchmark adds for its own settings, not the kernel's arguments.
RUN_SETTINGS = ("iterations", "repeats", "min_time", "threads")
RUN_FLAGS = ("process_time", "real_time", "manual_time")


def parse_args_of(run_name):
    """('BM_X', [('variant', 'di_euler'), ('N', '400')]) from 'BM_X/di_euler/N:400/real_time'."""
    parts = run_name.split("/")
    family, args, variant = parts[0], [], []
    for p in parts[1:]:
        if ":" in p:
            k, v = p.split(":", 1)
            if k not in RUN_SETTINGS:
                args.append((k, v))
        elif p.replace(".", "", 1).isdigit():
            args.append(("arg%d" % len(args), p))
        elif p not in RUN_FLAGS:
            variant.append(p)
    if variant:
        args.insert(0, ("variant", "/".join(variant)))
    return family, args


def select_runs(benchmarks):
    """One row per benchmark instance: the median aggregate when repetitions ran, else the run."""
    rows, medians = {}, {}
    for b in benchmarks:
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                medians[b["run_name"]] = b
            continue
        if b.get("big_o") is not None or b["name"].endswith(("_BigO", "_RMS")):
            continue
        rows.setdefault(b.get("run_name", b["name"]), []).append(b)
    out = []
    for name in list(rows) + [n for n in medians if n not in rows]:
        runs = rows.get(name, [])
        chosen = dict(medians[name] if name in medians else runs[0])
        chosen["run_name"] = name
        out.append(chosen)
    return out


def growth_exponent(points):
    """Least-squares slope of log(cpu) against log(size); None with fewer than 2 sizes."""
    pts = [(math.log(n), math.log(t)) for n, t in points if n > 0 and t > 0]
    if len(pts) < 2:
        return None
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    if sxx == 0:
        return None
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx


def family_table(family, runs):
    lines = ["## %s" % family, ""]
    arg_names = []
    counters = []
    for r in runs:
        for k, _ in parse_args_of(r["run_name"])[1]:
            if k not in arg_names:
                arg_names.append(k)
        for k in r:
            if k not in STANDARD_KEYS and k not in counters:
                counters.append(k)
    header = arg_names + ["wall", "CPU", "timed runs"] + counters + ["label"]
    lines.append("| " + " | ".join(header) + " |")
    lines.append("|" + "---|" * len(header))
    sized = {}
    for r in runs:
        args = dict(parse_args_of(r["run_name"])[1])
        unit = r.get("time_unit", "ns")
        if r.get("error_occurred"):
            cells = [args.get(a, "") for a in arg_names] + ["error: " + r.get("error_message", "")]
            cells += [""] * (len(header) - len(cells))
            lines.append("| " + " | ".join(cells) + " |")
            continue
        cells = [args.get(a, "") for a in arg_names]
        cells += ["%s %s" % (fmt(r["real_time"]), unit), "%s %s" % (fmt(r["cpu_time"]), unit)]
        cells.append(fmt(r.get("iterations")))
        cells += [fmt(r.get(c)) for c in counters]
        cells.append(r.get("label", ""))
        lines.append("| " + " | ".join(cells) + " |")
        # Growth over the one size argument, other arguments held fixed.
        for a in arg_names:
            v = args.get(a, "")
            if a in SIZE_ARGUMENTS and v.replace(".", "", 1).isdigit():
                rest = tuple((k, w) for k, w in sorted(args.items()) if k != a)
                sized.setdefault((a, rest), []).append(
                    (float(v), r["cpu_time"] * UNIT_SECONDS.get(unit, 1e-9)))
                break
    lines.append("")
    for (a, rest), pts in sized.items():
        b = growth_exponent(pts)
        if b is None:
            continue
        sizes = sorted(int(p[0]) for p in pts)
        where = ", ".join("%s=%s" % kv for kv in rest)
        lines.append("CPU time ~ %s^%.2f over %s = %s%s (least squares on the logarithms)." % (
            a, b, a, ", ".join(str(s) for s in sizes), " with " + where if where else ""))
    lines.append("")
    return lines


def mega(x):
    return "-" if x is None else "%.1f M" % (x / 1e6)


def change(before, after):
    if not before or after is None:
        return "-"
    return "%+.1f %%" % (100.0 * (after - before) / before)


def kernel_time(benchmarks, run_name):
    """(cpu_s, wall_s) of a run in a Google Benchmark JSON (median when aggregated)."""
    for r in benchmarks:
        if r.get("run_name") != run_name:
            continue
        if r.get("run_type") == "aggregate" and r.get("aggregate_name") != "median":
            continue
        unit = UNIT_SECONDS[r["time_unit"]]
        return r["cpu_time"] * unit, r["real_time"] * unit
    return None


def ms(t):
    return "-" if t is None else "%.1f / %.1f ms" % (1e3 * t[0], 1e3 * t[1])


def callgrind_section(after, before, old_benchmarks):
    """Issue 20's figures: instruction counts (results/callgrind.json, written by
    results/plotting/callgrind_counts.py) before and after, next to times: the committed
    kernel run (`old_benchmarks`, before) and the kernels run with the counts (after)."""
    lines = ["## Instruction counts (callgrind) next to times", "",
             "Generated from `callgrind.json` (after, commit %s) and `callgrind-before.json` "
             "(before, commit %s) by `results/plotting/callgrind_counts.py`: instruction counts do "
             "not depend on the machine's load, times do. Times are CPU / wall; \"before\" times "
             "are this file's kernel run below, \"after\" times the kernels run with the counts "
             "(load average %s before, %s after). Times of the two runs are not comparable "
             "with each other (another day and load; equal instruction counts took up to 2x "
             "different CPU times): compare instructions across columns, times within one." % (
                 after.get("ipopt_commit", "?"), before.get("ipopt_commit", "?"),
                 ", ".join("%.1f" % x for x in after.get("times", {}).get("load_before", [])),
                 ", ".join("%.1f" % x for x in after.get("times", {}).get("load_after", []))),
             ""]
    times = after.get("times", {}).get("kernels", {})
    scheme_index = {"euler": 0, "trapezoid": 1, "hermite-simpson": 2, "lgr": 3}
    lines += ["### Ipopt on comm-path2d, N = 400: OCPBench's share of the instructions", "",
              "| scheme | iterations | instructions before | after | change | OCPBench's "
              "callbacks before | after | share before | share after | MUMPS before | after | "
              "time before | time after |", "|---" * 13 + "|"]
    old = {(r["transcription"], r["terminal"]): r for r in before.get("ipopt", [])}
    for r in after.get("ipopt", []):
        b = old.get((r["transcription"], r["terminal"]), {})
        name = "BM_IpoptPaperProblem/scheme:%d/hard:%d/iterations:1" % (
            scheme_index[r["transcription"]], r["terminal"] == "hard")
        t_after = times.get(name + "_median", times.get(name))
        lines.append("| %s, %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["transcription"], r["terminal"], r["iterations"], mega(b.get("instructions")),
            mega(r["instructions"]), change(b.get("instructions"), r["instructions"]),
            mega(b.get("ocpbench_instructions")), mega(r["ocpbench_instructions"]),
            "-" if not b else "%.1f %%" % (100 * b["ocpbench_share"]),
            "%.1f %%" % (100 * r["ocpbench_share"]), mega(b.get("mumps")), mega(r["mumps"]),
            ms(kernel_time(old_benchmarks, name)),
            "-" if not t_after else ms((t_after["cpu_seconds"], t_after["wall_seconds"]))))
    lines.append("")
    ca, cb = after.get("channel", {}), before.get("channel", {})
    if ca:
        lines += ["### Channel prediction (500 x 500 grid, m = 500): 1 thread against 2", "",
                  "| | before | after |", "|---|---|---|",
                  "| instructions, 1 thread | %s | %s |" % (
                      mega(cb.get("predict_instructions")), mega(ca["predict_instructions"])),
                  "| serial (outside the parallel jobs) | %s (%.1f %%) | %s (%.2f %%) |" % (
                      mega(cb.get("serial_instructions")), 100 * cb.get("serial_fraction", 0),
                      mega(ca["serial_instructions"]), 100 * ca["serial_fraction"]),
                  "| 2-thread critical path in instructions | %s | %s |" % (
                      mega(cb.get("critical_path_2_threads")),
                      mega(ca["critical_path_2_threads"])),
                  "| speedup bound on 2 idle cores (instructions / critical path) | %.2f | %.2f |" % (
                      cb.get("instruction_speedup_2_threads", float("nan")),
                      ca["instruction_speedup_2_threads"]),
                  "| FFTW planning / execution | %s / %s | %s / %s |" % (
                      mega(cb.get("fft_plan")), mega(cb.get("fft_execute")),
                      mega(ca["fft_plan"]), mega(ca["fft_execute"])),
                  "| building the paper's channel (one comm-path2d make) | %s | %s |" % (
                      mega(cb.get("paper_channel_build_instructions")),
                      mega(ca["paper_channel_build_instructions"]))]
        for threads in (1, 2):
            name = "BM_ChannelPredictGrid/threads:%d/process_time/real_time" % threads
            t_after = times.get(name + "_median", times.get(name))
            lines.append("| time, %d thread%s (process CPU / wall) | %s | %s |" % (
                threads, "s" if threads > 1 else "", ms(kernel_time(old_benchmarks, name)),
                "-" if not t_after else ms((t_after["cpu_seconds"], t_after["wall_seconds"]))))
        lines.append("")
    sa, sb = after.get("suite", {}), before.get("suite", {})
    if sa:
        lines += ["### The paper suite (`%s`)" % sa["command"], "",
                  "| | before | after |", "|---|---|---|",
                  "| CPU s (all threads) | %s | %.1f |" % (
                      "%.1f" % sb["cpu_seconds"] if sb else "-", sa["cpu_seconds"]),
                  "| wall s | %s | %.1f |" % ("%.1f" % sb["wall_seconds"] if sb else "-",
                                             sa["wall_seconds"]),
                  "| load average before / after | %s | %.1f / %.1f |" % (
                      "%.1f / %.1f" % (sb["load_before"][0], sb["load_after"][0]) if sb else "-",
                      sa["load_before"][0], sa["load_after"][0]), ""]
    oa, ob = after.get("online", {}), before.get("online", {})
    if oa:
        lines += ["### Online re-planning (seed 1, Hamiltonian, %d channel updates)" %
                  oa.get("updates", 4), "",
                  "| | before | after |", "|---|---|---|",
                  "| OnlineChannel::Update, instructions | %s | %s |" % (
                      mega(ob.get("update_instructions")), mega(oa["update_instructions"])),
                  "| FFTW planning | %s | %s |" % (mega(ob.get("fft_plan")),
                                                   mega(oa["fft_plan"])),
                  "| FFTW execution | %s | %s |" % (mega(ob.get("fft_execute")),
                                                    mega(oa["fft_execute"]))]
        for name in ("BM_OnlineCycle/hamiltonian_50it/process_time/real_time",
                     "BM_OnlineCycle/ipopt_euler/process_time/real_time"):
            t_after = times.get(name + "_median", times.get(name))
            lines.append("| time, `%s` | %s | %s |" % (
                name.split("/")[1], ms(kernel_time(old_benchmarks, name)),
                "-" if not t_after else ms((t_after["cpu_seconds"], t_after["wall_seconds"]))))
        lines.append("")
    return lines


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("json_file")
    p.add_argument("--out", required=True)
    p.add_argument("--callgrind", help="callgrind_counts.py output (default: callgrind.json "
                   "beside json_file, if present); callgrind-before.json beside it is the "
                   "baseline")
    a = p.parse_args()
    with open(a.json_file) as f:
        data = json.load(f)
    ctx = data.get("context", {})
    runs = select_runs(data.get("benchmarks", []))
    families = {}
    for r in runs:
        families.setdefault(parse_args_of(r["run_name"])[0], []).append(r)
    lines = [
        "# Benchmarks of `ocpbench_kernels`",
        "",
        "Generated by `results/plotting/benchmark_tables.py` from `%s`; do not edit." %
        os.path.basename(a.json_file),
        "Machine: %s CPUs at %s MHz, load average %s when the run started; run at %s, "
        "library build %s." % (ctx.get("num_cpus", "?"), ctx.get("mhz_per_cpu", "?"),
                               ", ".join(fmt(x) for x in ctx.get("load_avg", [])) or "?",
                               ctx.get("date", "?"), ctx.get("library_build_type", "?")),
        "Each kernel's source (`bench/kernels/`) says what it times and what its counters mean.",
        "",
    ]
    counts = a.callgrind or os.path.join(os.path.dirname(os.path.abspath(a.json_file)),
                                         "callgrind.json")
    if os.path.exists(counts):
        with open(counts) as f:
            after = json.load(f)
        base = os.path.join(os.path.dirname(os.path.abspath(counts)), "callgrind-before.json")
        before = {}
        if os.path.exists(base):
            with open(base) as f:
                before = json.load(f)
        lines += callgrind_section(after, before, data.get("benchmarks", []))
    for family in sorted(families):
        lines += family_table(family, families[family])
    text = "\n".join(lines).rstrip() + "\n"
    out_dir = os.path.dirname(os.path.abspath(a.out))
    fd, tmp = tempfile.mkstemp(dir=out_dir, prefix=".benchmarks.", suffix=".md")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    os.chmod(tmp, 0o644)
    os.replace(tmp, a.out)
    print("wrote %s (%d benchmarks in %d families)" % (a.out, len(runs), len(families)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
