#!/usr/bin/env python3
"""Writes the malformed DXF files of this folder: exactly one defect each, named after it.
Run from this folder; the files are committed, this script documents how they were made."""
import os
import random

def dxf(entities, blocks=None, header=True):
    s = "0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1015\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n" if header else ""
    if blocks:
        s += "0\nSECTION\n2\nBLOCKS\n" + blocks + "0\nENDSEC\n"
    s += "0\nSECTION\n2\nENTITIES\n" + entities + "0\nENDSEC\n0\nEOF\n"
    return s

def line(x1, y1, x2, y2, h='100', layer='0'):
    return f"0\nLINE\n5\n{h}\n8\n{layer}\n10\n{x1}\n20\n{y1}\n30\n0.0\n11\n{x2}\n21\n{y2}\n31\n0.0\n"

def block(name, body):
    return f"0\nBLOCK\n8\n0\n2\n{name}\n70\n0\n10\n0\n20\n0\n30\n0\n" + body + "0\nENDBLK\n8\n0\n"

def insert(name, h, x=0, y=0, extra=""):
    return f"0\nINSERT\n5\n{h}\n8\n0\n2\n{name}\n10\n{x}\n20\n{y}\n30\n0\n" + extra

good = line(0, 0, 10, 0, '100') + line(10, 0, 10, 10, '101')
full = dxf(good + line(10, 10, 0, 0, '102'))
files = {}
files['empty.dxf'] = ""
files['truncated_inside_entity.dxf'] = full[:full.index("21\n0\n31", full.index("5\n102"))]  # ends after the 3rd LINE's x2
files['non_numeric_coordinate.dxf'] = dxf(good + line(10, 10, 'abc', 0, '102'))
files['nan_coordinate.dxf'] = dxf(good + line(10, 10, 0, 'nan', '102'))
files['inf_coordinate.dxf'] = dxf(good + line('inf', 10, 0, 0, '102'))
files['huge_coordinate_1e300.dxf'] = dxf(good + line(10, 10, '1e300', 0, '102'))
files['unknown_section.dxf'] = dxf(good).replace(
    "0\nSECTION\n2\nENTITIES", "0\nSECTION\n2\nFOOBAR\n0\nENDSEC\n0\nSECTION\n2\nENTITIES")
rng = random.Random(20261121)
files['binary_garbage.dxf'] = bytes(rng.randrange(256) for _ in range(4096))
cycle_blocks = (block("A", line(0, 0, 1, 0, '200') + insert("B", '201', 5, 0)) +
                block("B", line(0, 0, 0, 1, '300') + insert("A", '301', 0, 5)))
files['insert_cycle_a_b_a.dxf'] = dxf(good + insert("A", '102'), cycle_blocks)
# 10^7 entities: a MINSERT of 1000 x 1000 cells of a 10-LINE block ...
ten = block("TEN", "".join(line(i, 0, i, 1, f"{0x400 + i:X}") for i in range(10)))
files['insert_expansion_1e7_minsert.dxf'] = dxf(
    good + insert("TEN", '102', extra="70\n1000\n71\n1000\n44\n20\n45\n2\n"), ten)
# ... and through 7 nested blocks, each inserting the previous one 10 times.
nested = block("N0", line(0, 0, 1, 0, '500'))
h = 0x600
for lvl in range(1, 8):
    body = ""
    for k in range(10):
        body += insert(f"N{lvl - 1}", f"{h:X}", k * 2, lvl)
        h += 1
    nested += block(f"N{lvl}", body)
files['insert_expansion_1e7_nested.dxf'] = dxf(good + insert("N7", '102'), nested)
files['group_code_not_integer.dxf'] = full.replace("11\n0\n21", "1x\n0\n21", 1)
files['bulge_before_first_vertex.dxf'] = dxf(
    good + "0\nLWPOLYLINE\n5\n102\n8\n0\n90\n2\n70\n0\n42\n0.5\n10\n0\n20\n0\n10\n5\n20\n5\n")
files['vertex_count_mismatch.dxf'] = dxf(
    good + "0\nLWPOLYLINE\n5\n102\n8\n0\n90\n1000000000\n70\n0\n10\n0\n20\n0\n10\n5\n20\n5\n")
files['group_code_without_value.dxf'] = full[:full.index("0\nEOF")] + "0\n"
for name, content in files.items():
    if isinstance(content, bytes):
        with open(name, 'wb') as f:
            f.write(content)
    else:
        with open(name, 'w', newline='') as f:
            f.write(content)
