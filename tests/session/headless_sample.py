#!/usr/bin/python3
"""Makes a headless copy of a LinuxCNC configuration (one of LinuxCNC's own samples, as a user
has it, or after `volcomp init`'s patch) that runs one program and records a trace, so that a
test can run it without X: the display becomes kins/configs/common/headless_driver.py, what
needs X goes (PYVCP panels, the postgui HAL file that nets them, vismach models loaded with
loadusr and their pins, hal_manualtoolchange), and a sampler records at servo rate the world
command, the joint commands, volkins' gain (0 without volkins), the tool length offset,
motion-controller's time, kinstype.is-N of the TCP type (the trace's "tcp" column: with
sparm=identityfirst type 1 is the TCP kinematics, for LinuxCNC's trt modules and for volkins
alike; without it, as in the bridgemill sample, type 0: --tcp-type 0; trivkins, which has no
such pins: --tcp-type -1, the column 0) and, with volkins, the
L its correction used (volkins.correction-length: it slews to a new G43 offset).

    headless_sample.py CONFIG_DIR INI RUN_DIR --program FILE [--compensation on|off]
                       [--tcp-type N] [--sets SIGNAL=VALUE]... [--bit-column NAME=SOURCE]...

--bit-column records one more column NAME (after the others) of a bit pin (SOURCE with a dot) or
of a signal (without one: the xyzb sample's B-is-unlocked).

CONFIG_DIR is copied to RUN_DIR (its INI keeps its name); the program path is relative to it.
The INI's HALCMDs and the HAL files in the folder are filtered alike. A signal that only
connected a vismach model goes with its `sets`; one that a vismach model drove for others (the
bridgemill's :gui-pivot-len, 5axisgui's pivot_len) gets its value with --sets, as a user without
the model would set it.
"""
import argparse
import os
import re
import shutil
import sys

DRIVER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../kins/configs/common/headless_driver.py")


# A vismach model: a userspace program loaded with loadusr whose name ends in "gui"
# (xyzbc-trt-gui, 5axisgui), and its pins.
VISMACH_LOAD = re.compile(r"loadusr\b.*\bgui\b|loadusr\b(\s+-\S+)*\s+\S*gui\b")
VISMACH_PIN = re.compile(r"\S*gui\.")


class HalFilter:
    """Drops what needs X from HAL commands (an INI's HALCMD values or a HAL file's lines)."""

    def __init__(self):
        self.tool_signal = None  # the signal motion.tooloffset.z is on
        self.dropped = set()     # signals that only connected a vismach model

    def command(self, value):
        """The command without what needs X, or None to drop it."""
        words = value.split()
        if not words:
            return value
        if words[0] == "loadusr" and VISMACH_LOAD.match(value):
            return None
        if words[0] == "net":
            kept = [t for t in words if not VISMACH_PIN.match(t)]
            if not [t for t in kept[2:] if t not in ("<=", "=>")]:
                self.dropped.add(words[1])
                return None
            if "motion.tooloffset.z" in kept:
                self.tool_signal = words[1]
            return " ".join(kept) if len(kept) != len(words) else value
        if words[0] == "sets" and len(words) > 1 and words[1] in self.dropped:
            return None
        return value


def filter_hal_file(path, hal_filter):
    with open(path) as f:
        lines = f.readlines()
    out = []
    for line in lines:
        code = line.split("#", 1)[0].strip()
        if code:
            filtered = hal_filter.command(code)
            if filtered is None:
                continue
            if filtered != code:
                line = filtered + "\n"
        out.append(line)
    with open(path, "w") as f:
        f.writelines(out)


def headless_lines(lines, folder, coordinates, joints, has_volkins, tcp_type, sets, bits):
    out, section, hal_filter = [], None, HalFilter()
    # The configuration's own HAL files first (LinuxCNC runs them before the HALCMDs).
    for line in lines:
        key, _, value = line.strip().partition("=")
        name = value.strip().split()[0] if value.strip() else ""
        if key.strip() == "HALFILE" and not name.startswith("LIB:") and os.path.exists(os.path.join(folder, name)):
            filter_hal_file(os.path.join(folder, name), hal_filter)
    for line in lines:
        stripped = line.strip()
        if stripped.startswith("["):
            if section == "HAL":
                out.extend(trace_lines(coordinates, joints, has_volkins, hal_filter.tool_signal, tcp_type, sets, bits))
            section = stripped.strip("[]")
        key, _, value = stripped.partition("=")
        key, value = key.strip(), value.strip()
        if section == "DISPLAY" and key == "DISPLAY":
            line = "DISPLAY = " + os.path.realpath(DRIVER) + "\n"
        elif (section == "DISPLAY" and key == "PYVCP") or (section == "HAL" and key == "POSTGUI_HALFILE"):
            continue
        elif section == "HAL" and key == "HALCMD":
            filtered = hal_filter.command(value)
            if filtered is None:
                continue
            if filtered != value:
                line = "HALCMD = " + filtered + "\n"
        elif section == "HAL" and key == "HALFILE" and value.startswith("LIB:basic_sim.tcl"):
            if "-no_use_hal_manualtoolchange" not in value:
                line = "HALFILE = " + value + " -no_use_hal_manualtoolchange\n"
        out.append(line)
    if section == "HAL":
        out.extend(trace_lines(coordinates, joints, has_volkins, hal_filter.tool_signal, tcp_type, sets, bits))
    return out


def trace_lines(coordinates, joints, has_volkins, tool_signal, tcp_type, sets, bits):
    cfg = "f" * (len(coordinates) + joints + 2) + "s" + "b" + ("f" if has_volkins else "") + "b" * len(bits)
    pins = ["axis.%s.pos-cmd" % c for c in coordinates]
    pins += ["joint.%d.pos-cmd" % j for j in range(joints)]
    lines = ["sets %s %s" % tuple(s.split("=", 1)) for s in sets]
    lines += ["loadrt sampler depth=8000 cfg=" + cfg, "setp sampler.0.enable 0"]
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
    if tcp_type >= 0:  # trivkins has no kinstype.is-N pins (--tcp-type -1): the column stays 0
        lines.append("net :trace-tcp kinstype.is-%d => sampler.0.pin.%d" % (tcp_type, n))
    if has_volkins:  # the L volkins' correction used (it slews to a new G43 offset)
        lines.append("net :trace-correction-length volkins.correction-length => sampler.0.pin.%d" % (n + 1))
    n += 2 if has_volkins else 1
    for name, source in (b.split("=", 1) for b in bits):
        lines.append(("net :trace-%s %s" % (name, source) if "." in source else "net " + source) +
                     " => sampler.0.pin.%d" % n)
        n += 1
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
    p.add_argument("--tcp-type", type=int, default=1)
    p.add_argument("--sets", action="append", default=[])
    p.add_argument("--bit-column", action="append", default=[])
    a = p.parse_args()
    shutil.rmtree(a.run_dir, ignore_errors=True)
    shutil.copytree(a.config_dir, a.run_dir, symlinks=False)
    ini = os.path.join(a.run_dir, a.ini)
    with open(ini) as f:
        lines = f.readlines()
    # Each axis once (the bridgemill's XYZBCWY names Y twice: a gantry).
    coordinates = "".join(dict.fromkeys(ini_value(lines, "TRAJ", "COORDINATES").replace(" ", "").lower()))
    joints = int(ini_value(lines, "KINS", "JOINTS"))
    has_volkins = ini_value(lines, "KINS", "KINEMATICS").split()[0] == "volkins"
    out = headless_lines(lines, a.run_dir, coordinates, joints, has_volkins, a.tcp_type, a.sets, a.bit_column)
    columns = list(coordinates) + ["j%d" % j for j in range(joints)]
    columns += ["gain", "tool_offset", "controller_time", "tcp"] + (["correction_length"] if has_volkins else [])
    columns += [b.split("=", 1)[0] for b in a.bit_column]
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
