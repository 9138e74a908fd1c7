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

5-axis swarf parts (the tool's side lying on a wall tilted outward, C turning 360 deg, and a
floor raster of the vertical tool): on the MC-300, cone_a (wall 40 deg) and cone_b (28 deg),
conical pockets round the part zero; on bc_head, head_draft_a (a 70 x 50 pocket with R15
corners, walls drafted 35 deg: the linear axes carry the tool along the straight walls, C turns
in the corners; beside it an 80 x 14 slot whose vertical walls face the machine's y, cut by the
tool's side with the head leaning B20 along the slot, which a swarf wall on this machine never
shows: cut_leaning_slot; and a 24 x 24 x 5 3+2 pocket at B35 C105 (cut_pocket), whose floor,
cut by the flat end at the swarf's B, shows the errors along the tilted tool that no swarf
wall or vertical floor does, and whose walls face the machine's y at another C than the
slot's; and a swarf ring, a conical pocket of 20 deg, 12 mm radius at its foot, 8 deep,
round X-50 Y-25 (its walls at 2 heights, 36 points each, its floor cut but not measured):
56 mm from the C axis where the pocket's centre is 22 mm from it, so the walls' error round
a turn of C, which is the C table's plus the linear axes' change over the circle the
feature's centre runs round the C axis, is seen at two radii and the two can be told apart;
the pocket's walls at 2 heights, its floor on a 15 x 9 grid; 351 points) and head_cone_b (a
cone of 22 deg centred at X-30 Y-25, which head_draft_a's tables are carried to). On bc_head the head
tilts the tool towards +x of the C frame, so C faces the wall to the tool: B = +tilt, C = the
wall's azimuth + 15 deg (the fixture's turn); on the MC-300 B = -tilt, C = the azimuth
(swarf_pose). Checked by assertions: the tool axis from frame() is the wall's slope at every
point of the pass.

The tool axis in the part frame for B C is R_C(C)^T R_B(B)^T z with R_B the rotation about +Y
and R_C about -Z (checked against `volcomp simulate`, which writes it). Before writing,
checks (assertions): every floor point lies under the flat end of a raster pass at the floor
depth, every wall point 5 mm (the radius) from the wall pass's axis, and the raster covers
the floor (stepover below the diameter).

Run: python3 make_parts_5axis.py (writes pocket_32_a.ngc, pocket_32_a_points.csv,
pocket_32_b.ngc, pocket_32_b_points.csv, the head_pocket_*, cone_*, head_draft_a and head_cone_b
parts beside itself). Standard library only, deterministic."""
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
    lines = ["%", f"({title})",
             "(tcp world: X Y Z are the tool tip in the part frame; written by make_parts_5axis.py)",
             "G21 G90 G17 G40 G49 G54 G94", "T1 M6", "G43 H1", "S8000 M3"]
    cut, points = cut_pocket(b_deg, c_deg, centre, half_u, half_v, depth, machine)
    lines += cut + ["M5", "M2", "%"]
    with open(os.path.join(HERE, name + ".ngc"), "w") as f:
        f.write("\n".join(lines) + "\n")
    return write_plan(name, title, "FL: floor (normal: the tool axis); WU+ WU- WV+ WV-: walls at three heights, "
                      "normals into the pocket", points)


def cut_pocket(b_deg, c_deg, centre, half_u, half_v, depth, machine, prefix=""):
    """A 3+2 pocket (the module's docstring): the program lines from the first rapid to the
    last retract, and its plan points (face names prefixed with `prefix`)."""
    t, u, v = frame(b_deg, c_deg, machine)
    at = lambda a, b, h: add(centre, scale(a, u), scale(b, v), scale(-h, t))  # h: depth below the top
    lines = []
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
    lines.append(f"G0 X{fmt(p[0])} Y{fmt(p[1])} Z{fmt(p[2])}")

    # CMM plan.
    points = []
    n_u, n_v = int(2 * (half_u - 2) // 6) + 1, int(2 * (half_v - 2) // 6) + 1
    for i in range(n_u):
        for j in range(n_v):
            a = -half_u + 2 + i * (2 * (half_u - 2)) / (n_u - 1)
            b = -half_v + 2 + j * (2 * (half_v - 2)) / (n_v - 1)
            # under the flat end of a raster pass (or of the wall pass, at the same depth)
            assert any(abs(b - row) <= RADIUS and lo - RADIUS <= a <= hi + RADIUS for row, lo, hi in floor_passes)
            points.append((prefix + "FL", at(a, b, depth), t))
    for h in (2.0, depth / 2, depth - 2.0):
        for sign_u in (1, -1):  # walls u = +-half_u, normals into the pocket
            n = int((2 * (half_v - CORNER)) // 5) + 1
            for j in range(n):
                b = -half_v + CORNER + j * (2 * (half_v - CORNER)) / (n - 1)
                assert abs(b) <= half_v - RADIUS  # across from the wall pass, not in a corner's fillet
                points.append((prefix + "WU" + ("+" if sign_u > 0 else "-"), at(sign_u * half_u, b, h), scale(-sign_u, u)))
        for sign_v in (1, -1):
            n = int((2 * (half_u - CORNER)) // 5) + 1
            for i in range(n):
                a = -half_u + CORNER + i * (2 * (half_u - CORNER)) / (n - 1)
                assert abs(a) <= half_u - RADIUS
                points.append((prefix + "WV" + ("+" if sign_v > 0 else "-"), at(a, sign_v * half_v, h), scale(-sign_v, v)))
    return lines, points


def swarf_pose(tilt_deg, c_deg, machine):
    """B and the azimuth (deg, in the part frame) of the tool axis for a swarf pass whose tool
    leans outward by `tilt_deg` at table angle C: the axis must be the cone's generatrix
    (sin a cos theta, sin a sin theta, cos a) at the azimuth theta of the tip.
    mc300: t = (-sin B cos C, -sin B sin C, cos B): B = -tilt, theta = C.
    bc_head: t = R_z(C - 15) (sin B, 0, cos B) (frame() above; the head tilts towards +x of
    the C frame, the fixture is turned 15 deg): B = +tilt, theta = C - 15."""
    if machine == "mc300":
        return -tilt_deg, c_deg
    return tilt_deg, c_deg - BC_HEAD_FIXTURE_DEG


def write_cone(name, title, tilt_deg, floor_radius, depth, step_deg=0.2, machine="mc300", centre=(0.0, 0.0)):
    """A conical pocket round the part's Z axis, wider at the top (the wall tilted outward by
    `tilt_deg`): the floor by a raster of the vertical tool (B0 C0), the wall by one swarf
    pass of the tool's side lying on it (C turning 0 -> 360 deg, B and the tip's azimuth
    from swarf_pose: the tool axis along the cone's generatrix at the tip's azimuth, checked
    against frame()). The tip sits r off the wall along its normal, its flat end's lowest
    point on the wall's foot: the side touches the wall along the generatrix. `centre`: the
    cone's axis in the part frame (x, y); off the table's axis, the linear axes move while C
    turns (on the table's axis the tip stands still in the machine while the part turns)."""
    lines = ["%", f"({title})",
             "(tcp world: X Y Z are the tool tip in the part frame; written by make_parts_5axis.py)",
             "G21 G90 G17 G40 G49 G54 G94", "T1 M6", "G43 H1", "S8000 M3"]
    cut, points = cut_cone(tilt_deg, floor_radius, depth, step_deg, machine, centre)
    lines += cut + ["M5", "M2", "%"]
    with open(os.path.join(HERE, name + ".ngc"), "w") as f:
        f.write("\n".join(lines) + "\n")
    return write_plan(name, title, "FL: floor (normal +Z); WALL: the conical wall at three heights, normals into the pocket",
                      points)


def cut_cone(tilt_deg, floor_radius, depth, step_deg, machine, centre, heights=None, per_ring=36, floor=5,
             prefix=""):
    """A conical pocket (write_cone): the program lines from the first rapid to the last
    retract, and its plan points (face names prefixed with `prefix`): the floor on a
    (2 floor + 1)^2 grid within 3 mm of the tool's reach (none for floor = 0), the wall at
    `heights` above the floor (default 3 mm, half the depth and depth - 3 mm), `per_ring`
    points round each."""
    a = math.radians(tilt_deg)
    cx, cy = centre
    b_deg, _ = swarf_pose(tilt_deg, 0.0, machine)
    bottom = -depth
    lines = [f"G0 X{fmt(cx)} Y{fmt(cy)} Z{fmt(SAFE)} B0.0000 C0.0000"]
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
            lines += [f"G0 X{fmt(x0 + cx)} Y{fmt(y + cy)} Z{fmt(2.0)}", f"G1 Z{fmt(bottom)} F{PLUNGE:.0f}"]
            first = False
        else:
            lines.append(f"G1 X{fmt(x0 + cx)} Y{fmt(y + cy)}")
        lines.append(f"G1 X{fmt(x1 + cx)} Y{fmt(y + cy)} F{FEED:.0f}")
        passes.append((y, -half, half))
    lines.append(f"G0 Z{fmt(SAFE)}")

    def tip(theta):
        c, s_ = math.cos(theta), math.sin(theta)
        foot = (cx + floor_radius * c, cy + floor_radius * s_, bottom)
        inward = (-math.cos(a) * c, -math.cos(a) * s_, math.sin(a))  # wall normal, into the pocket
        return add(foot, scale(RADIUS, inward))

    def azimuth(c_deg):
        b, theta_deg = swarf_pose(tilt_deg, c_deg, machine)
        theta = math.radians(theta_deg)
        generatrix = (math.sin(a) * math.cos(theta), math.sin(a) * math.sin(theta), math.cos(a))
        t = frame(b, c_deg, machine)[0]
        assert max(abs(x - y) for x, y in zip(t, generatrix)) < 1e-12, "the tool axis is not the generatrix"
        return theta

    steps = int(round(360 / step_deg))
    p = tip(azimuth(0.0))
    lines += [f"G0 X{fmt(p[0])} Y{fmt(p[1])} Z{fmt(SAFE)} B{fmt(b_deg)} C0.0000",
              f"G1 X{fmt(p[0])} Y{fmt(p[1])} Z{fmt(p[2])} F{PLUNGE:.0f}"]
    for k in range(1, steps + 1):
        theta = azimuth(k * step_deg)
        p = tip(theta)
        lines.append(f"G1 X{fmt(p[0])} Y{fmt(p[1])} Z{fmt(p[2])} C{k * step_deg:.4f}" + (f" F{FEED:.0f}" if k == 1 else ""))
    g = frame(b_deg, 360.0, machine)[0]
    up = add(p, scale(SAFE, g))
    lines.append(f"G0 X{fmt(up[0])} Y{fmt(up[1])} Z{fmt(up[2])}")

    points = []
    for ix in range(-floor, floor + 1) if floor else ():
        for iy in range(-floor, floor + 1):
            x, y = ix * (reach - 3) / floor, iy * (reach - 3) / floor
            if math.hypot(x, y) > reach - 3:
                continue
            assert any(abs(y - row) <= RADIUS and lo - RADIUS <= x <= hi + RADIUS for row, lo, hi in passes)
            points.append((prefix + "FL", (cx + x, cy + y, bottom), (0.0, 0.0, 1.0)))
    for h in (heights or (3.0, depth / 2, depth - 3.0)):
        for k in range(per_ring):
            theta = 2 * math.pi * (k + 0.5) / per_ring
            c, s_ = math.cos(theta), math.sin(theta)
            r_at = floor_radius + h * math.tan(a)
            normal = (-math.cos(a) * c, -math.cos(a) * s_, math.sin(a))
            assert h / math.cos(a) < 25  # within the flute length above the tip
            points.append((prefix + "WALL", (cx + r_at * c, cy + r_at * s_, bottom + h), normal))
    return lines, points



def write_drafted_pocket(name, title, tilt_deg, half_u, half_v, corner, depth, centre, machine="bc_head",
                         step_deg=0.2, slot=None, pockets=(), rings=(), wall_heights=None, floor_grid=(5, 3)):
    """A pocket with drafted walls: its foot a rectangle 2 half_u x 2 half_v with corners of
    radius `corner` (above the tool's radius), round `centre` (x, y in the part frame), every
    wall tilted outward by `tilt_deg` (straight walls are planes, corners are cones). The floor
    by a raster of the vertical tool (B0 C0); the walls by one swarf pass of the tool's side
    lying on them, counter-clockwise, the tool axis along the wall's line of steepest slope:
    B and C from swarf_pose (C = the wall's azimuth + 15 deg on bc_head, 0 -> 360 once round).
    Along a straight wall C stands and the linear axes carry the tool along it; round a
    corner C turns 90 deg. The tip sits r off the wall along its normal, its flat end's lowest
    point on the wall's foot (as in write_cone). Its plan: the floor on a (2 gx + 1) x (2 gy + 1)
    grid 8 mm inside the walls' feet (`floor_grid` = (gx, gy)), the walls at `wall_heights`
    above the floor (default 3 mm, half the depth and depth - 3 mm), 36 points round each.
    Then, on the same part: the leaning slot (`slot`, cut_leaning_slot), the 3+2 pockets
    (`pockets`, cut_pocket's arguments) and the swarf rings (`rings`: conical pockets,
    cut_cone's (tilt, floor radius, depth, centre, heights, points per height), their walls
    measured, not their floors)."""
    a = math.radians(tilt_deg)
    cx, cy = centre
    bottom = -depth
    assert corner > RADIUS / math.cos(a), "the tool's side would not fit the corners"
    su, sv = half_u - corner, half_v - corner  # the corners' centres at (+-su, +-sv)
    b_deg, theta0 = swarf_pose(tilt_deg, 0.0, machine)
    theta0 %= 360.0

    # The foot contour, counter-clockwise from (half_u, -sv): (kind, length, ...) elements.
    elements = []
    for q in range(4):
        phi = 90.0 * q  # outward normal's azimuth along the straight wall
        n = (math.cos(math.radians(phi)), math.sin(math.radians(phi)))
        along = (-n[1], n[0])
        half_len = sv if q % 2 == 0 else su
        reach = half_u if q % 2 == 0 else half_v
        start = (reach * n[0] - half_len * along[0], reach * n[1] - half_len * along[1])
        elements.append(("wall", 2 * half_len, phi, start, along))
        cc = ((su if q in (0, 3) else -su), (sv if q in (0, 1) else -sv))
        elements.append(("corner", corner * math.pi / 2, phi, cc))
    perimeter = sum(e[1] for e in elements)

    def foot_at(s_mm):
        """Foot point and outward normal azimuth (deg) at arc length s from (half_u, -sv)."""
        s_mm %= perimeter
        for e in elements:
            if s_mm <= e[1] + 1e-12:
                if e[0] == "wall":
                    _, _, phi, start, along = e
                    return (start[0] + s_mm * along[0], start[1] + s_mm * along[1]), phi
                _, _, phi0, cc = e
                phi = phi0 + math.degrees(s_mm / corner)
                return (cc[0] + corner * math.cos(math.radians(phi)), cc[1] + corner * math.sin(math.radians(phi))), phi
            s_mm -= e[1]
        raise AssertionError(s_mm)

    def inward(phi):  # wall normal at a foot of outward azimuth phi, into the pocket
        c, s_ = math.cos(math.radians(phi)), math.sin(math.radians(phi))
        return (-math.cos(a) * c, -math.cos(a) * s_, math.sin(a))

    def tip(foot, phi):
        return add((cx + foot[0], cy + foot[1], bottom), scale(RADIUS, inward(phi)))

    def check_axis(c_deg, phi):
        b, theta = swarf_pose(tilt_deg, c_deg, machine)
        assert abs((theta - phi + 180.0) % 360.0 - 180.0) < 1e-9, "C does not face the tool to the wall"
        t = frame(b, c_deg, machine)[0]
        c, s_ = math.cos(math.radians(phi)), math.sin(math.radians(phi))
        generatrix = (math.sin(a) * c, math.sin(a) * s_, math.cos(a))
        assert max(abs(x - y) for x, y in zip(t, generatrix)) < 1e-12, "the tool axis is not the wall's slope"

    lines = ["%", f"({title})",
             "(tcp world: X Y Z are the tool tip in the part frame; written by make_parts_5axis.py)",
             "G21 G90 G17 G40 G49 G54 G94", "T1 M6", "G43 H1", "S8000 M3",
             f"G0 X{fmt(cx)} Y{fmt(cy)} Z{fmt(SAFE)} B0.0000 C0.0000"]
    # Floor raster (tool vertical): rows along x inside the tool centre's reach, the foot
    # inset by the radius (a rounded rectangle with corners corner - r).
    def half_width(y, inset):
        r_in = corner - inset
        if abs(y) <= sv:
            return half_u - inset
        return su + math.sqrt(max(r_in * r_in - (abs(y) - sv) ** 2, 0.0))
    reach_v = half_v - RADIUS - 1.0
    rows, y = [], -reach_v
    while y < reach_v - 1e-9:
        rows.append(y)
        y += STEPOVER
    rows.append(reach_v)
    passes = []
    for k, y in enumerate(rows):
        half = half_width(y, RADIUS) - 1.0
        x0, x1 = (-half, half) if k % 2 == 0 else (half, -half)
        if k == 0:
            lines += [f"G0 X{fmt(cx + x0)} Y{fmt(cy + y)} Z{fmt(2.0)}", f"G1 Z{fmt(bottom)} F{PLUNGE:.0f}"]
        else:
            lines.append(f"G1 X{fmt(cx + x0)} Y{fmt(cy + y)}")
        lines.append(f"G1 X{fmt(cx + x1)} Y{fmt(cy + y)} F{FEED:.0f}")
        passes.append((y, -half, half))
    lines.append(f"G0 Z{fmt(SAFE)}")

    # The swarf pass: from the foot point whose azimuth is theta0 (C = 0) round once to C = 360.
    quarter = int(theta0 // 90)
    assert theta0 - 90 * quarter > 1e-6, "C = 0 should face a corner, not a straight wall"
    s0 = sum(e[1] for e in elements[:2 * quarter + 1]) + corner * math.radians(theta0 - 90 * quarter)
    foot, phi = foot_at(s0)
    check_axis(0.0, phi)
    p = tip(foot, phi)
    lines += [f"G0 X{fmt(p[0])} Y{fmt(p[1])} Z{fmt(SAFE)} B{fmt(b_deg)} C0.0000",
              f"G1 X{fmt(p[0])} Y{fmt(p[1])} Z{fmt(p[2])} F{PLUNGE:.0f}"]
    first = True
    s_mm, c_deg = s0, 0.0
    while s_mm < s0 + perimeter - 1e-9:
        here = s_mm % perimeter
        # the element under s (the last one if s is at its end) and where it ends
        acc = 0.0
        for e in elements:
            if here < acc + e[1] - 1e-9:
                break
            acc += e[1]
        end_of_element = s_mm + (acc + e[1] - here)
        if e[0] == "wall":
            s_mm = min(end_of_element, s0 + perimeter)
            foot, phi = foot_at(s_mm)
        else:
            s_mm = min(s_mm + corner * math.radians(step_deg), end_of_element, s0 + perimeter)
            foot, phi = foot_at(s_mm)
            c_deg = (phi - theta0) % 360.0
            if s_mm >= s0 + perimeter - 1e-9:
                c_deg = 360.0
        check_axis(c_deg, phi)
        p = tip(foot, phi)
        lines.append(f"G1 X{fmt(p[0])} Y{fmt(p[1])} Z{fmt(p[2])} C{c_deg:.4f}" + (f" F{FEED:.0f}" if first else ""))
        first = False
    assert c_deg == 360.0
    up = add(p, scale(SAFE, frame(b_deg, 360.0, machine)[0]))
    lines.append(f"G0 X{fmt(up[0])} Y{fmt(up[1])} Z{fmt(up[2])}")
    slot_points = []
    if slot is not None:
        lines.append(f"G0 Z{fmt(up[2] + SAFE)}")
        lines += cut_leaning_slot(slot, machine, slot_points)
    for k, pocket in enumerate(pockets):  # 3+2 pockets (cut_pocket's arguments), faces named P1FL, P1WU+, ...
        cut, more = cut_pocket(*pocket, machine, prefix=f"P{k + 1}")
        lines += cut
        slot_points += more
    for k, (tilt, radius, ring_depth, at, heights, per_ring) in enumerate(rings):  # faces K1WALL, K2WALL, ...
        cut, more = cut_cone(tilt, radius, ring_depth, step_deg, machine, at, heights, per_ring, floor=0,
                             prefix=f"K{k + 1}")
        lines += cut
        slot_points += more
    lines += ["M5", "M2", "%"]
    with open(os.path.join(HERE, name + ".ngc"), "w") as f:
        f.write("\n".join(lines) + "\n")

    # CMM plan (the docstring): the walls' points equally spaced along the contour.
    points = []
    gx, gy = floor_grid
    for ix in range(-gx, gx + 1):
        for iy in range(-gy, gy + 1):
            x, y = ix * (half_u - 8) / gx, iy * (half_v - 8) / gy
            if abs(x) > half_width(y, 8.0) + 1e-9:
                continue
            assert any(abs(y - row) <= RADIUS and lo - RADIUS <= x <= hi + RADIUS for row, lo, hi in passes)
            points.append(("FL", (cx + x, cy + y, bottom), (0.0, 0.0, 1.0)))
    for h in (wall_heights or (3.0, depth / 2, depth - 3.0)):
        assert h / math.cos(a) < 25  # within the flute length above the tip
        for k in range(36):
            foot, phi = foot_at((k + 0.5) * perimeter / 36)
            c, s_ = math.cos(math.radians(phi)), math.sin(math.radians(phi))
            out = h * math.tan(a)
            points.append(("WALL", (cx + foot[0] + out * c, cy + foot[1] + out * s_, bottom + h), inward(phi)))
    return write_plan(name, title, "FL: floor (normal +Z); WALL: the drafted walls at "
                      f"{len(wall_heights or (0, 0, 0))} heights, normals into the pocket"
                      + ("; SL: the leaning slot's walls at two heights" if slot else "")
                      + ("; P1FL, P1WU+, ...: the 3+2 pockets' floors and walls" if pockets else "")
                      + ("; K1WALL, ...: the swarf rings' walls" if rings else ""), points + slot_points)


def cut_leaning_slot(slot, machine, points):
    """A straight slot along the part's x with vertical walls, cut by the tool's side leaning
    along the slot (one pass along each wall, C and B held): with bc_head at C = 15 (the
    fixture's turn undone) the machine's axes are the part's, the head tilts the tool in the
    XZ plane, so the walls (normals +-y) contain the tool axis and the side touches them
    along a line; they face the machine's y, which a swarf wall on this machine never does.
    The tilted flat end leaves no flat floor (not measured). `slot`: (B, y of the slot's
    middle, half its length, width, depth of the tip). Returns the program lines; the plan's
    wall points (2 heights above the tip, 10 mm clear of the ends) go to `points`."""
    b_deg, y_mid, half_len, width, tip_depth = slot
    c_deg = BC_HEAD_FIXTURE_DEG
    assert machine == "bc_head"
    t = frame(b_deg, c_deg, machine)[0]
    assert abs(t[1]) < 1e-12, "the tool does not lie in the slot's walls"
    lines = []
    x0, x1 = -half_len, half_len
    for k, side in enumerate((-1, 1)):
        y = y_mid + side * (width / 2 - RADIUS)  # the pass touching the wall at y_mid + side * width / 2
        a_from, a_to = (x0, x1) if k == 0 else (x1, x0)
        lines += [f"G0 X{fmt(a_from)} Y{fmt(y)} Z{fmt(SAFE)} B{fmt(b_deg)} C{fmt(c_deg)}",
                  f"G1 Z{fmt(-tip_depth)} F{PLUNGE:.0f}", f"G1 X{fmt(a_to)} F{FEED:.0f}", f"G0 Z{fmt(SAFE)}"]
        for h in (tip_depth - 2.0, tip_depth - 4.5):
            assert h < tip_depth - 1.0 and h > 0.5
            n = 8
            for i in range(n):
                x = -half_len + 10 + i * (2 * half_len - 20) / (n - 1)
                points.append(("SL" + ("+" if side > 0 else "-"), (x, y_mid + side * width / 2, -h),
                               (0.0, -float(side), 0.0)))
    return lines

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
    print(write_drafted_pocket("head_draft_a", "5-axis swarf on bc_head, head B35 and table C: a 70 x 50 pocket, corners "
                               "R15, walls drafted 35 deg, 15 deep, C turning 360 deg, and its floor; a slot cut by the "
                               "tool leaning 20 deg along it; a 3+2 pocket at B35 C105; a swarf ring of 20 deg at X-50 "
                               "Y-25", 35, 35, 25, 15, 15, (20.0, 10.0), slot=(20.0, -50.0, 40.0, 14.0, 6.0),
                               pockets=[(35, 105, (-65.0, 10.0, 0.0), 12, 12, 5)],
                               rings=[(20, 12, 8, (-50.0, -25.0), (3.0, 5.0), 36)], wall_heights=(3.0, 12.0),
                               floor_grid=(7, 4)))
    print(write_cone("head_cone_b", "5-axis swarf on bc_head, head B22 and table C: a conical pocket, wall tilted 22 deg, "
                     "centred at X-30 Y-25, C turning 360 deg, and its floor", 22, 24, 12, machine="bc_head",
                     centre=(-30.0, -25.0)))
