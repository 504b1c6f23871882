#!/usr/bin/env python3
"""Routes of `cutroute optimize` against Debian's dxf2gcode on the shared DXF corpus.

Runs our optimizer on every drawing, measures the written program with the independent
../shared/tools/gcode_stats.py, and prints a table against ../shared/data/dxf/dxf2gcode-baseline.md
(rapid travel between contours, pierces, precedence violations).

    python3 bench/compare_dxf2gcode.py [--cutroute build/cutroute] [--time-limit 2] [--min-contours 50]
"""
import argparse
import json
import pathlib
import re
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
SHARED = ROOT.parent / "shared"


def baseline():
    rows = {}
    for line in (SHARED / "data/dxf/dxf2gcode-baseline.md").read_text().splitlines():
        m = re.match(r"\| (\S+\.dxf) \| (\d+) \| ([\d.]+) \| ([\d.]+) \| ([\d.]+) \| (\d+) / (\d+) \|", line)
        if m:
            rows[m.group(1)] = dict(pierces=int(m.group(2)), cut=float(m.group(3)), rapid=float(m.group(4)),
                                    between=float(m.group(5)), violations=int(m.group(6)))
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cutroute", default=str(ROOT / "build/cutroute"))
    ap.add_argument("--time-limit", default="2")
    ap.add_argument("--min-contours", type=int, default=0)
    ap.add_argument("--extra", default="", help="more optimize options, e.g. --allow-crossing")
    args = ap.parse_args()
    base = baseline()
    print("| file | contours | pierces | rapid between (ours) | dxf2gcode | ratio | violations (ours / dxf2gcode) | wall s |")
    print("|---|---:|---:|---:|---:|---:|---|---:|")
    ratios = []
    ours_sum = theirs_sum = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        for dxf in sorted((SHARED / "data/dxf").glob("*.dxf")):
            prog = pathlib.Path(tmp) / (dxf.stem + ".ngc")
            t0 = time.monotonic()
            cmd = [args.cutroute, "optimize", str(dxf), "-o", str(prog), "--quiet", "--time-limit",
                   args.time_limit] + args.extra.split()
            r = subprocess.run(cmd, capture_output=True, text=True)
            name = dxf.name
            if r.returncode != 0 and "--allow-crossing" in r.stderr:
                # Drawn with crossing contours: refused by default; what the shop would run next.
                t0 = time.monotonic()
                r = subprocess.run(cmd + ["--allow-crossing"], capture_output=True, text=True)
                name += " (--allow-crossing)"
            wall = time.monotonic() - t0
            b = base.get(dxf.name)
            if r.returncode != 0:
                print(f"| {name} | | | refused: {r.stderr.strip()[:80]} | {b and b['between']} | | | {wall:.2f} |")
                continue
            st = json.loads(subprocess.run([sys.executable, str(SHARED / "tools/gcode_stats.py"), "--json", str(prog)],
                                           capture_output=True, text=True, check=True).stdout)[0]
            # A nest counts when either side sees that many contours (dxf2gcode splits some drawings
            # into more contours than we do; chain cutting makes fewer pierces than contours).
            if max(st["pierces"], b["pierces"] if b else 0) < args.min_contours:
                continue
            ratio = st["Loff_rapid_between_contours"] / b["between"] if b and b["between"] > 0 else float("nan")
            ratios.append(ratio)
            if b:
                ours_sum += st["Loff_rapid_between_contours"]
                theirs_sum += b["between"]
            print(f"| {name} | {st['contours']} | {st['pierces']} | {st['Loff_rapid_between_contours']:.1f} | "
                  f"{b['between'] if b else ''} | {ratio:.3f} | {st['precedence_violations']} / {b['violations'] if b else ''} | {wall:.2f} |")
    if ratios:
        print(f"\nworst ratio {max(ratios):.3f}, mean ratio {sum(ratios) / len(ratios):.3f} over {len(ratios)} files")
        print(f"summed: {ours_sum:.1f} mm against {theirs_sum:.1f} mm, ratio {ours_sum / theirs_sum:.3f}")


if __name__ == "__main__":
    main()
