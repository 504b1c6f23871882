#!/usr/bin/python3
"""Independent frame count (docs/FRAMES.md) for tests: lines with a word other than N/O after
removing comments, skipping '%' lines, up to and including the M2/M30 block. Prints one number per file."""
import re
import sys

for path in sys.argv[1:]:
    n = 0
    for line in open(path, encoding="utf-8", errors="replace").read().splitlines():
        text = re.sub(r"\([^)]*\)", "", line).split(";")[0].strip()
        if not text or text.startswith("%"):
            continue
        letters = {c.upper() for c in re.findall(r"([A-Za-z])\s*[-+]?[\d.]", text)}
        if letters - {"N", "O"}:
            n += 1
            if re.search(r"M0*(2|30)(?![\d.])", text.upper()):
                break
    print(n)
