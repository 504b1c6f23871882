#!/usr/bin/env python3
"""How fast `cutroute optimize` converges on the large nests of the corpus.

For each nest: one long run (the best objective it finds, default 60 s), then runs with short time
limits; prints T_cut (eq. 10), the solver's sequencing objective (rapids, pierces, cutting at the
set speed), the gap to the long run, and the wall time.

    python3 bench/optimize_convergence.py [--cutroute build/cutroute] [--long 60] [--limits 0.5 1 2 3]
"""
import argparse
import json
import pathlib
import subprocess
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
SHARED = ROOT.parent / "shared"
NESTS = ["vrs_Lv10_SHEET_001.dxf", "d2g_DRAAK.dxf"]


def run(exe, dxf, limit, extra):
    with tempfile.TemporaryDirectory() as tmp:
        rep = pathlib.Path(tmp) / "r.json"
        t0 = time.monotonic()
        subprocess.run([exe, "optimize", str(dxf), "-o", str(pathlib.Path(tmp) / "p.ngc"), "--report", str(rep),
                        "--quiet", "--time-limit", str(limit)] + extra, check=True)
        wall = time.monotonic() - t0
        r = json.loads(rep.read_text())
    return r["t_cut_s"], r["solver"]["objective"], r["rapid_length_mm"], wall


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cutroute", default=str(ROOT / "build/cutroute"))
    ap.add_argument("--long", type=float, default=60)
    ap.add_argument("--limits", type=float, nargs="*", default=[0.5, 1, 2, 3])
    ap.add_argument("--extra", default="")
    args = ap.parse_args()
    extra = args.extra.split()
    print("| nest | time limit s | wall s | T_cut s | gap to long run | solver objective s | gap | rapid mm |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for name in NESTS:
        dxf = SHARED / "data/dxf" / name
        best_t, best_obj, best_rapid, wall = run(args.cutroute, dxf, args.long, extra)
        print(f"| {name} | {args.long:g} | {wall:.2f} | {best_t:.2f} | 0 | {best_obj:.2f} | 0 | {best_rapid:.0f} |")
        for lim in args.limits:
            t, obj, rapid, wall = run(args.cutroute, dxf, lim, extra)
            print(f"| {name} | {lim:g} | {wall:.2f} | {t:.2f} | {100 * (t - best_t) / best_t:+.2f} % | {obj:.2f} | "
                  f"{100 * (obj - best_obj) / best_obj:+.2f} % | {rapid:.0f} |")


if __name__ == "__main__":
    main()
