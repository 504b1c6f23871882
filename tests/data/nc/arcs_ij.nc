; I/J arcs, incremental centre (default G91.1): a full circle, a half circle, a quarter
G21 G90
G0 X10 Y0
M3
G2 X10 Y0 I-10 J0 F3000 ; full circle r 10, clockwise: 62.83185307 mm
M5
G0 X50 Y0
M4
G3 X30 Y0 I-10 J0 ; half circle r 10: 31.41592654 mm
G3 X20 Y-10 I0 J-10 ; quarter, centre (30,-10), r 10, ccw from (30,0) to (20,-10): 15.70796327 mm
M5
G0 X0 Y0
M30
