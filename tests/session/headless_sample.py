#!/usr/bin/python3
"""Makes a headless copy of a LinuxCNC configuration (one of LinuxCNC's own samples, as a user
has it, or after `volcomp init`'s patch) that runs one program and records a trace, so that a
test can run it without X: the display becomes kins/configs/common/headless_driver.py, what
needs X goes (PYVCP panels, the postgui HAL file that nets them, vismach models loaded with
loadusr and their pins, hal_manualtoolchange), and a sampler records at servo rate the world
command, the joint commands, volkins' gain (0 without volkins), the tool length offset,
motion-controller's time and kinstype.is-1 (the trace's "tcp" column: with sparm=identityfirst,
type 1 is the TCP kinematics, for LinuxCNC's trt modules and for volkins alike).

    headless_sample.py CONFIG_DIR INI RUN_DIR --program FILE [--compensation on|off]

CONFIG_DIR is copied to RUN_DIR (its INI keeps its name); the program path is relative to it.
A signal that only connected a vismach model goes with its `sets`.
"""
import argparse
import os
import re
import shutil
import sys

DRIVER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../kins/configs/common/headless_driver.py")


def headless_lines(lines, coordinates, joints, has_volkins):
    out, section, tool_signal, dropped = [], None, None, set()
    for line in lines:
        stripped = line.strip()
        if stripped.startswith("["):
            if section == "HAL":
                out.extend(trace_lines(coordinates, joints, has_volkins, tool_signal))
            section = stripped.strip("[]")
        key, _, value = stripped.partition("=")
        key, value = key.strip(), value.strip()
        if section == "DISPLAY" and key == "DISPLAY":
            line = "DISPLAY = " + os.path.realpath(DRIVER) + "\n"
        elif (section == "DISPLAY" and key == "PYVCP") or (section == "HAL" and key == "POSTGUI_HALFILE"):
            continue
        elif section == "HAL" and key == "HALCMD" and re.match(r"loadusr\b.*-gui\b", value):
            continue  # a vismach model: needs X
        elif section == "HAL" and key == "HALCMD" and value.startswith("net "):
            value = " ".join(t for t in value.split() if not re.match(r"\S+-gui\.", t))
            if not [t for t in value.split()[2:] if t not in ("<=", "=>")]:
                dropped.add(value.split()[1])  # only the vismach model was on it
                continue
            line = "HALCMD = " + value + "\n"
            m = re.match(r"net\s+(\S+)\s.*\bmotion\.tooloffset\.z\b", value)
            if m:
                tool_signal = m.group(1)
        elif section == "HAL" and key == "HALCMD" and value.startswith("sets ") and value.split()[1] in dropped:
            continue
        elif section == "HAL" and key == "HALFILE" and value.startswith("LIB:basic_sim.tcl"):
            if "-no_use_hal_manualtoolchange" not in value:
                line = "HALFILE = " + value + " -no_use_hal_manualtoolchange\n"
        out.append(line)
    if section == "HAL":
        out.extend(trace_lines(coordinates, joints, has_volkins, tool_signal))
    return out


def trace_lines(coordinates, joints, has_volkins, tool_signal):
    cfg = "f" * (len(coordinates) + joints + 2) + "s" + "b"
    pins = ["axis.%s.pos-cmd" % c.lower() for c in coordinates]
    pins += ["joint.%d.pos-cmd" % j for j in range(joints)]
    lines = ["loadrt sampler depth=8000 cfg=" + cfg, "setp sampler.0.enable 0"]
    n = 0
    for pin in pins:
        lines.append("net :trace-%d %s => sampler.0.pin.%d" % (n, pin, n))
        n += 1
    lines.append("net :trace-gain %s=> sampler.0.pin.%d" % ("volkins.gain " if has_volkins else "", n))
    n += 1
    if tool_signal:
        lines.append("net %s => sampler.0.pin.%d" % (tool_signal, n))
    else:
        lines.append("net :trace-tool motion.tooloffset.z => sampler.0.pin.%d" % n)
    n += 1
    lines.append("net :trace-time motion-controller.time => sampler.0.pin.%d" % n)
    n += 1
    lines.append("net :trace-tcp kinstype.is-1 => sampler.0.pin.%d" % n)
    lines.append("addf sampler.0 servo-thread")
    return ["HALCMD = " + l + "\n" for l in lines]


def ini_value(lines, section, key):
    current = None
    for line in lines:
        s = line.strip()
        if s.startswith("["):
            current = s.strip("[]")
        elif current == section and s.partition("=")[0].strip() == key:
            return s.partition("=")[2].strip()
    raise SystemExit("headless_sample.py: no [%s]%s" % (section, key))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("config_dir")
    p.add_argument("ini")
    p.add_argument("run_dir")
    p.add_argument("--program", required=True)
    p.add_argument("--compensation", default="on")
    a = p.parse_args()
    shutil.rmtree(a.run_dir, ignore_errors=True)
    shutil.copytree(a.config_dir, a.run_dir, symlinks=False)
    ini = os.path.join(a.run_dir, a.ini)
    with open(ini) as f:
        lines = f.readlines()
    coordinates = ini_value(lines, "TRAJ", "COORDINATES").replace(" ", "")
    joints = int(ini_value(lines, "KINS", "JOINTS"))
    has_volkins = ini_value(lines, "KINS", "KINEMATICS").split()[0] == "volkins"
    out = headless_lines(lines, coordinates, joints, has_volkins)
    columns = [c.lower() for c in coordinates] + ["j%d" % j for j in range(joints)]
    columns += ["gain", "tool_length", "controller_time", "tcp"]
    out.append("\n[DRIVER]\nPROGRAM = %s\nCOMPENSATION = %s\nTRACE = trace.csv\nTRACE_COLUMNS = %s\nRESULT = result.txt\n"
               % (a.program, a.compensation, " ".join(columns)))
    with open(ini, "w") as f:
        f.writelines(out)
    for root, dirs, files in os.walk(a.run_dir):
        for name in dirs + files:
            os.chmod(os.path.join(root, name), 0o777)
    os.chmod(a.run_dir, 0o777)


if __name__ == "__main__":
    sys.exit(main())
