#!/usr/bin/env python3
"""Writes the 5-axis test parts of the self-tuning proof (tests/preproc/selftune_test.cpp,
VirtualShop5Axis) for the MC-300 (table-table, B about +Y on the bed, C about -Z on B), run
in the tcp world: X Y Z are the tool tip in the part frame (the machine file's [fixture]
frame; ../mc300.var has zero offsets), B C the table's angles. T1 = 10 mm flat end mill,
100 mm long (../mc300.tbl).

A 3+2 pocket: the table turned to B C and held there, a rectangular pocket milled into the
plane square to the tool: the floor by a raster of the flat end, the walls by one pass of
the tool's side around them (climb milling), the full depth in one pass. Its CMM plan: the
floor on a grid 2 mm inside the walls (normal: the tool axis), the walls at three heights
(normals into the pocket), 7 mm from the corners (which the tool rounds to R5).

  pocket_32_a: B-45 C120, 60 x 40, 8 deep, centred on the part zero
  pocket_32_b: B-25 C235, 50 x 50, 6 deep, centred 30 mm off it (another shape and pose)
  head_pocket_a: the same kind of pocket on the head-table test machine bc_head
    (tests/unit/machines/data/bc_head.toml: B turns the head, C the table), B-40 C60, 60 x 40 x 8
  head_pocket_b: on bc_head, B30 C200, 50 x 50 x 6, centred 30 mm off the part zero

The tool axis in the part frame for B C is R_C(C)^T R_B(B)^T z with R_B the rotation about +Y
and R_C about -Z (checked against `volcomp simulate`, which writes it). Before writing,
checks (assertions): every floor point lies under the flat end of a raster pass at the floor
depth, every wall point 5 mm (the radius) from the wall pass's axis, and the raster covers
the floor (stepover below the diameter).

Run: python3 make_parts_5axis.py (writes pocket_32_a.ngc, pocket_32_a_points.csv,
pocket_32_b.ngc, pocket_32_b_points.csv, the head_pocket_* and cone_* parts beside itself). Standard library only,
deterministic."""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
RADIUS = 5.0
STEPOVER = 6.0
SAFE = 25.0    # retract distance above the pocket's top, along the tool axis
FEED = 1000.0
PLUNGE = 200.0
BC_HEAD_FIXTURE_DEG = 15.0  # tests/unit/machines/data/bc_head.toml [fixture] rotation_deg about z
CORNER = 7.0   # wall points stay this far from the pocket's corners (rounded to the tool radius, 5)


def rot_y(a):
    c, s = math.cos(a), math.sin(a)
    return [[c, 0, s], [0, 1, 0], [-s, 0, c]]


def rot_z(a):
    c, s = math.cos(a), math.sin(a)
    return [[c, -s, 0], [s, c, 0], [0, 0, 1]]


def mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def add(*vs):
    return tuple(sum(c) for c in zip(*vs))


def scale(k, v):
    return tuple(k * c for c in v)


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def unit(v):
    n = math.sqrt(dot(v, v))
    return tuple(c / n for c in v)


def frame(b_deg, c_deg, machine="mc300"):
    """Tool axis t (tip into the spindle) and two directions u, v in the plane square to it.
    mc300: B and C both turn the table. bc_head: B (about +y) turns the head, C (about -z)
    the table, and the fixture is turned 15 deg about z: t = R_z(C - 15) (sin B, 0, cos B)."""
    if machine == "mc300":
        m = mul(rot_y(math.radians(b_deg)), rot_z(-math.radians(c_deg)))  # part -> machine
        t = (m[2][0], m[2][1], m[2][2])  # third row: machine z in the part frame
    else:
        b = math.radians(b_deg)
        m = rot_z(math.radians(c_deg - BC_HEAD_FIXTURE_DEG))
        t = tuple(dot(row, (math.sin(b), 0.0, math.cos(b))) for row in m)
    u = unit(add((1.0, 0.0, 0.0), scale(-t[0], t)))
    v = cross(t, u)
    return t, u, v


def fmt(x):
    return f"{x:.4f}"


def write_plan(name, title, legend, points):
    """The CMM plan: (face, point, normal) numbered per face; returns the number of points."""
    with open(os.path.join(HERE, name + "_points.csv"), "w") as f:
        f.write(f"# {title}: CMM plan written by make_parts_5axis.py\n# {legend}\n")
        f.write("# nominal points on the cut surfaces (part frame), unit normals out of the material\n")
        f.write("id,x[mm],y[mm],z[mm],i,j,k\n")
        counts = {}
        for face, p, n in points:
            counts[face] = counts.get(face, 0) + 1
            f.write(f"{face}{counts[face]:03d},{fmt(p[0])},{fmt(p[1])},{fmt(p[2])},"
                    f"{n[0]:.6f},{n[1]:.6f},{n[2]:.6f}\n")
    return len(points)


def write_part(name, title, b_deg, c_deg, centre, half_u, half_v, depth, machine="mc300"):
    t, u, v = frame(b_deg, c_deg, machine)
    at = lambda a, b, h: add(centre, scale(a, u), scale(b, v), scale(-h, t))  # h: depth below the top
    lines = ["%", f"({title})",
             "(tcp world: X Y Z are the tool tip in the part frame; written by make_parts_5axis.py)",
             "G21 G90 G17 G40 G49 G54 G94", "T1 M6", "G43 H1", "S8000 M3"]
    top = at(0, 0, -SAFE)
    lines.append(f"G0 X{fmt(top[0])} Y{fmt(top[1])} Z{fmt(top[2])} B{fmt(b_deg)} C{fmt(c_deg)}")
    # Floor: raster along u at the floor depth.
    rows = []
    b = -half_v + RADIUS
    while b < half_v - RADIUS - 1e-9:
        rows.append(b)
        b += STEPOVER
    rows.append(half_v - RADIUS)
    assert all(r2 - r1 <= 2 * RADIUS - 1 for r1, r2 in zip(rows, rows[1:])), "the raster leaves ridges"
    a0, a1 = -half_u + RADIUS, half_u - RADIUS
    start = at(a0, rows[0], -2)
    lines.append(f"G0 X{fmt(start[0])} Y{fmt(start[1])} Z{fmt(start[2])}")
    p = at(a0, rows[0], depth)
    lines.append(f"G1 X{fmt(p[0])} Y{fmt(p[1])} Z{fmt(p[2])} F{PLUNGE:.0f}")
    floor_passes = []
    for k, row in enumerate(rows):
        a_from, a_to = (a0, a1) if k % 2 == 0 else (a1, a0)
        p = at(a_to, row, depth)
        lines.append(f"G1 X{fmt(p[0])} Y{fmt(p[1])} Z{fmt(p[2])} F{FEED:.0f}")
        floor_passes.append((row, min(a_from, a_to), max(a_from, a_to)))
        if k + 1 < len(rows):
            q = at(a_to, rows[k + 1], depth)
            lines.append(f"G1 X{fmt(q[0])} Y{fmt(q[1])} Z{fmt(q[2])}")
    # Walls: one pass of the side around the pocket, climb milling (clockwise seen from the spindle).
    corners = [(half_u - RADIUS, -half_v + RADIUS), (-half_u + RADIUS, -half_v + RADIUS),
               (-half_u + RADIUS, half_v - RADIUS), (half_u - RADIUS, half_v - RADIUS)]
    for a, b in corners + corners[:1]:
        p = at(a, b, depth)
        lines.append(f"G1 X{fmt(p[0])} Y{fmt(p[1])} Z{fmt(p[2])}")
    p = at(corners[0][0], corners[0][1], -SAFE)
    lines += [f"G0 X{fmt(p[0])} Y{fmt(p[1])} Z{fmt(p[2])}", "M5", "M2", "%"]
    with open(os.path.join(HERE, name + ".ngc"), "w") as f:
        f.write("\n".join(lines) + "\n")

    # CMM plan.
    points = []
    n_u, n_v = int(2 * (half_u - 2) // 6) + 1, int(2 * (half_v - 2) // 6) + 1
    for i in range(n_u):
        for j in range(n_v):
            a = -half_u + 2 + i * (2 * (half_u - 2)) / (n_u - 1)
            b = -half_v + 2 + j * (2 * (half_v - 2)) / (n_v - 1)
            # under the flat end of a raster pass (or of the wall pass, at the same depth)
            assert any(abs(b - row) <= RADIUS and lo - RADIUS <= a <= hi + RADIUS for row, lo, hi in floor_passes)
            points.append(("FL", at(a, b, depth), t))
    for h in (2.0, depth / 2, depth - 2.0):
        for sign_u in (1, -1):  # walls u = +-half_u, normals into the pocket
            n = int((2 * (half_v - CORNER)) // 5) + 1
            for j in range(n):
                b = -half_v + CORNER + j * (2 * (half_v - CORNER)) / (n - 1)
                assert abs(b) <= half_v - RADIUS  # across from the wall pass, not in a corner's fillet
                points.append(("WU" + ("+" if sign_u > 0 else "-"), at(sign_u * half_u, b, h), scale(-sign_u, u)))
        for sign_v in (1, -1):
            n = int((2 * (half_u - CORNER)) // 5) + 1
            for i in range(n):
                a = -half_u + CORNER + i * (2 * (half_u - CORNER)) / (n - 1)
                assert abs(a) <= half_u - RADIUS
                points.append(("WV" + ("+" if sign_v > 0 else "-"), at(a, sign_v * half_v, h), scale(-sign_v, v)))
    return write_plan(name, title, "FL: floor (normal: the tool axis); WU+ WU- WV+ WV-: walls at three heights, "
                      "normals into the pocket", points)


def write_cone(name, title, tilt_deg, floor_radius, depth, step_deg=0.2):
    """A conical pocket round the part's Z axis, wider at the top (the wall tilted outward by
    `tilt_deg`): the floor by a raster of the vertical tool (B0 C0), the wall by one swarf
    pass of the tool's side lying on it (B = -tilt, C turning 360 deg with the tool's azimuth).
    The tool axis for B C is (-sin B cos C, -sin B sin C, cos B) in the part frame: along the
    cone's generatrix at azimuth C. The tip sits r off the wall along its normal, its flat end's
    lowest point on the wall's foot: the side touches the wall along the generatrix."""
    a = math.radians(tilt_deg)
    bottom = -depth
    lines = ["%", f"({title})",
             "(tcp world: X Y Z are the tool tip in the part frame; written by make_parts_5axis.py)",
             "G21 G90 G17 G40 G49 G54 G94", "T1 M6", "G43 H1", "S8000 M3",
             f"G0 X0.0000 Y0.0000 Z{fmt(SAFE)} B0.0000 C0.0000"]
    # Floor raster (tool vertical), inside the circle of the tool centre r from the wall's foot.
    reach = floor_radius - RADIUS
    rows, y = [], -reach + 1.0
    while y < reach - 1.0 - 1e-9:
        rows.append(y)
        y += STEPOVER
    rows.append(reach - 1.0)
    first = True
    passes = []
    for k, y in enumerate(rows):
        half = math.sqrt(reach * reach - y * y)
        x0, x1 = (-half, half) if k % 2 == 0 else (half, -half)
        if first:
            lines += [f"G0 X{fmt(x0)} Y{fmt(y)} Z{fmt(2.0)}", f"G1 Z{fmt(bottom)} F{PLUNGE:.0f}"]
            first = False
        else:
            lines.append(f"G1 X{fmt(x0)} Y{fmt(y)}")
        lines.append(f"G1 X{fmt(x1)} Y{fmt(y)} F{FEED:.0f}")
        passes.append((y, -half, half))
    lines.append(f"G0 Z{fmt(SAFE)}")

    def tip(theta):
        c, s_ = math.cos(theta), math.sin(theta)
        foot = (floor_radius * c, floor_radius * s_, bottom)
        inward = (-math.cos(a) * c, -math.cos(a) * s_, math.sin(a))  # wall normal, into the pocket
        return add(foot, scale(RADIUS, inward))

    steps = int(round(360 / step_deg))
    p = tip(0.0)
    lines += [f"G0 X{fmt(p[0])} Y{fmt(p[1])} Z{fmt(SAFE)} B{fmt(-tilt_deg)} C0.0000",
              f"G1 X{fmt(p[0])} Y{fmt(p[1])} Z{fmt(p[2])} F{PLUNGE:.0f}"]
    for k in range(1, steps + 1):
        theta = 2 * math.pi * k / steps
        p = tip(theta)
        lines.append(f"G1 X{fmt(p[0])} Y{fmt(p[1])} Z{fmt(p[2])} C{k * step_deg:.4f}" + (f" F{FEED:.0f}" if k == 1 else ""))
    g = (math.sin(a), 0.0, math.cos(a))
    up = add(p, scale(SAFE, g))
    lines += [f"G0 X{fmt(up[0])} Y{fmt(up[1])} Z{fmt(up[2])}", "M5", "M2", "%"]
    with open(os.path.join(HERE, name + ".ngc"), "w") as f:
        f.write("\n".join(lines) + "\n")

    points = []
    for ix in range(-5, 6):
        for iy in range(-5, 6):
            x, y = ix * (reach - 3) / 5, iy * (reach - 3) / 5
            if math.hypot(x, y) > reach - 3:
                continue
            assert any(abs(y - row) <= RADIUS and lo - RADIUS <= x <= hi + RADIUS for row, lo, hi in passes)
            points.append(("FL", (x, y, bottom), (0.0, 0.0, 1.0)))
    for h in (3.0, depth / 2, depth - 3.0):
        for k in range(36):
            theta = 2 * math.pi * (k + 0.5) / 36
            c, s_ = math.cos(theta), math.sin(theta)
            r_at = floor_radius + h * math.tan(a)
            normal = (-math.cos(a) * c, -math.cos(a) * s_, math.sin(a))
            assert h / math.cos(a) < 25  # within the flute length above the tip
            points.append(("WALL", (r_at * c, r_at * s_, bottom + h), normal))
    return write_plan(name, title, "FL: floor (normal +Z); WALL: the conical wall at three heights, normals into the pocket",
                      points)


if __name__ == "__main__":
    print(write_part("pocket_32_a", "3+2 pocket at B-45 C120 on the MC-300, 60 x 40 x 8", -45, 120, (0.0, 0.0, 0.0),
                     30, 20, 8))
    print(write_part("pocket_32_b", "3+2 pocket at B-25 C235 on the MC-300, 50 x 50 x 6", -25, 235, (30.0, -20.0, 0.0),
                     25, 25, 6))
    print(write_part("head_pocket_a", "3+2 pocket at B-40 C60 on bc_head, head-table, 60 x 40 x 8", -40, 60,
                     (0.0, 0.0, 0.0), 30, 20, 8, machine="bc_head"))
    print(write_part("head_pocket_b", "3+2 pocket at B30 C200 on bc_head, head-table, 50 x 50 x 6", 30, 200,
                     (30.0, -20.0, 0.0), 25, 25, 6, machine="bc_head"))
    print(write_cone("cone_a", "5-axis swarf: a conical pocket, wall tilted 40 deg, C turning 360 deg, and its floor",
                     40, 30, 15))
    print(write_cone("cone_b", "5-axis swarf: a conical pocket, wall tilted 28 deg, C turning 360 deg, and its floor",
                     28, 24, 12))
