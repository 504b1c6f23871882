(a control that switches the beam with M7 on, M9 off; M3 starts a spindle-like output)
G21 G90
M3
G0 X0 Y0
M7
G1 X0 Y25 F2000
M9
G0 X10 Y25
M7
G1 X10 Y0
M9
G0 X0 Y0
M5
M30
