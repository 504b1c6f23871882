%
(CRLF line ends, lower case, comments, block delete, dwell in seconds)
g21 g90

g0 x0 y0
/m3
g4 p0.5 (pierce dwell)
g1x20y0f1200 ; compact words
g1 X 20 Y 15
m5
g4 P1.25
N5
m30
%
