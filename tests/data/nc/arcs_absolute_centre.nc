(G90.1: I and J are the absolute centre; same geometry as arcs_ij.nc)
G21 G90 G90.1
G0 X10 Y0
M3
G2 X10 Y0 I0 J0 F3000
M5
G0 X50 Y0
M4
G3 X30 Y0 I40 J0
G3 X20 Y-10 I30 J-10
M5
G91.1
G0 X0 Y0
M30
