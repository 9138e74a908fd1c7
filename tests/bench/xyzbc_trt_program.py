#!/usr/bin/env python3
"""Rewrites an MC-300 program written for world=axes (its X Y Z B C words are the nominal
joints, Z without the G43 tool length) for LinuxCNC's xyzbc-trt-kins, whose world is the tool
tip in the rotating table's frame: every programmed point is the xyzbc-trt-kins forward
kinematics (trtfuncs.c, LinuxCNC 2.9) of the same joints, so both runs move the joints through
the same points. servo_cost.sh compares the two kinematics on the same joint motion.

    xyzbc_trt_program.py IN.ngc OUT.ngc --rot-point X Y Z [--offset DX DZ] [--tool-offset T]

The pivot values must be the ones set on the xyzbc-trt-kins pins (kins/configs/mc300/
xyzbc_trt.hal); --tool-offset is the G43 offset active while the points run (mc300.tbl's
tool 1: 100 mm). Lines are read as this repository's programs write them: one block per line,
plain numbers, modal X Y Z B C (each rewritten line carries all five words).
"""
import argparse
import math
import re

WORD = re.compile(r"([XYZBC])\s*(-?\d+(?:\.\d*)?|-?\.\d+)", re.IGNORECASE)


def forward(j, rot, dx, dz):
    """xyzbcKinematicsForward (trtfuncs.c), dz already including the tool offset."""
    xr, yr, zr = rot
    x, y, z, b, c = j
    b, c = math.radians(b), math.radians(c)
    px = (math.cos(c) * math.cos(b) * (x - dx - xr) + math.sin(c) * (y - yr)
          - math.cos(c) * math.sin(b) * (z - dz - zr) + math.cos(c) * dx + xr)
    py = (-math.sin(c) * math.cos(b) * (x - dx - xr) + math.cos(c) * (y - yr)
          + math.sin(c) * math.sin(b) * (z - dz - zr) - math.sin(c) * dx + yr)
    pz = math.sin(b) * (x - dx - xr) + math.cos(b) * (z - dz - zr) + dz + zr
    return px, py, pz


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("input")
    p.add_argument("output")
    p.add_argument("--rot-point", nargs=3, type=float, required=True)
    p.add_argument("--offset", nargs=2, type=float, default=[0.0, 0.0])
    p.add_argument("--tool-offset", type=float, default=0.0)
    a = p.parse_args()
    dx, dz = a.offset[0], a.offset[1] + a.tool_offset
    modal = {"X": 0.0, "Y": 0.0, "Z": 0.0, "B": 0.0, "C": 0.0}
    out = []
    for line in open(a.input):
        text = line.split(";")[0]
        if text.lstrip().startswith("(") or not WORD.search(text) or re.search(r"[TH]\d", text, re.I):
            out.append(line)
            continue
        for letter, value in WORD.findall(text):
            modal[letter.upper()] = float(value)
        # LinuxCNC's world Z is the program's plus the tool offset (G43).
        joints = (modal["X"], modal["Y"], modal["Z"] + a.tool_offset, modal["B"], modal["C"])
        x, y, z = forward(joints, a.rot_point, dx, dz)
        rest = WORD.sub("", text).strip()
        words = "X%.6f Y%.6f Z%.6f B%.6f C%.6f" % (x, y, z - a.tool_offset, modal["B"], modal["C"])
        out.append((rest + " " + words).strip() + "\n")
    open(a.output, "w").writelines(out)


if __name__ == "__main__":
    main()
