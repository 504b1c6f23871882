(G40/G41/G42 noted; G64, G49, G54, G94, T, S, D words accepted; an unknown A word warned about)
G21 G90 G64 G49 G54 G94
T1 M6
S6000
G0 X0 Y0
M3
G41 D1 G1 X100 Y0 F5000
G1 X100 Y100 A15
G40
G1 X0 Y100
G42 G1 X0 Y0
G40
M5
G12 X500 Y500 (unknown G code: the block does not move)
G0 X0 Y0
M30
