#!/usr/bin/env python3
"""Acceptance corpus: does `volcomp predistort` on an error-free machine write programs that
mean what the originals mean, as LinuxCNC's own interpreter (rs274 -g) reads them?

For each program: rs274 on the original (not clean: excluded), volcomp predistort (refused:
counted with its reason), rs274 on the output, and the two canonical call streams compared:
the same path within the tolerance, the same feeds (G93: the same time per move), tools, tool
length offsets, spindle, coolant, dwells, messages and stops, in order. Splines and NURBS: rs274
prints only NURBS_FEED; their control points are read from it with gdb and turned into the arcs
LinuxCNC's task canon makes of them (nurbs_feed). See README.md.

    compare_corpus.py --volcomp build/preproc/volcomp [--report out.csv] [--min-equivalent 95]
    compare_corpus.py --volcomp ... --program FILE      (one program, the first difference shown)
    compare_corpus.py --volcomp ... --self-test         (the comparison can fail)
"""
import argparse
import concurrent.futures
import csv
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
MACHINE = os.path.join(HERE, "xyz_perfect.toml")
# A program that moves a rotary axis runs on a machine that has it (at most two rotary axes).
ROTARY_MACHINES = {"A": "xyzac_perfect.toml", "B": "xyzbc_perfect.toml", "C": "xyzac_perfect.toml"}
NCFILES = "/usr/share/linuxcnc/ncfiles"
TOLERANCE_MM = 0.0011          # rs274 prints 4 decimals: 0.05 um rounding per number, plus ours
TOLERANCE_INCH_MM = 0.0001 * 25.4 * 1.1
TOOLS = range(1, 100)          # tool n: length 10 + n mm, diameter 1 + n / 10 mm


def corpus():
    programs = []
    for root in (NCFILES, os.path.join(HERE, "corpus")):
        for folder, _, files in os.walk(root):
            programs += [os.path.join(folder, f) for f in sorted(files) if f.endswith(".ngc")]
    return sorted(programs)


def subroutine_path(program):
    """Folders rs274 and volcomp search for NAME.ngc: the program's own, and the sample
    library folders LinuxCNC's sample configurations put on SUBROUTINE_PATH."""
    folders = [os.path.dirname(program)]
    for extra in ("ngcgui_lib", "ngcgui_lib/utilitysubs", "remap-subroutines", "gcmc_lib"):
        path = os.path.join(NCFILES, extra)
        if os.path.isdir(path) and path not in folders:
            folders.append(path)
    return folders


def write_files(work, program):
    # rs274's machine units are inches (saicanon.cc); volcomp reads the same files with
    # --machine-units inch, as it would on a LinuxCNC set up in inches.
    with open(os.path.join(work, "tools_inch.tbl"), "w") as f:
        for n in TOOLS:
            f.write(f"T{n} P{n} Z{(10 + n) / 25.4!r} D{(1 + n / 10) / 25.4!r}\n")
    zero_var(work)
    with open(os.path.join(work, "rs274.ini"), "w") as f:
        f.write("[RS274NGC]\nSUBROUTINE_PATH = " + ":".join(subroutine_path(program)) + "\n")


def zero_var(work):
    """Zero offsets, G54. rs274 writes the file back on exit (G92 offsets persist): every run
    starts from a fresh one."""
    with open(os.path.join(work, "zero.var"), "w") as f:
        f.write("5220\t1.000000\n")


def run(args, cwd, timeout=60):
    env = dict(os.environ, HOME=cwd)  # rs274 truncates $HOME/.tool.mmap: one HOME per run
    try:
        r = subprocess.run(args, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout,
                           errors="replace")
        return r.returncode, r.stdout, r.stderr
    except subprocess.TimeoutExpired:
        return -1, "", "timeout"


TOOL_CHANGE = re.compile(r"\bM\s*0*(6|61)(?![\d.])", re.I)
LENGTH_WORDS = re.compile(r"G\s*0*(43|49)(?![\d.])(\s*H\s*[-+]?[\d.]+)?", re.I)


def normalized(program, work):
    """The original as a real LinuxCNC session reads it: on a line with a tool change (M6, M61)
    and G43/G49, the standalone rs274 re-reads its position after the change without the new
    length (the next move without Z keeps program Z); LinuxCNC keeps the machine still, as it
    does with G43 on the next line (measured in a session, see README.md). rs274 gets that."""
    lines, changed = [], False
    for line in open(program, errors="replace").read().split("\n"):
        code = re.sub(r"\(.*?\)|;.*", lambda m: " " * len(m.group(0)), line)
        words = LENGTH_WORDS.search(code)
        if TOOL_CHANGE.search(code) and words and not re.search(r"[XYZABC]\s*[-+.\d\[#]", code[words.end():], re.I):
            lines += [line[:words.start()] + line[words.end():], words.group(0)]
            changed = True
        else:
            lines.append(line)
    if not changed:
        return program
    copy = os.path.join(work, "original_" + os.path.basename(program))
    with open(copy, "w") as f:
        f.write("\n".join(lines))
    return copy


def rs274(work, program):
    """rs274's canonical calls for a program, with the control points of its NURBS_FEED calls
    ((text, splines); None if rs274 fails), and all it printed."""
    args = ["rs274", "-i", "rs274.ini", "-t", "tools_inch.tbl", "-v", "zero.var", "-g", program]
    zero_var(work)
    code, out, err = run(args, work)
    text = out + err
    bad = code != 0 or re.search(r"^\s*(error|Error|Unknown|Unable|Cannot|.*failed)", err, re.M)
    if bad:
        return None, text
    splines = []
    if "NURBS_FEED(" in out:
        splines = nurbs_control_points(work, args, out.count("NURBS_FEED("))
        if splines is None:
            return None, text + "\nNURBS_FEED: its control points could not be read (gdb is needed)"
    return (out, splines), text


def nurbs_control_points(work, args, calls):
    """[(order, [(x, y, weight), ...]), ...] of rs274's NURBS_FEED calls, in order (program
    units), read with gdb (nurbs_control_points_gdb.py); None if that fails."""
    if not shutil.which("gdb"):
        return None
    points_file = os.path.join(work, "nurbs_points.txt")
    zero_var(work)
    script = os.path.join(HERE, "nurbs_control_points_gdb.py")
    env = dict(os.environ, HOME=work, NURBS_POINTS=points_file)
    try:
        subprocess.run(["gdb", "-q", "-batch", "-nx", "-x", script, "--args"] + args, cwd=work, env=env,
                       capture_output=True, text=True, timeout=300)
        splines = []
        for line in open(points_file):
            v = line.split()
            values = [float(x) for x in v[1:]]
            splines.append((int(v[0]), [tuple(values[i:i + 3]) for i in range(0, len(values), 3)]))
    except (OSError, ValueError, subprocess.TimeoutExpired):
        return None
    return splines if len(splines) == calls else None


def nurbs_feed(points, order):
    """The moves LinuxCNC 2.9's task canon makes of NURBS_FEED (emccanon.cc NURBS_FEED, biarc,
    arc; nurbs_additional_functions.cc), redone here in its order of operations: the curve
    sampled at 4 points per control point, each pair of samples joined by a biarc. A list of
    ("arc", end, centre, rotation) and ("line", end, None, 0), program units, XY plane."""
    n = len(points) - 1
    knots = [0 if i < order else i - order + 1 if i <= n else n - order + 2 for i in range(n + order + 1)]
    u_max = float(n - order + 2)

    def basis(u):  # N(i, order)(u), i = 0..n: Cox-de Boor, a span holds u with both ends
        level = [1.0 if knots[i] <= u <= knots[i + 1] else 0.0 for i in range(len(knots) - 1)]
        for k in range(2, order + 1):
            nxt = []
            for i in range(len(knots) - k):
                left, right = knots[i + k - 1] - knots[i], knots[i + k] - knots[i + 1]
                if left == 0 and right != 0:
                    nxt.append(((knots[i + k] - u) * level[i + 1]) / right)
                elif right == 0 and left != 0:
                    nxt.append(((u - knots[i]) * level[i]) / left)
                elif left == 0 and right == 0:
                    nxt.append(0.0)
                else:
                    nxt.append(((u - knots[i]) * level[i]) / left + ((knots[i + k] - u) * level[i + 1]) / right)
            level = nxt
        return level

    def point(u):
        b = basis(u)
        den = 0.0
        for i, p in enumerate(points):
            den = den + b[i] * p[2]
        x = y = 0.0
        for i, p in enumerate(points):
            x = x + p[0] * b[i] * p[2] / den
            y = y + p[1] * b[i] * p[2] / den
        return x, y

    def unit(x, y):
        h = math.hypot(x, y)
        return (x / h, y / h) if h != 0 else (x, y)

    def tangent(u):
        lo, hi = max(0.0, u - 1e-5), min(u_max, u + 1e-5)
        (x1, y1), (x3, y3) = point(lo), point(hi)
        return unit((x3 - x1) / (hi - lo), (y3 - y1) / (hi - lo))

    moves = []

    def arc(x0, y0, x1, y1, dx, dy):
        x, y = x1 - x0, y1 - y0
        den = 2 * (y * dx - x * dy)
        if abs(den) > 0.000001:
            r = -(x * x + y * y) / den
            moves.append(("arc", (x1, y1), (x0 + dy * r, y0 - dx * r), 1 if r < 0 else -1))
        else:
            moves.append(("line", (x1, y1), None, 0))

    def biarc(p0, ts, p4, te):
        ts, te = unit(*ts), unit(*te)
        vx, vy = p0[0] - p4[0], p0[1] - p4[1]
        c = vx * vx + vy * vy
        b = 2 * (vx * (ts[0] + te[0]) + vy * (ts[1] + te[1]))
        a = 2 * (ts[0] * te[0] + ts[1] * te[1] - 1)
        discr = b * b - 4 * a * c
        if discr < 0:
            return
        beta1, beta2 = (-b - math.sqrt(discr)) / 2 / a, (-b + math.sqrt(discr)) / 2 / a
        if beta1 > 0 and beta2 > 0:
            return
        beta = beta2 if beta1 < beta2 else beta1
        alpha = beta
        p1 = (p0[0] + alpha * ts[0], p0[1] + alpha * ts[1])
        p3 = (p4[0] - beta * te[0], p4[1] - beta * te[1])
        p2 = ((p1[0] * beta + p3[0] * alpha) / (alpha + beta), (p1[1] * beta + p3[1] * alpha) / (alpha + beta))
        arc(p0[0], p0[1], p2[0], p2[1], *ts)
        arc(p2[0], p2[1], p4[0], p4[1], *unit(p3[0] - p2[0], p3[1] - p2[1]))

    steps = len(points) * 4
    p0, t0 = point(0.0), tangent(0.0)
    for i in range(1, steps + 1):
        u = u_max * i / steps
        p1, t1 = point(u), tangent(u)
        biarc(p0, t0, p1, t1)
        p0, t0 = p1, t1
    return moves


NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def numbers(text):
    return [float(x) for x in NUMBER.findall(text)]


class Canon:
    """The canonical calls of one rs274 run: moves in world coordinates (mm, deg) and the
    other events, in order."""

    def __init__(self, text, splines=()):
        self.moves, self.events = [], []
        units, g5x, g92, rotation, tool = 1.0, [0.0] * 6, [0.0] * 6, 0.0, [0.0, 0.0, 0.0]
        plane, feed, inverse = 17, 0.0, False
        at = [0.0] * 6
        program_at = [0.0] * 6  # the same in program coordinates (mm, deg)
        splines = list(splines)

        def world(p):
            q = [p[i] + g92[i] for i in range(6)]
            a = math.radians(rotation)
            x, y = q[0], q[1]
            q[0], q[1] = math.cos(a) * x - math.sin(a) * y, math.sin(a) * x + math.cos(a) * y
            q = [q[i] + g5x[i] for i in range(6)]
            for i in range(3):
                q[i] += tool[i]
            return q

        def length(values):
            return [v * units for v in values]

        for line in text.splitlines():
            m = re.match(r"\s*\d+\s+N\S*\s+([A-Z_0-9]+)\((.*)\)\s*$", line)
            if not m:
                continue
            call, args = m.group(1), m.group(2)
            v = numbers(args)
            if call == "USE_LENGTH_UNITS":
                units = 25.4 if "INCHES" in args else 1.0
            elif call == "SET_G5X_OFFSET":
                g5x = length(v[1:4]) + v[4:7]
            elif call == "SET_G92_OFFSET":
                g92 = length(v[0:3]) + v[3:6]
            elif call == "SET_XY_ROTATION":
                rotation = v[0]
            elif call == "USE_TOOL_LENGTH_OFFSET":
                tool = length(v[0:3])
                self.events.append(("TOOL_LENGTH", tuple(round(t, 3) for t in tool)))
            elif call == "SELECT_PLANE":
                plane = 18 if "XZ" in args else 19 if "YZ" in args else 17
            elif call == "SET_FEED_RATE":
                feed = v[0] * units
            elif call == "SET_FEED_MODE":
                inverse = len(v) > 1 and v[1] == 1
            elif call in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED"):
                if call == "ARC_FEED":
                    first, second, normal = {17: (0, 1, 2), 18: (2, 0, 1), 19: (1, 2, 0)}[plane]
                    p = [0.0] * 6
                    p[first], p[second], p[normal] = v[0] * units, v[1] * units, v[5] * units
                    p[3:6] = v[6:9]
                    c = list(p)
                    c[first], c[second] = v[2] * units, v[3] * units
                    end, centre = world(p), world(c)
                    move = {"kind": "arc", "end": end, "centre": centre, "plane": (first, second, normal),
                            "rotation": int(v[4])}
                else:
                    p = length(v[0:3]) + v[3:6]
                    end = world(p)
                    move = {"kind": "rapid" if call == "STRAIGHT_TRAVERSE" else "feed", "end": end}
                move["start"] = at
                move["feed"] = feed
                move["inverse"] = inverse
                at, program_at = end, p
                self.moves.append(move)
                self.events.append(("MOVE", len(self.moves) - 1))
            elif call == "NURBS_FEED":  # the task canon's moves (XY plane, the other axes stay)
                order, points = splines.pop(0)
                for kind, xy, centre_xy, turn in nurbs_feed(points, order):
                    p = list(program_at)
                    p[0], p[1] = xy[0] * units, xy[1] * units
                    move = {"kind": "feed" if kind == "line" else "arc", "end": world(p), "start": at,
                            "feed": feed, "inverse": inverse}
                    if kind == "arc":
                        c = list(p)
                        c[0], c[1] = centre_xy[0] * units, centre_xy[1] * units
                        move.update(centre=world(c), plane=(0, 1, 2), rotation=turn)
                    at, program_at = move["end"], p
                    self.moves.append(move)
                    self.events.append(("MOVE", len(self.moves) - 1))
            elif call in ("SELECT_TOOL", "CHANGE_TOOL", "CHANGE_TOOL_NUMBER", "SET_SPINDLE_SPEED", "DWELL"):
                self.events.append((call, tuple(round(x, 4) for x in v)))
            elif call in ("START_SPINDLE_CLOCKWISE", "START_SPINDLE_COUNTERCLOCKWISE", "STOP_SPINDLE_TURNING",
                          "FLOOD_ON", "FLOOD_OFF", "MIST_ON", "MIST_OFF", "PROGRAM_STOP", "OPTIONAL_PROGRAM_STOP",
                          "PROGRAM_END", "PALLET_SHUTTLE"):
                self.events.append((call, ()))
            elif call == "MESSAGE":
                self.events.append((call, (args,)))


def distance(a, b):
    return math.sqrt(sum((a[i] - b[i]) ** 2 for i in range(6)))


def move_length(m):
    if m["kind"] != "arc":
        return math.sqrt(sum((m["end"][i] - m["start"][i]) ** 2 for i in range(3)))
    f, s, n = m["plane"]
    r0 = math.hypot(m["start"][f] - m["centre"][f], m["start"][s] - m["centre"][s])
    a0 = math.atan2(m["start"][s] - m["centre"][s], m["start"][f] - m["centre"][f])
    a1 = math.atan2(m["end"][s] - m["centre"][s], m["end"][f] - m["centre"][f])
    sweep = a1 - a0
    turns = m["rotation"]
    if turns > 0:
        while sweep <= 1e-12:
            sweep += 2 * math.pi
        sweep += 2 * math.pi * (turns - 1)
    else:
        while sweep >= -1e-12:
            sweep -= 2 * math.pi
        sweep -= 2 * math.pi * (-turns - 1)
    return math.hypot(abs(sweep) * r0, m["end"][n] - m["start"][n])


def midpoint(m):
    return [(m["start"][i] + m["end"][i]) / 2 for i in range(6)]


def on_move(point, m, tolerance):
    """Is `point` on the input move (segment, or the arc's circle between its normal ends)?"""
    a, b = m["start"], m["end"]
    if m["kind"] != "arc":
        d = [b[i] - a[i] for i in range(6)]
        dd = sum(x * x for x in d)
        t = 0.0 if dd == 0 else max(0.0, min(1.0, sum((point[i] - a[i]) * d[i] for i in range(6)) / dd))
        return distance(point, [a[i] + t * d[i] for i in range(6)]) <= tolerance
    f, s, n = m["plane"]
    c = m["centre"]
    r0, r1 = math.hypot(a[f] - c[f], a[s] - c[s]), math.hypot(b[f] - c[f], b[s] - c[s])
    r = math.hypot(point[f] - c[f], point[s] - c[s])
    lo, hi = min(a[n], b[n]), max(a[n], b[n])
    return (min(r0, r1) - tolerance <= r <= max(r0, r1) + tolerance and lo - tolerance <= point[n] <= hi + tolerance)


def compare(original, output, tolerance):
    """The first difference of the output's canon from the original's, or None."""
    a, b = Canon(*original), Canon(*output)
    # Motion: each input move's end reached in order; output ends in between lie on it.
    k = 0
    piece_of = {}
    for i, m in enumerate(a.moves):
        if distance(m["start"], m["end"]) <= tolerance and m["kind"] != "arc":
            continue
        time, pieces = 0.0, 0
        while True:
            if k >= len(b.moves):
                return f"input move {i + 1} (to {fmt(m['end'])}) is missing from the output"
            p = b.moves[k]
            zero = distance(p["start"], p["end"]) <= tolerance and p["kind"] != "arc"
            if not zero and not on_move(p["end"], m, tolerance):
                return (f"output move {k + 1} ends at {fmt(p['end'])}, off input move {i + 1} "
                        f"({fmt(m['start'])} -> {fmt(m['end'])})")
            if not zero and (p["kind"] == "rapid") != (m["kind"] == "rapid"):
                return f"output move {k + 1} is a {p['kind']}, input move {i + 1} a {m['kind']}"
            if not zero and p["kind"] == "arc" and (m["kind"] != "arc" or (p["rotation"] > 0) != (m["rotation"] > 0)):
                return f"output move {k + 1} is an arc turning the other way than input move {i + 1}"
            if not zero and p["kind"] == "feed" and not on_move(midpoint(p), m, tolerance):
                return f"output move {k + 1}'s middle {fmt(midpoint(p))} is off input move {i + 1}"
            if not zero:
                piece_of[k] = i
                pieces += 1
                if p["kind"] != "rapid" and p["feed"] > 0:
                    time += move_length(p) / p["feed"]
            k += 1
            if distance(p["end"], m["end"]) <= tolerance and (m["kind"] != "arc" or pieces > 0):
                break
        if m["kind"] != "rapid" and m["feed"] > 0 and pieces:
            expected = move_length(m) / m["feed"]
            if m["inverse"] or pieces > 1:
                if abs(time - expected) > 2e-3 * expected + 1e-9:
                    return f"input move {i + 1} takes {expected:.6g} min, its output {time:.6g} min"
            elif abs(b.moves[k - 1]["feed"] - m["feed"]) > 1e-4 * m["feed"] + 1e-4:
                return f"input move {i + 1} feed {m['feed']:.6g}, output {b.moves[k - 1]['feed']:.6g} mm/min"
    for p in b.moves[k:]:
        if distance(p["start"], p["end"]) > tolerance:
            return f"the output moves on after the input's last move (to {fmt(p['end'])})"
    # The other events, in order (moves left out: their order is checked above).
    ea = [e for e in a.events if e[0] != "MOVE"]
    eb = [e for e in b.events if e[0] != "MOVE"]
    for x, y in zip(ea, eb):
        if x != y:
            return f"event {x} in the input, {y} in the output"
    if len(ea) != len(eb):
        return f"{len(ea)} non-motion events in the input, {len(eb)} in the output"
    return None


def fmt(p):
    return "(" + ", ".join(f"{x:.4f}" for x in p) + ")"


def check(program, volcomp, keep=None):
    """(category, detail) of one program."""
    work = keep or tempfile.mkdtemp(prefix="acceptance-")
    try:
        write_files(work, program)
        original, text = rs274(work, normalized(program, work))
        if original is None:
            last = [l for l in text.splitlines() if l.strip()][-1:] or ["?"]
            return "rs274-error", last[0][:200]
        tolerance = TOLERANCE_INCH_MM if "CANON_UNITS_INCHES" in original[0] else TOLERANCE_MM
        out = os.path.join(work, "out.ngc")
        args = [volcomp, "predistort", MACHINE, program, "-o", out, "--var", "zero.var", "--tool-table",
                "tools_inch.tbl", "--machine-units", "inch", "-q", "--start", "0,0,0"]
        for folder in subroutine_path(program):
            args += ["--subroutine-path", folder]
        zero_var(work)
        code, _, err = run(args, work)
        missing = re.search(r"this machine has no ([ABC]) axis", err)
        if code != 0 and missing:
            args[2] = os.path.join(HERE, ROTARY_MACHINES[missing.group(1)])
            code, _, err = run(args, work)
        if code != 0:
            return "refused", err.strip().splitlines()[-1][:300] if err.strip() else f"exit {code}"
        output, text = rs274(work, out)
        if output is None:
            return "different", "rs274 fails on the output: " + text.strip().splitlines()[-1][:200]
        difference = compare(original, output, tolerance)
        return ("different", difference) if difference else ("equivalent", "")
    finally:
        if not keep:
            shutil.rmtree(work, ignore_errors=True)


def reason_group(detail):
    text = re.sub(r"^.*?:\d+:\d+: error: ", "", detail)
    text = re.sub(r"\d+(\.\d+)?", "N", text)
    return text[:110]


def self_test(volcomp):
    """The comparison must see a 0.01 mm move, a 1 % feed change, an arc turned the other way and
    a spline's end 0.01 mm away."""
    work = tempfile.mkdtemp(prefix="acceptance-self-")
    program = os.path.join(work, "p.ngc")
    with open(program, "w") as f:
        f.write("G21 G90 G54\nG0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X20 Y10\nG2 X30 Y0 I5 J-5\n"
                "G5 X40 Y5 I2 J0 P0 Q-2\nG0 Z5\nM2\n")
    write_files(work, program)
    original, _ = rs274(work, program)
    ok = original is not None and compare(original, original, TOLERANCE_MM) is None
    for old, new in (("X20 Y10", "X20.01 Y10"), ("F300", "F303"), ("G2 X30", "G3 X30"), ("G5 X40", "G5 X40.01")):
        with open(os.path.join(work, "q.ngc"), "w") as f:
            f.write(open(program).read().replace(old, new))
        changed, _ = rs274(work, "q.ngc")
        found = compare(original, changed, TOLERANCE_MM)
        print(f"self-test: {old} -> {new}: {found}")
        ok = ok and found is not None
    shutil.rmtree(work, ignore_errors=True)
    return ok


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--volcomp", required=True)
    parser.add_argument("--program")
    parser.add_argument("--report")
    parser.add_argument("--min-equivalent", type=float, default=0.0)
    parser.add_argument("--self-test", action="store_true")
    args = parser.parse_args()
    volcomp = os.path.abspath(args.volcomp)
    if args.self_test:
        return 0 if self_test(volcomp) else 1
    if args.program:
        work = tempfile.mkdtemp(prefix="acceptance-one-")
        category, detail = check(os.path.abspath(args.program), volcomp, keep=work)
        print(f"{category}: {detail}\n(files in {work})")
        return 0 if category != "different" else 1
    programs = corpus()
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        results = list(pool.map(lambda p: (p, *check(p, volcomp)), programs))
    counts = {}
    for _, category, _ in results:
        counts[category] = counts.get(category, 0) + 1
    clean = len(results) - counts.get("rs274-error", 0)
    share = 100.0 * counts.get("equivalent", 0) / max(clean, 1)
    if args.report:
        with open(args.report, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["program", "category", "detail"])
            w.writerows(results)
    print(f"{len(results)} programs: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
    print(f"equivalent: {counts.get('equivalent', 0)} of {clean} that rs274 runs clean ({share:.1f} %)")
    groups = {}
    for p, category, detail in results:
        if category == "refused":
            groups.setdefault(reason_group(detail), []).append(os.path.basename(p))
    print("refusals by reason:")
    for reason, names in sorted(groups.items(), key=lambda g: -len(g[1])):
        print(f"  {len(names):3d}  {reason}   e.g. {names[0]}")
    different = [(p, d) for p, c, d in results if c == "different"]
    for p, d in different:
        print(f"DIFFERENT {p}: {d}")
    return 1 if different or share < args.min_equivalent else 0


if __name__ == "__main__":
    sys.exit(main())
