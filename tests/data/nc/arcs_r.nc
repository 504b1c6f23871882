(R-form arcs: R > 0 the short way, R < 0 the long way)
G21 G90
G0 X10 Y0
M3
G3 X0 Y10 R10 F3000 (quarter circle: 15.70796327 mm)
G2 X10 Y0 R-10 (three quarters: 47.12388980 mm)
M5
G0 X0 Y0
M30
