#!/usr/bin/env python3
"""Large CAM-style programs for the pre-distorter benchmark (deterministic).

  make_programs.py 3axis LINES OUT.ngc   mill3: a wavy raster finish, 0.3-0.8 mm G1 segments
  make_programs.py 5axis LINES OUT.ngc   MC-300: a swarf contour, X Y Z B C on every line
"""
import math
import random
import sys


def three_axis(lines, out):
    random.seed(1)
    out.write("(benchmark: 3-axis raster finish on mill3, G54 from tests/programs/mill3.var)\n")
    out.write("G21 G90 G17 G94 G54\nT1 M6\nS8000 M3\nG0 G43 H1 Z20\nG0 X-140 Y-55\nG1 Z-2 F300\nF1500\n")
    x, y, d = -140.0, -55.0, 1
    for _ in range(lines - 10):
        x += d * random.uniform(0.3, 0.8)
        if x > 140 or x < -140:
            x, y, d = max(-140.0, min(140.0, x)), y + 0.5, -d
            if y > 55:
                y = -55.0
        out.write(f"X{x:.4f} Y{y:.4f} Z{-2 + 0.5 * math.sin(x / 7.0):.4f}\n")
    out.write("G0 Z20\nM5\nM30\n")


def five_axis(lines, out):
    out.write("(benchmark: 5-axis swarf contour on the MC-300, axes convention)\n")
    out.write("G21 G90 G17 G94 G54\nT1 M6\nS6000 M3\nG43 H1\nG0 X-300 Y-100 Z-150 B0 C0\nG0 B-35\nG1 F2000\n")
    for k in range(lines - 10):
        c = (k * 0.05) % 720.0          # 0.05 deg of C per block: 0.05 mm along the contour
        t = math.radians(c)
        out.write(f"X{-300 + 60 * math.cos(t):.4f} Y{-160 + 60 * math.sin(t):.4f} "
                  f"Z{-200 + 5 * math.sin(3 * t):.4f} B{-35 + 10 * math.sin(2 * t):.4f} C{c:.4f}\n")
    out.write("G0 Z-100\nM5\nM30\n")


if __name__ == "__main__":
    kind, lines, path = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    with open(path, "w") as f:
        (three_axis if kind == "3axis" else five_axis)(lines, f)
