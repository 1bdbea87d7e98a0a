#!/usr/bin/python3
"""Instruction counts (valgrind --tool=callgrind) of the channel and Ipopt figures of issue 20.

    /usr/bin/python3 results/plotting/callgrind_counts.py [--bin build/bin] [--out results/callgrind.json]
        [--only ipopt,channel,online]

Callgrind counts instructions, which a loaded machine does not change (wall times it does), so a
change can be judged on the shared 2-core machine. Each measurement runs one `ocpbench` command
under callgrind, collecting only inside one function (--toggle-collect), and reads inclusive
counts with callgrind_annotate:

- ipopt: `ocpbench solve --problem comm-path2d --solver ipopt --transcription T --terminal M`,
  collected inside IpoptApplication::OptimizeTNLP; OCPBench's share is the inclusive count of
  the TNLP callbacks (NlpTnlp::*: eval_f, eval_grad_f, eval_g, eval_jac_g, eval_h, ...) over
  the whole solve; the rest is Ipopt, MUMPS and BLAS.
- channel: `ocpbench channel predict --samples 500 --seed 1 --threads 1 --no-files`, collected
  inside PredictOnGrid: the whole prediction, its parallel rounds (GridWorker's SetupJob,
  Convolve, Tile, Finish), the serial rest, and from them the 2-thread critical path in
  instructions (each round halved, the FFT job not split), which bounds the 2-thread speedup
  on an idle machine. Also the channel build of one comm-path2d solve (MakePaperChannel).
- online: `ocpbench online --problem comm-path2d --solver hamiltonian --seed 1` (4 channel
  updates), collected inside OnlineChannel::Update: FFTW planning (fftw_plan_*,
  fftw_destroy_plan) against FFTW execution (fftw_execute*).

- suite: `ocpbench run bench/suites/paper.json` natively, CPU and wall time (the channel
  cache: one build per seed instead of one per case).
- times: the Google Benchmark kernels of the same figures (BM_IpoptPaperProblem,
  BM_ChannelPredictGrid with 1 and 2 threads, BM_OnlineCycle), natively, median of 3, with the
  load average around them.

Writes the counts as JSON (results/callgrind.json); results/plotting/benchmark_tables.py puts
them, with the times, in results/benchmarks.md. Needs valgrind; takes 10-20 minutes.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

# The adapter's TNLP methods themselves (not the Guard<...> lambdas they call, which would count
# the same instructions twice).
TNLP = r"^\?\?\?:ocpb::\(anonymous namespace\)::NlpTnlp::"
# FFTW's API entry points (its internal planner functions nest and would count twice).
FFT_PLAN = r"^\?\?\?:fftw_(plan_dft_r2c_2d|plan_dft_c2r_2d|plan_dft_2d|destroy_plan)$"
FFT_EXECUTE = r"^\?\?\?:fftw_execute(_dft_r2c|_dft_c2r|_dft)?$"
LINE = re.compile(r"^\s*([\d,]+)\s+\(\s*[\d.]+%\)\s+(.*)$")


def inclusive_counts(out_file):
    """{symbol: inclusive instructions} from callgrind_annotate --inclusive=yes."""
    text = subprocess.run(
        ["callgrind_annotate", "--inclusive=yes", "--threshold=100", out_file],
        check=True, capture_output=True, text=True).stdout
    counts = {}
    for line in text.splitlines():
        m = LINE.match(line)
        if m:
            name = m.group(2).strip()
            name = re.sub(r"\s*\[[^\]]*\]$", "", name)  # the object file
            counts[name] = counts.get(name, 0) + int(m.group(1).replace(",", ""))
    return counts


def total(counts):
    return counts.get("PROGRAM TOTALS", 0)


def matching(counts, pattern, exclude=None):
    """Sum of the inclusive counts of symbols matching `pattern` (regex), none nested."""
    rx, ex = re.compile(pattern), re.compile(exclude) if exclude else None
    return sum(v for k, v in counts.items() if rx.search(k) and not (ex and ex.search(k)))


def callgrind(command, collect, tmp, threads=False):
    """Counts of `command`, collected inside `collect` (and, with threads, inside every thread
    the process starts: the grid prediction's workers)."""
    out = os.path.join(tmp, "callgrind.out")
    toggles = ["--toggle-collect=" + collect]
    if threads:
        toggles.append("--toggle-collect=std::thread::_State_impl*")
    subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out] + toggles +
                   command,
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return inclusive_counts(out)


IPOPT_CASES = "euler:penalty,trapezoid:penalty,hermite-simpson:penalty,hermite-simpson:hard," \
              "lgr:penalty"


def measure_ipopt(bin_dir, tmp, cases=IPOPT_CASES):
    rows = []
    for scheme, terminal in (c.split(":") for c in cases.split(",")):
        record = os.path.join(tmp, "solve.json")
        command = [os.path.join(bin_dir, "ocpbench"), "solve", "--problem", "comm-path2d",
                   "--solver", "ipopt", "--transcription", scheme, "--terminal", terminal,
                   "--no-trajectory", "--json", record]
        c = callgrind(command, "Ipopt::IpoptApplication::OptimizeTNLP*", tmp)
        with open(record) as f:
            r = json.load(f)
        # The callbacks are methods of one class; Guard<...> lambdas are inside them.
        callbacks = matching(c, TNLP + r"(eval_f|eval_grad_f|eval_g|eval_jac_g|eval_h|"
                                r"get_nlp_info|get_bounds_info|get_starting_point|"
                                r"finalize_solution|intermediate_callback)\(")
        rows.append({
            "transcription": scheme, "terminal": terminal,
            "iterations": r["iterations"], "objective": r["objective"],
            "instructions": total(c), "ocpbench_instructions": callbacks,
            "ocpbench_share": callbacks / total(c),
            "eval_h": matching(c, TNLP + r"eval_h\("),
            "mumps": matching(c, r"^\?\?\?:dmumps_c$"),
        })
        print("ipopt", rows[-1], file=sys.stderr)
    return rows


def measure_channel(bin_dir, tmp):
    command = [os.path.join(bin_dir, "ocpbench"), "channel", "predict", "--samples", "500",
               "--seed", "1", "--threads", "1", "--no-files"]
    c = callgrind(command, "ocpb::PredictOnGrid*", tmp)
    whole = total(c)
    worker = r"^\?\?\?:ocpb::\(anonymous namespace\)::GridWorker::"
    rounds = {name: matching(c, worker + name + r"\(")
              for name in ("SetupJob", "Convolve", "Tile", "Finish")}
    # What runs in parallel: the job rounds (RunJobs), or, before them, only the tiles.
    parallel = matching(c, r"^\?\?\?:ocpb::\(anonymous namespace\)::RunJobs\(int") or \
        rounds["Tile"]
    serial = whole - parallel
    # 2 threads, dynamic scheduling: each round about half its work, round 2 no less than its
    # largest job (Convolve, the FFT); before the rounds, the tiles alone were parallel.
    if rounds["Convolve"]:
        path = serial + rounds["SetupJob"] / 2 + rounds["Finish"] / 2 + \
            max(rounds["Convolve"], (rounds["Convolve"] + rounds["Tile"]) / 2)
    else:
        path = serial + rounds["Tile"] / 2
    out = {"predict_instructions": whole, "rounds": rounds, "serial_instructions": serial,
           "serial_fraction": serial / whole, "critical_path_2_threads": path,
           "instruction_speedup_2_threads": whole / path,
           "fft_plan": matching(c, FFT_PLAN), "fft_execute": matching(c, FFT_EXECUTE)}
    out["paper_channel_build_instructions"] = measure_channel_build(bin_dir, tmp)
    print("channel", out, file=sys.stderr)
    return out


def measure_channel_build(bin_dir, tmp):
    """Instructions of MakePaperChannel in one comm-path2d make (all threads)."""
    command = [os.path.join(bin_dir, "ocpbench"), "solve", "--problem", "comm-path2d",
               "--solver", "hamiltonian", "--option", "max_iterations=1", "--no-trajectory"]
    return total(callgrind(command, "ocpb::MakePaperChannel*", tmp, threads=True))


def measure_build(bin_dir, tmp):
    return {"paper_channel_build_instructions": measure_channel_build(bin_dir, tmp)}


def measure_online(bin_dir, tmp):
    command = [os.path.join(bin_dir, "ocpbench"), "online", "--problem", "comm-path2d",
               "--solver", "hamiltonian", "--seed", "1", "--no-trajectory",
               "--json", os.path.join(tmp, "online.json")]
    c = callgrind(command, "ocpb::OnlineChannel::Update*", tmp)
    out = {"update_instructions": total(c),
           "fft_plan": matching(c, FFT_PLAN), "fft_execute": matching(c, FFT_EXECUTE),
           "updates": 4}
    print("online", out, file=sys.stderr)
    return out


def measure_times(bin_dir, tmp):
    """Times of the matching Google Benchmark kernels, run natively in the same session (CPU
    and wall; the load average before and after says how much the wall times mean)."""
    out = os.path.join(tmp, "times.json")
    load0 = os.getloadavg()
    subprocess.run([os.path.join(bin_dir, "ocpbench_kernels"),
                    "--benchmark_filter=BM_IpoptPaperProblem|BM_ChannelPredictGrid|BM_OnlineCycle",
                    "--benchmark_repetitions=3", "--benchmark_report_aggregates_only=true",
                    "--benchmark_out=" + out, "--benchmark_out_format=json"],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(out) as f:
        runs = json.load(f)["benchmarks"]
    rows = {}
    for r in runs:
        if r.get("run_type") == "aggregate" and r.get("aggregate_name") != "median":
            continue
        unit = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[r["time_unit"]]
        rows[r["run_name"]] = {"cpu_seconds": r["cpu_time"] * unit,
                               "wall_seconds": r["real_time"] * unit,
                               "label": r.get("label", "")}
    return {"kernels": rows, "load_before": load0, "load_after": os.getloadavg()}


def measure_suite(bin_dir, tmp):
    """The paper suite natively: CPU (user + system, all threads) and wall time, with the load
    average around it; the channel cache shows here (5 channels built instead of 96)."""
    import resource
    import time
    load0 = os.getloadavg()
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    subprocess.run([os.path.join(bin_dir, "ocpbench"), "run", "bench/suites/paper.json",
                    "--out", os.path.join(tmp, "paper")],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = {"command": "ocpbench run bench/suites/paper.json --out DIR",
           "cpu_seconds": (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime),
           "wall_seconds": wall, "load_before": load0, "load_after": os.getloadavg()}
    print("suite", out, file=sys.stderr)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", default="build/bin")
    ap.add_argument("--out", default="results/callgrind.json")
    ap.add_argument("--only", default="ipopt,channel,online,times,suite")
    ap.add_argument("--ipopt-cases", default=IPOPT_CASES,
                    help="scheme:terminal,... for the ipopt part (default: %(default)s)")
    a = ap.parse_args()
    result = {}
    if os.path.exists(a.out):
        with open(a.out) as f:
            result = json.load(f)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    with tempfile.TemporaryDirectory() as tmp:
        for part in a.only.split(","):
            fn = {"ipopt": measure_ipopt, "channel": measure_channel,
                  "online": measure_online, "times": measure_times, "build": measure_build,
                  "suite": measure_suite}[part]
            if part == "build":  # the channel build alone (also part of "channel")
                result.setdefault("channel", {}).update(fn(a.bin, tmp))
                continue
            result[part] = fn(a.bin, tmp, a.ipopt_cases) if part == "ipopt" else fn(a.bin, tmp)
            result[part + "_commit"] = commit
    tmp_out = a.out + ".tmp"
    with open(tmp_out, "w") as f:
        json.dump(result, f, indent=1)
    os.replace(tmp_out, a.out)


if __name__ == "__main__":
    main()
