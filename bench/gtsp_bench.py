#!/usr/bin/env python3
"""Accuracy/time tables for the route solver on GTSPLIB and TSPLIB SOP (../shared/data).

Runs `cutroute gtsp FILE --json --seed S` for each instance and seed, compares with the best-known
values listed in the corpus READMEs, and prints markdown tables (one row per instance).

  bench/gtsp_bench.py --cli build/cutroute --set gtsp-small   # <= 89 clusters, 5 seeds
  bench/gtsp_bench.py --cli build/cutroute --set gtsp-large   # 99..217 clusters, 5 seeds
  bench/gtsp_bench.py --cli build/cutroute --set sop          # SOP <= 100 nodes, 10 s limit
Extra arguments after -- go to cutroute (e.g. -- --threads 2).

Runs are deterministic for a seed (they stop on stagnation, not on time), but the spread between
seeds is wide: on gtsp-large, seeds 1-5 gave a mean gap of 0.131 % and seeds 1-12 0.175 % for the
same code (session 5). The summary line gives the standard error of the mean gap; compare two
versions on 12 or more seeds, and confirm on a second set (--first-seed 13) before trusting a
difference of less than two standard errors.
"""
import argparse
import json
import os
import re
import resource
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.join(HERE, "..", "..", "shared", "data")


def table(readme, cols):
    rows = {}
    for line in open(readme, encoding="utf-8"):
        parts = [p.strip() for p in line.split("|")]
        if len(parts) < 6 or not parts[1] or parts[1] in ("name", "file") or parts[1].startswith("---"):
            continue
        rows[parts[1]] = [parts[c] for c in cols]
    return rows


def run(cli, path, seed, extra, time_limit):
    cmd = [cli, "gtsp", path, "--json", "--seed", str(seed), "--time-limit", str(time_limit)] + extra
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    j = json.loads(out)
    # CPU seconds of the whole process (reading + solving, all threads): on a shared machine the
    # wall time (time_s, solve only) is inflated by other jobs, the CPU time much less.
    j["cpu_s"] = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return j


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", default=os.path.join(HERE, "..", "build", "cutroute"))
    ap.add_argument("--set", choices=["gtsp-small", "gtsp-large", "sop"], required=True)
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--first-seed", type=int, default=1)
    ap.add_argument("--only", default="", help="regex on instance names")
    ap.add_argument("extra", nargs="*")
    a = ap.parse_args()
    if a.set == "sop":
        rows = table(os.path.join(SHARED, "sop", "README.md"), [2, 3])
        # "<= 100 nodes" read as the TSPLIB size: n counts the two dummy end nodes (kro124p: 101).
        items = [(n, int(v[0]), int(v[1].split()[0])) for n, v in rows.items() if int(v[0]) <= 101]
        folder, limit, seeds = os.path.join(SHARED, "sop"), 10, a.seeds
    else:
        rows = table(os.path.join(SHARED, "gtsplib", "README.md"), [2, 5])
        lo, hi = (1, 89) if a.set == "gtsp-small" else (99, 217)
        items = [(n + ".gtsp", int(v[0]), int(v[1])) for n, v in rows.items() if lo <= int(v[0]) <= hi]
        folder, limit, seeds = os.path.join(SHARED, "gtsplib"), 60, a.seeds
    if a.only:
        items = [it for it in items if re.search(a.only, it[0])]
    print(f"| instance | size | best known | mean gap % | max gap % | at best | mean wall s | max wall s | mean cpu s |")
    print(f"|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    all_gaps, all_times, all_cpu, hits, runs = [], [], [], 0, 0
    for name, size, best in items:
        gaps, times, cpus, at_best = [], [], [], 0
        for s in range(a.first_seed, a.first_seed + seeds):
            j = run(a.cli, os.path.join(folder, name), s, a.extra, limit)
            obj = j["objective"]
            gap = 100.0 * (obj - best) / best if best else 0.0
            gaps.append(gap)
            times.append(j["time_s"])
            cpus.append(j["cpu_s"])
            at_best += obj <= best
        all_gaps += gaps
        all_times += times
        all_cpu += cpus
        hits += at_best
        runs += seeds
        print(f"| {name} | {size} | {best} | {sum(gaps)/len(gaps):.3f} | {max(gaps):.3f} | {at_best}/{seeds} | "
              f"{sum(times)/len(times):.3f} | {max(times):.3f} | {sum(cpus)/len(cpus):.3f} |", flush=True)
    n = len(all_gaps)
    mean = sum(all_gaps) / n
    se = (sum((g - mean) ** 2 for g in all_gaps) / (n - 1) / n) ** 0.5 if n > 1 else 0.0
    print(f"\nall: {len(items)} instances x {seeds} seeds (from {a.first_seed}): mean gap {mean:.4f} % (standard error {se:.4f}), "
          f"max gap {max(all_gaps):.3f} %, at best {hits}/{runs}, mean time {sum(all_times)/len(all_times):.3f} s, "
          f"max time {max(all_times):.3f} s, mean cpu {sum(all_cpu)/len(all_cpu):.3f} s")


if __name__ == "__main__":
    sys.exit(main())
