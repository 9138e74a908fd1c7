#!/usr/bin/env python3
"""Writes the test parts of the self-tuning proof (tests/preproc/selftune_test.cpp) for mill3
(mill3.var G54, mill3.tbl T1 = 10 mm flat end mill): each part's program and its CMM plan
(nominal points on the cut surfaces, unit normals out of the material, part frame = G54).

  part A: a 200 x 120 block centred on the part zero: top face-milled at z = 0, walls
          side-milled in two passes (tip at z = -10, -20), leaving a floor ring at z = -20.
  part B: a different part: a 100 mm boss centred at (40, 20), top face-milled at z = -5,
          wall cut by full circles (z = -15, -25), and a straight 150 mm wall along y = -80.

Run: python3 make_parts.py (writes part_a.ngc, part_a_points.csv, part_b.ngc, part_b_points.csv
beside itself). Deterministic."""
import math
import os

R = 5.0  # tool radius (T1, D10)
HERE = os.path.dirname(os.path.abspath(__file__))


def f(v):
    s = f"{v:.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def header(title):
    return ["%", f"({title})", "(mill3: G54 from mill3.var, T1 10 mm flat end mill from mill3.tbl)",
            "G21 G90 G17 G40 G49 G80 G94 G91.1", "G54", "T1 M6", "S8000 M3", "G0 G43 H1 Z50."]


def raster(lines, x0, x1, y0, y1, step, z):
    """Face milling along X, zig-zag, from y0 to y1 (inclusive, last line at y1)."""
    n = math.ceil((y1 - y0) / step)
    ys = [y0 + (y1 - y0) * k / n for k in range(n + 1)]
    lines += [f"G0 X{f(x0)} Y{f(ys[0])}", "G0 Z2.", f"G1 Z{f(z)} F300."]
    for k, y in enumerate(ys):
        if k:
            lines.append(f"G1 Y{f(y)} F1200.")
        lines.append(f"G1 X{f(x1 if k % 2 == 0 else x0)} F1200.")
    lines.append("G0 Z50.")


def block_walls(lines, hx, hy, depths):
    """Outside contour of the block |x| <= hx, |y| <= hy, climb (clockwise), corner arcs."""
    cx, cy = hx + R, hy + R
    for z in depths:
        lines += [f"G0 X{f(-cx)} Y0", "G0 Z2.", f"G1 Z{f(z)} F300."]
        lines += [f"G1 Y{f(hy)} F1200.", f"G2 X{f(-hx)} Y{f(cy)} I{f(R)} J0",
                  f"G1 X{f(hx)}", f"G2 X{f(cx)} Y{f(hy)} I0 J{f(-R)}",
                  f"G1 Y{f(-hy)}", f"G2 X{f(hx)} Y{f(-cy)} I{f(-R)} J0",
                  f"G1 X{f(-hx)}", f"G2 X{f(-cx)} Y{f(-hy)} I0 J{f(R)}",
                  "G1 Y0", "G0 Z50."]


def write(name, lines, points, comment):
    with open(os.path.join(HERE, name + ".ngc"), "w") as out:
        out.write("\n".join(lines + ["M5", "M30", "%"]) + "\n")
    ids = set()
    with open(os.path.join(HERE, name + "_points.csv"), "w") as out:
        out.write(f"# {comment}\n# nominal points on the cut surfaces (part frame = G54), unit normals out of the material\n")
        out.write("id,x[mm],y[mm],z[mm],i,j,k\n")
        for pid, p, n in points:
            assert pid not in ids
            ids.add(pid)
            assert abs(math.hypot(*n) - 1) < 1e-12
            out.write(",".join([pid] + [f(v) for v in p] + [f(v) for v in n]) + "\n")


def part_a():
    hx, hy = 100.0, 60.0
    lines = header("self-tuning test part A: 200 x 120 block, top z 0, walls to z -20")
    raster(lines, -hx - 10, hx + 10, -hy, hy, 8.0, 0.0)
    block_walls(lines, hx, hy, [-10.0, -20.0])
    pts = []
    for z in (-5.0, -15.0):
        for k, y in enumerate(range(-50, 51, 10)):
            pts.append((f"A-W+X-{z:+.0f}-{k:02d}", (hx, y, z), (1, 0, 0)))
            pts.append((f"A-W-X-{z:+.0f}-{k:02d}", (-hx, y, z), (-1, 0, 0)))
        for k, x in enumerate(range(-90, 91, 10)):
            pts.append((f"A-W+Y-{z:+.0f}-{k:02d}", (x, hy, z), (0, 1, 0)))
            pts.append((f"A-W-Y-{z:+.0f}-{k:02d}", (x, -hy, z), (0, -1, 0)))
    for i, x in enumerate(range(-90, 91, 20)):
        for j, y in enumerate(range(-50, 51, 20)):
            pts.append((f"A-TOP-{i}{j}", (x, y, 0.0), (0, 0, 1)))
    for k, y in enumerate(range(-40, 41, 20)):
        pts.append((f"A-FL+X-{k}", (hx + 2.5, y, -20.0), (0, 0, 1)))
        pts.append((f"A-FL-X-{k}", (-hx - 2.5, y, -20.0), (0, 0, 1)))
    for k, x in enumerate(range(-80, 81, 20)):
        pts.append((f"A-FL+Y-{k}", (x, hy + 2.5, -20.0), (0, 0, 1)))
        pts.append((f"A-FL-Y-{k}", (x, -hy - 2.5, -20.0), (0, 0, 1)))
    write("part_a", lines, pts, "self-tuning test part A (make_parts.py): walls at z -5 and -15, top z 0, floor ring z -20")


def part_b():
    cx, cy, r = 40.0, 20.0, 50.0
    lines = header("self-tuning test part B: 100 mm boss at X40 Y20, top z -5, straight wall y -80")
    raster(lines, cx - 60, cx + 60, cy - 56, cy + 56, 8.0, -5.0)
    for z in (-15.0, -25.0):  # boss wall: full circles, climb (clockwise), tool centre on r + R
        lines += [f"G0 X{f(cx + r + R)} Y{f(cy)}", "G0 Z2.", f"G1 Z{f(z)} F300.",
                  f"G2 X{f(cx + r + R)} Y{f(cy)} I{f(-(r + R))} J0 F1200.", "G0 Z50."]
    for z in (-15.0, -25.0):  # straight wall y = -80 facing -y: tool centre at y = -85
        lines += ["G0 X-85. Y-85.", "G0 Z2.", f"G1 Z{f(z)} F300.", "G1 X85. F1200.", "G0 Z50."]
    pts = []
    for z in (-10.0, -20.0):
        for k in range(36):
            a = math.radians(10 * k)
            pts.append((f"B-CYL-{z:+.0f}-{k:02d}", (cx + r * math.cos(a), cy + r * math.sin(a), z),
                        (math.cos(a), math.sin(a), 0)))
        for k, x in enumerate(range(-70, 71, 10)):
            pts.append((f"B-WALL-{z:+.0f}-{k:02d}", (x, -80.0, z), (0, -1, 0)))
    for i, dx in enumerate(range(-40, 41, 20)):
        for j, dy in enumerate(range(-40, 41, 20)):
            if math.hypot(dx, dy) <= 45:
                pts.append((f"B-TOP-{i}{j}", (cx + dx, cy + dy, -5.0), (0, 0, 1)))
    write("part_b", lines, pts, "self-tuning test part B (make_parts.py): boss wall at z -10 and -20, top z -5, wall y -80")


part_a()
part_b()
