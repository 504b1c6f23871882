(G1 with the beam off is neither L_on nor L_off; G0 with the beam on re-pierces)
G21 G90
F600
G1 X30 Y40 (beam off feed move: 50 mm at 600 mm/min = 5 s)
M3
G1 X60 Y40
G0 X60 Y80 (rapid with the beam on: 40 mm of L_off)
G1 X90 Y80 (cutting again: a second pierce)
M5
G0 X0 Y0
M2
