#!/usr/bin/env python3
"""How well `cutroute optimize` keeps to --time-limit on huge made nests.

Writes the nests itself (nothing to download): perforated plates (one 3 000 x 3 000 mm outline
holding N circles of 10 mm on a grid) and sheets of P rectangular parts with two holes each. For
each nest and limit it prints the wall time of the whole command (reading and writing included),
how far it ran over the limit, where the time went (the report's timing_s), the work the route
search did and T_cut, and the peak memory when /usr/bin/time is there.

    python3 bench/time_limit.py [--cutroute build/cutroute] [--holes 40000 72000] [--parts 5000 24000]
                                [--limits 2 5 10] [--extra "--svg x.svg"]
"""
import argparse
import json
import math
import os
import pathlib
import shutil
import subprocess
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent


def dxf_text(lines, circles):
    out = ["0", "SECTION", "2", "HEADER", "9", "$INSUNITS", "70", "4", "0", "ENDSEC", "0", "SECTION", "2", "ENTITIES"]
    for (x1, y1, x2, y2) in lines:
        out += ["0", "LINE", "8", "0", "10", repr(x1), "20", repr(y1), "11", repr(x2), "21", repr(y2)]
    for (cx, cy, r) in circles:
        out += ["0", "CIRCLE", "8", "0", "10", repr(cx), "20", repr(cy), "40", repr(r)]
    out += ["0", "ENDSEC", "0", "EOF"]
    return "\n".join(out) + "\n"


def rect(x, y, w, h):
    return [(x, y, x + w, y), (x + w, y, x + w, y + h), (x + w, y + h, x, y + h), (x, y + h, x, y)]


def plate(holes):
    """One 3 000 x 3 000 mm outline with `holes` circles of 10 mm on a square grid."""
    k = math.ceil(math.sqrt(holes))
    pitch = 2900.0 / k
    circles = [(50 + pitch * (i + 0.5), 50 + pitch * (j + 0.5), 5.0) for i in range(k) for j in range(k)][:holes]
    return dxf_text(rect(0.0, 0.0, 3000.0, 3000.0), circles)


def parts(count):
    """`count` parts of 40 x 25 mm, 10 mm apart, each with two holes of 8 mm."""
    cols = math.ceil(math.sqrt(count * 35 / 50))
    lines, circles = [], []
    for n in range(count):
        x, y = 10.0 + 50.0 * (n % cols), 10.0 + 35.0 * (n // cols)
        lines += rect(x, y, 40.0, 25.0)
        circles += [(x + 10.0, y + 12.5, 4.0), (x + 30.0, y + 12.5, 4.0)]
    return dxf_text(lines, circles)


def run(exe, dxf, limit, extra, tmp):
    rep = tmp / "r.json"
    cmd = [exe, "optimize", str(dxf), "-o", str(tmp / "p.ngc"), "--report", str(rep), "--quiet",
           "--time-limit", str(limit)] + extra
    timer = shutil.which("time") or ("/usr/bin/time" if os.path.exists("/usr/bin/time") else None)
    if timer:
        cmd = [timer, "-f", "%M", "-o", str(tmp / "rss.txt")] + cmd
    t0 = time.monotonic()
    subprocess.run(cmd, check=True)
    wall = time.monotonic() - t0
    rss = int((tmp / "rss.txt").read_text().split()[-1]) / 1024 if timer else float("nan")
    return json.loads(rep.read_text()), wall, rss


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cutroute", default=str(ROOT / "build/cutroute"))
    ap.add_argument("--holes", type=int, nargs="*", default=[40000, 72000])
    ap.add_argument("--parts", type=int, nargs="*", default=[5000, 24000])
    ap.add_argument("--limits", type=float, nargs="*", default=[2, 5, 10])
    ap.add_argument("--extra", default="")
    args = ap.parse_args()
    extra = args.extra.split()
    print("| nest | contours | limit s | wall s | over s | entries s | solver s | refine s | programs s | work M | T_cut s | peak MB |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmpdir:
        tmp = pathlib.Path(tmpdir)
        nests = [(f"plate of {n} holes", n + 1, plate, n) for n in args.holes]
        nests += [(f"{n} parts with 2 holes", 3 * n, parts, n) for n in args.parts]
        for name, contours, make, n in nests:
            dxf = tmp / "nest.dxf"
            dxf.write_text(make(n))
            for limit in args.limits:
                r, wall, rss = run(args.cutroute, dxf, limit, extra, tmp)
                t = r["timing_s"]
                chosen = t.get(r["chosen"], {})
                print(f"| {name} | {contours} | {limit:g} | {wall:.2f} | {wall - limit:+.2f} | {t['entries']:.2f} | "
                      f"{r['solver']['time_s']:.2f} | {chosen.get('refine', 0):.2f} | {chosen.get('evaluate', 0):.2f} | "
                      f"{r['solver']['work_m']:.1f} | {r['t_cut_s']:.1f} | {rss:.0f} |", flush=True)


if __name__ == "__main__":
    main()
