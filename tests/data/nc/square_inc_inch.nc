(the same kind of rectangle, 4 in x 2 in, incremental inch, no N numbers)
G20 G91 G17
G0 X1 Y1
M3
G1 X4 F240
Y2
X-4
Y-2
M5
G0 X-1 Y-1
M2
