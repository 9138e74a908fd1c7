#!/usr/bin/env python3
"""Writes the test parts of the self-tuning proof (tests/preproc/selftune_test.cpp) for mill3
(G54 from ../mill3.var, T1 = 10 mm flat end mill from ../mill3.tbl): each part's program and
its CMM plan (nominal points on the cut surfaces, unit normals out of the material, in the
part frame = program coordinates: part zero at the table centre, 60 mm above the table top;
stock z -60..0, x -220..220, y -130..130).

  part A: a 200 x 120 block centred on the part zero: top face-milled at z 0 (raster along X,
          stepover 8), walls side-milled by climb milling (clockwise, corner arcs R5 about the
          block corners) in two passes, tip at z -10 then -20, leaving a floor ring at z -20.
  part B: a 100 mm boss centred at (40, 20): top face-milled at z -5 (raster over the 110 x 110
          square around it, stepover 8), wall cut by full circles G2 (tool centre on r 55) at
          tip z -15 and -25; and a straight wall y = -80, x -75..75, facing -y: a slot, tool
          centre on y = -85 from x 75 to -75 (climb on that wall), tip z -15 then -25.

Only G0/G1/G2/G3 (IJ), no cutter compensation, canned cycles, O-words or G92. Before writing,
checks (assertions) read the programs back as written: every CMM point lies 5 mm (the tool
radius) from the centre path of a cutting move below it (walls) or under the flat bottom of a
cut at its height (top, floor); no cut removes it; material behind it, none in front; the
moves stay within mill3's travel; rapids only above the stock.

Run: python3 make_parts.py (writes part_a.ngc, part_a_points.csv, part_b.ngc,
part_b_points.csv beside itself). Standard library only, deterministic."""
import math
import os
import re

HERE = os.path.dirname(os.path.abspath(__file__))
PROGRAMS = os.path.dirname(HERE)
MACHINE = os.path.join(PROGRAMS, "..", "..", "machines", "data", "mill3.toml")

SAFE = 50.0     # retract height
CLEAR = 2.0     # rapid down to here, feed below (stock top: z 0)
PLUNGE = 300.0  # feed of the plunges
FEED = 1200.0   # feed of the cuts
STEP = 8.0      # stepover of the face milling
FLUTE = 30.0    # cutting length of the tool (as the virtual shop's machined surface takes it)
STOCK = ((-220.0, 220.0), (-130.0, 130.0), (-60.0, 0.0))
TOL = 1e-4      # mm: points are written with 4 decimals (a point on the cylinder is within 0.07 um)


# ---- set-up: G54, tool, travel --------------------------------------------------------------
def read_setup():
    params = {}
    with open(os.path.join(PROGRAMS, "mill3.var")) as f:
        for line in f:
            if line.split():
                number, value = line.split()[:2]
                params[int(number)] = float(value)
    g54 = (params[5221], params[5222], params[5223])
    with open(os.path.join(PROGRAMS, "mill3.tbl")) as f:
        for line in f:
            words = line.split(";")[0].split()
            if words and words[0] == "T1":
                w = {x[0]: float(x[1:]) for x in words[1:]}
                length, radius = w["Z"], w["D"] / 2
    try:
        import tomllib  # Python 3.11+
        with open(MACHINE, "rb") as f:
            toml = tomllib.load(f)
        travel = {a["axis"]: tuple(a["travel_mm"]) for a in toml["workpiece_chain"] + toml["tool_chain"]}
    except ImportError:
        travel = {"X": (0, 500), "Y": (0, 300), "Z": (-300, 0)}  # machines/data/mill3.toml
    return g54, length, radius, travel


G54, LENGTH, R, TRAVEL = read_setup()
assert R == 5.0 and LENGTH == 100.0, "T1 in mill3.tbl should be the 10 mm end mill, 100 mm long"


# ---- writing ------------------------------------------------------------------------------
def g(v):
    """A G-code number: 4 decimals at most, a decimal point always (110., -52., 0.5)."""
    s = f"{v:.4f}".rstrip("0")
    return "0." if s == "-0." else s


def c(v, decimals=4):
    """A CSV number: up to `decimals` decimals, no trailing zeros (100, -5, 89.2404)."""
    s = f"{v:.{decimals}f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def header(title, notes):
    return (["%", f"({title})"] + [f"({n})" for n in notes] +
            ["(mill3: G54 from mill3.var, T1 10 mm flat end mill from mill3.tbl)",
             "G21 G90 G17 G40 G49 G80 G94 G91.1", "G54", "T1 M6", "S8000 M3", f"G0 G43 H1 Z{g(SAFE)}"])


def footer():
    return ["M5", "M30", "%"]


def enter(x, y, z):
    """Rapid above (x, y), plunge to z; the next cut sets the feed."""
    return [f"G0 X{g(x)} Y{g(y)}", f"G0 Z{g(CLEAR)}", f"G1 Z{g(z)} F{g(PLUNGE)}"]


def raster(x0, x1, y0, y1, z):
    """Face milling, zig-zag lines along X from y0 to y1 (stepover STEP, y1 - y0 a multiple)."""
    n = round((y1 - y0) / STEP)
    assert abs(y0 + n * STEP - y1) < 1e-9
    lines = enter(x0, y0, z)
    for k in range(n + 1):
        if k:
            lines.append(f"G1 Y{g(y0 + k * STEP)}")
        lines.append(f"G1 X{g(x1 if k % 2 == 0 else x0)}" + (f" F{g(FEED)}" if k == 0 else ""))
    return lines + [f"G0 Z{g(SAFE)}"]


def write(name, program, points, notes):
    ids = set()
    rows = []
    for pid, p, n in points:
        assert pid not in ids, pid
        ids.add(pid)
        assert abs(math.sqrt(sum(v * v for v in n)) - 1) < 1e-12, pid
        rows.append(",".join([pid] + [c(v) for v in p] + [c(v, 6) for v in n]))
    csv = [f"# {n}" for n in notes] + ["id,x[mm],y[mm],z[mm],i,j,k"] + rows
    check(name, program, csv)
    with open(os.path.join(HERE, name + ".ngc"), "w") as out:
        out.write("\n".join(program) + "\n")
    with open(os.path.join(HERE, name + "_points.csv"), "w") as out:
        out.write("\n".join(csv) + "\n")


# ---- part A -------------------------------------------------------------------------------
def part_a():
    hx, hy = 100.0, 60.0  # block |x| <= 100, |y| <= 60
    ox, oy = hx + R, hy + R  # tool centre path of the walls
    prog = header("self-tuning test part A: 200 x 120 block, top z 0, walls to z -20, floor ring z -20",
                  ["face the top: raster along X at z 0, stepover 8, tool centre x -110..110, y -60..60"])
    prog += raster(-hx - 2 * R, hx + 2 * R, -hy, hy, 0.0)
    for z in (-10.0, -20.0):
        prog.append(f"(walls: climb, clockwise, tool centre 5 outside, corner arcs R5 about the corners; tip z {c(z)})")
        prog += enter(-ox, -hy, z)  # start at a corner, where nothing is measured
        prog += [f"G1 Y{g(hy)} F{g(FEED)}", f"G2 X{g(-hx)} Y{g(oy)} I{g(R)} J0.",
                 f"G1 X{g(hx)}", f"G2 X{g(ox)} Y{g(hy)} I0. J{g(-R)}",
                 f"G1 Y{g(-hy)}", f"G2 X{g(hx)} Y{g(-oy)} I{g(-R)} J0.",
                 f"G1 X{g(-hx)}", f"G2 X{g(-ox)} Y{g(-hy)} I0. J{g(R)}",
                 f"G0 Z{g(SAFE)}"]
    prog += footer()

    def wall(face, along, at, normal):  # along the wall, at z -5 (001..) then -15
        return [(f"A-{face}-{k + 1:03d}", (*at(s), z), normal)
                for k, (z, s) in enumerate((z, s) for z in (-5.0, -15.0) for s in along)]

    def floor(face, along, at):
        return [(f"A-{face}-{k + 1:03d}", (*at(s), -20.0), (0, 0, 1)) for k, s in enumerate(along)]
    short, long_ = range(-50, 51, 10), range(-90, 91, 10)  # 10 mm from the corners
    pts = wall("W+X", short, lambda s: (hx, s), (1, 0, 0))
    pts += wall("W+Y", long_, lambda s: (s, hy), (0, 1, 0))
    pts += wall("W-X", short, lambda s: (-hx, s), (-1, 0, 0))
    pts += wall("W-Y", long_, lambda s: (s, -hy), (0, -1, 0))
    top = [(x, y) for y in range(-50, 51, 20) for x in range(-90, 91, 20)]  # 5 mm inside the edges
    pts += [(f"A-TOP-{k + 1:03d}", (x, y, 0.0), (0, 0, 1)) for k, (x, y) in enumerate(top)]
    d = R / 2  # the floor ring: 2.5 mm outside the walls (under the middle of the tool), 20 mm from the corners
    short, long_ = range(-40, 41, 20), range(-80, 81, 20)
    pts += floor("FL+X", short, lambda s: (hx + d, s))
    pts += floor("FL+Y", long_, lambda s: (s, hy + d))
    pts += floor("FL-X", short, lambda s: (-hx - d, s))
    pts += floor("FL-Y", long_, lambda s: (s, -hy - d))
    write("part_a", prog, pts,
          ["self-tuning test part A (make_parts.py): 200 x 120 block centred on the part zero, mill3, G54, T1",
           "W+X W+Y W-X W-Y: walls x = +-100, y = +-60, every 10 mm (10 mm from the corners) at z -5 (001..) then -15",
           "TOP: top face z 0, 20 mm grid 5 mm inside the edges; FL+X FL+Y FL-X FL-Y: floor ring z -20, 2.5 mm outside the walls",
           "nominal points on the cut surfaces (part frame = G54), unit normals out of the material"])


# ---- part B -------------------------------------------------------------------------------
def part_b():
    cx, cy, rb = 40.0, 20.0, 50.0  # boss
    rc = rb + R  # tool centre circle
    wy, wx = -80.0, 75.0  # straight wall y = -80, x -75..75
    prog = header("self-tuning test part B: 100 mm boss at X40 Y20, top z -5; straight wall y -80, x -75..75",
                  ["face the boss top: raster along X at z -5, stepover 8, tool centre x -15..95, y -36..76"])
    prog += raster(cx - 55, cx + 55, cy - 7 * STEP, cy + 7 * STEP, -5.0)
    sx, sy = cx + 33.0, cy + 44.0  # start of the circles: on r 55 (33-44-55), where nothing is measured
    assert math.hypot(sx - cx, sy - cy) == rc
    for z in (-15.0, -25.0):
        prog.append(f"(boss wall: full circle G2, climb, tool centre on r 55 about X40 Y20; tip z {c(z)})")
        prog += enter(sx, sy, z)
        prog += [f"G2 X{g(sx)} Y{g(sy)} I{g(cx - sx)} J{g(cy - sy)} F{g(FEED)}", f"G0 Z{g(SAFE)}"]
    for z in (-15.0, -25.0):
        prog.append(f"(straight wall y -80 facing -y: slot, tool centre on y -85 from x 75 to -75, climb on the wall; tip z {c(z)})")
        prog += enter(wx, wy - R, z)
        prog += [f"G1 X{g(-wx)} F{g(FEED)}", f"G0 Z{g(SAFE)}"]
    prog += footer()

    pts = []
    cyl = [(z, a) for z in (-10.0, -20.0) for a in range(0, 360, 10)]
    pts += [(f"B-CYL-{k + 1:03d}",
             (cx + rb * math.cos(math.radians(a)), cy + rb * math.sin(math.radians(a)), z),
             (math.cos(math.radians(a)), math.sin(math.radians(a)), 0.0)) for k, (z, a) in enumerate(cyl)]
    top = [(dx, dy) for dy in range(-40, 41, 20) for dx in range(-40, 41, 20) if math.hypot(dx, dy) <= 45]
    pts += [(f"B-TOP-{k + 1:03d}", (cx + dx, cy + dy, -5.0), (0, 0, 1)) for k, (dx, dy) in enumerate(top)]
    wall = [(z, x) for z in (-10.0, -20.0) for x in range(-70, 71, 10)]
    pts += [(f"B-W-Y-{k + 1:03d}", (x, wy, z), (0, -1, 0)) for k, (z, x) in enumerate(wall)]
    write("part_b", prog, pts,
          ["self-tuning test part B (make_parts.py): 100 mm boss at (40, 20) and a straight wall, mill3, G54, T1",
           "CYL: boss wall r 50 every 10 deg from +x, at z -10 (001..036) then -20; TOP: boss top z -5, 20 mm grid, r <= 45",
           "W-Y: straight wall y = -80 (a slot's side), x -70..70 every 10 mm at z -10 (001..015) then -20",
           "nominal points on the cut surfaces (part frame = G54), unit normals out of the material"])


# ---- checks: the programs as written, the points as written -------------------------------
ALLOWED_G = {"0", "1", "2", "3", "17", "21", "40", "43", "49", "54", "80", "90", "91.1", "94"}
ALLOWED_M = {"3", "5", "6", "30"}


def parse(program):
    """Moves of our G-code subset: dicts with kind G0/G1/G2/G3, a, b (x, y, z) and arc centre."""
    moves, pos, mode = [], [None, None, None], None
    for text in program:
        assert all("(" not in comment for comment in re.findall(r"\(([^)]*)\)", text)), f"nested comment: {text!r}"
        code = re.sub(r"\([^)]*\)", "", text).split(";")[0].strip().upper()
        assert "(" not in code and ")" not in code, text
        if code in ("", "%"):
            continue
        words = re.findall(r"([A-Z])\s*([-+]?(?:\d+\.?\d*|\.\d+))", code)
        assert "".join(l + v for l, v in words) == code.replace(" ", ""), f"unread words in {text!r}"
        w = {}
        for letter, value in words:
            if letter == "G":
                number = f"{float(value):g}"
                assert number in ALLOWED_G, f"G{value} in {text!r}"
                if number in ("0", "1", "2", "3"):
                    mode = int(number)
            elif letter == "M":
                assert value in ALLOWED_M, f"M{value} in {text!r}"
            else:
                assert letter in "XYZIJFSTHN", f"{letter} in {text!r}"
                w[letter] = float(value)
        if not any(a in w for a in "XYZ"):
            continue
        end = [w.get("XYZ"[i], pos[i]) for i in range(3)]
        if None not in pos:
            m = {"kind": f"G{mode}", "a": tuple(pos), "b": tuple(end), "line": text}
            if mode in (2, 3):
                m["c"] = (pos[0] + w["I"], pos[1] + w["J"])
                r0 = math.hypot(pos[0] - m["c"][0], pos[1] - m["c"][1])
                assert abs(r0 - math.hypot(end[0] - m["c"][0], end[1] - m["c"][1])) < 1e-9, text
                assert pos[2] == end[2], f"helix in {text!r}"
                m["r"], m["a0"] = r0, math.atan2(pos[1] - m["c"][1], pos[0] - m["c"][0])
                a1 = math.atan2(end[1] - m["c"][1], end[0] - m["c"][0])
                sweep = (a1 - m["a0"]) % (2 * math.pi) if mode == 3 else -((m["a0"] - a1) % (2 * math.pi))
                m["sweep"] = sweep if abs(sweep) > 1e-12 else (2 * math.pi if mode == 3 else -2 * math.pi)
            else:
                assert pos[2] == end[2] or pos[:2] == end[:2], f"a straight move is horizontal or vertical: {text!r}"
            moves.append(m)
        pos = end
    return moves


def arc_points(m):
    """The arc's ends and the extreme points it passes (for its extent)."""
    pts = [m["a"], m["b"]]
    for k in range(-8, 9):
        t = k * math.pi / 2
        u = (t - m["a0"]) / m["sweep"]
        if 0 <= u <= 1:
            pts.append((m["c"][0] + m["r"] * math.cos(t), m["c"][1] + m["r"] * math.sin(t), m["a"][2]))
    return pts


def xy_distance(p, m):
    """Distance in xy from p to the move's tool centre path."""
    if m["kind"] in ("G2", "G3"):
        dx, dy = p[0] - m["c"][0], p[1] - m["c"][1]
        rho = math.hypot(dx, dy)
        if rho > 1e-12:
            u = (math.atan2(dy, dx) - m["a0"]) % (2 * math.pi) if m["sweep"] > 0 else (m["a0"] - math.atan2(dy, dx)) % (2 * math.pi)
            if u <= abs(m["sweep"]) + 1e-12:
                return abs(rho - m["r"])
        return min(math.hypot(p[0] - q[0], p[1] - q[1]) for q in (m["a"], m["b"]))
    (ax, ay), (bx, by) = m["a"][:2], m["b"][:2]
    dd = (bx - ax) ** 2 + (by - ay) ** 2
    u = 0.0 if dd == 0 else min(1.0, max(0.0, ((p[0] - ax) * (bx - ax) + (p[1] - ay) * (by - ay)) / dd))
    return math.hypot(p[0] - ax - u * (bx - ax), p[1] - ay - u * (by - ay))


def bottom(m):
    return min(m["a"][2], m["b"][2])


def removed(p, m, margin):
    """p inside the volume the tool swept in m (a flat-end cylinder; the shank above it too),
    by more than `margin` (< 0: or within -margin of it)."""
    return xy_distance(p, m) < R - margin and p[2] > bottom(m) + margin


def check(name, program, csv):
    moves = parse(program)
    cuts = [m for m in moves if m["kind"] != "G0"]

    # Rapids only above the stock (or straight up out of a cut); cuts within the stock.
    for m in moves:
        if m["kind"] == "G0":
            assert m["b"][2] >= CLEAR and (m["a"][:2] == m["b"][:2] or m["a"][2] >= CLEAR), m["line"]
    for m in cuts:
        for q in (arc_points(m) if "c" in m else [m["a"], m["b"]]):
            assert STOCK[0][0] <= q[0] - R and q[0] + R <= STOCK[0][1] and STOCK[1][0] <= q[1] - R and q[1] + R <= STOCK[1][1], m["line"]
        assert bottom(m) > STOCK[2][0], m["line"]

    # Travel: machine = program + G54, the tool length on Z.
    lo, hi = [math.inf] * 3, [-math.inf] * 3
    for m in moves:
        for q in (arc_points(m) if "c" in m else [m["a"], m["b"]]):
            for i in range(3):
                lo[i], hi[i] = min(lo[i], q[i]), max(hi[i], q[i])
    machine_lo = [lo[i] + G54[i] + (LENGTH if i == 2 else 0) for i in range(3)]
    machine_hi = [hi[i] + G54[i] + (LENGTH if i == 2 else 0) for i in range(3)]
    for i, axis in enumerate("XYZ"):
        assert TRAVEL[axis][0] <= machine_lo[i] and machine_hi[i] <= TRAVEL[axis][1], (name, axis, machine_lo[i], machine_hi[i])

    # The points as written.
    rows = [r.split(",") for r in csv if not r.startswith("#")]
    assert rows[0] == ["id", "x[mm]", "y[mm]", "z[mm]", "i", "j", "k"]
    worst, faces = 0.0, {}
    for row in rows[1:]:
        pid, p, n = row[0], tuple(map(float, row[1:4])), tuple(map(float, row[4:7]))
        assert abs(math.sqrt(sum(v * v for v in n)) - 1) < 1e-6, pid
        # No cut removes the point; material just behind it, none just in front.
        assert not any(removed(p, m, TOL) for m in cuts), f"{pid} is cut away"
        behind = tuple(p[i] - 0.01 * n[i] for i in range(3))
        front = tuple(p[i] + 0.01 * n[i] for i in range(3))
        assert not any(removed(behind, m, 0.0) for m in cuts), f"{pid}: no material behind it"
        assert any(removed(front, m, 0.0) for m in cuts), f"{pid}: material in front of it"
        flat = [m for m in cuts if m["a"][2] == m["b"][2]]
        if n[2] == 0:  # wall: the side of a cut below it, tool centre at p + R n, 5 mm from p
            centre = tuple(p[i] + R * n[i] for i in range(3))
            hits = [m for m in flat if TOL < p[2] - bottom(m) <= FLUTE and xy_distance(centre, m) <= TOL]
            assert hits, f"{pid}: no cutting move has its tool centre path 5 mm from it"
            worst = max(worst, min(abs(xy_distance(p, m) - R) for m in hits))
        else:  # top, floor: under the flat bottom of a cut at its height
            assert n == (0.0, 0.0, 1.0), pid
            hits = [m for m in flat if abs(bottom(m) - p[2]) <= 1e-9 and xy_distance(p, m) < R - TOL]
            assert hits, f"{pid}: not under the flat bottom of a cut at z {p[2]}"
        face = pid.rsplit("-", 1)[0]
        faces[face] = faces.get(face, 0) + 1
    print(f"{name}: {len(program)} program lines, {len(rows) - 1} points ({', '.join(f'{f} {k}' for f, k in faces.items())})")
    print(f"  walls 5 mm from a tool centre path to {worst * 1e3:.3f} um; machine X {machine_lo[0]:g}..{machine_hi[0]:g}, "
          f"Y {machine_lo[1]:g}..{machine_hi[1]:g}, Z {machine_lo[2]:g}..{machine_hi[2]:g} mm")


if __name__ == "__main__":
    part_a()
    part_b()
