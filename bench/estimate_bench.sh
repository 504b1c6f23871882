#!/usr/bin/env bash
# End-to-end: writes a 1 000 000-block program and times `cutroute estimate` on it (< 1 s wanted).
# Usage: bench/estimate_bench.sh [BUILD_DIR]   (default build). On a loaded machine compare the
# user CPU time: wall time then includes waiting for a core.
set -euo pipefail
build=${1:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
/usr/bin/python3 - "$tmp/big.nc" <<'PY'
import sys
out = ["G21 G90 G17", "F6000"]
k = 0
while len(out) + 12 < 1_000_000:
    x = 10 + (k % 140) * 20.0
    y = 10 + ((k // 140) % 70) * 20.0
    out += [f"G0 X{x+2:.3f} Y{y:.3f}", "M3", f"G1 X{x+10:.3f} Y{y:.3f}", f"G3 X{x+12:.3f} Y{y+2:.3f} I0 J2.000",
            f"G1 X{x+12:.3f} Y{y+6:.3f}", f"G3 X{x+10:.3f} Y{y+8:.3f} I-2.000 J0", f"G1 X{x+2:.3f} Y{y+8:.3f}",
            f"G3 X{x:.3f} Y{y+6:.3f} I0 J-2.000", f"G1 X{x:.3f} Y{y+2:.3f}", f"G3 X{x+2:.3f} Y{y:.3f} I2.000 J0", "M5"]
    k += 1
while len(out) < 999_999:
    out.append("G0 X0 Y0")
out.append("M30")
open(sys.argv[1], "w").write("\n".join(out) + "\n")
PY
echo "program: $(wc -l < "$tmp/big.nc") lines, $(du -h "$tmp/big.nc" | cut -f1)"
for i in 1 2 3; do
  /usr/bin/time -f "estimate: %e s wall, %U s user CPU, %M KiB max RSS" "$build/cutroute" estimate "$tmp/big.nc" --json > "$tmp/out.json"
done
/usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print('frames', j['frames'], 'pierces', j['pierces'], 'L_on', round(j['cut_length_mm'],3))" "$tmp/out.json"
