#!/usr/bin/python3
"""Soak driver: a headless LinuxCNC display that runs the MC-300 (volkins, thermal example machine)
for a given time and injects faults at random, recording every servo period.

LinuxCNC starts it as its DISPLAY (run_soak.sh writes the INI). It takes the machine out of
estop, homes it, and then, until SOAK_SECONDS have passed, runs part programs (nc/*.ngc: tool
changes, G43 / G43.1 / G49) and MDI blocks between them, with faults:
- per program, one of a shuffled bag: none, abort in the middle of a move, e-stop in the middle
  of a move (then reset, machine on, unhome, home, and a rest window), pause and resume;
- in the background, at random moments (moving or not): volkins.enable toggled, feed override
  changed (programs and MDI), temperature inputs' ramps moved, a sensor reading NaN or out of
  its range for a while and back.
Every event is counted and logged (events.csv: id, seconds, kind, detail) and marked in the trace
by the s32 signal soak-event (the event's id from the servo period the driver set it in). The
trace (trace.bin: float64 rows, trace.columns: their names) holds both sampler channels of
soak_trace.hal, every period, from the first homing to the end. rtapi_app's VmRSS is sampled
every SOAK_MEMORY_PERIOD s (memory.csv). result.txt gets "ok ..." or "error: ..." last.

Settings (environment): SOAK_SECONDS (default 150), SOAK_SEED (default 1), SOAK_MEMORY_PERIOD
(default 2), SOAK_NC (folder of the programs, default soak_nc beside the INI).
Must run with Debian's /usr/bin/python3 (the linuxcnc and hal modules live there).
"""
import collections
import glob
import os
import random
import struct
import subprocess
import sys
import time
import traceback

import hal
import linuxcnc

SAMPLER_KEY = 0x48534130  # SAMPLER_SHMEM_KEY + channel (src/hal/components/streamer.h)
COLUMNS = [
    # channel 0
    "x", "y", "z", "b", "c", "j0", "j1", "j2", "j3", "j4", "q0", "q1", "q2", "q3", "q4",
    "gain", "tool_offset", "correction_length", "event",
    # channel 1
    "event1", "controller_time", "inverse_time", "coolant_sensor", "temperature_coolant",
    "spindle_sensor", "temperature_spindle", "temperature_fault", "requested_vel", "current_vel",
    "motion_enabled", "homed0", "homed1", "homed2", "homed3", "homed4", "tcp", "active",
    "failures", "iterations", "eoffset_limited",
]
CHANNEL0 = 19
# Temperature inputs of machines/data/mc300_thermal.toml: (min, max) degC.
SENSORS = {"coolant": (18.0, 26.0), "spindle": (18.0, 28.0)}
TOOLS = {1: 100.0, 2: 60.0, 3: 150.0}  # soak.tbl (run_soak.sh: mc300.tbl and two more)


def rtapi_app_pid():
    """The master rtapi_app: the oldest of that name (halcmd's loadrt starts short-lived client
    rtapi_app processes beside it, which a 150 s run once sampled as they exited)."""
    oldest = None
    for comm in glob.glob("/proc/[0-9]*/comm"):
        try:
            with open(comm) as f:
                if f.read().strip() != "rtapi_app":
                    continue
            pid = int(comm.split("/")[2])
            with open("/proc/%d/stat" % pid) as f:
                started = int(f.read().rsplit(")", 1)[1].split()[19])  # field 22: starttime
            if oldest is None or started < oldest[0]:
                oldest = (started, pid)
        except (OSError, ValueError, IndexError):
            pass
    return oldest[1] if oldest else None


def vm_rss_kb(pid):
    """VmRSS of `pid`, or None if the process is gone."""
    try:
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
    except OSError:
        return None
    return -1


class Soak:
    def __init__(self, ini_path):
        self.ini = linuxcnc.ini(ini_path)
        self.folder = os.path.dirname(os.path.abspath(ini_path))
        self.seconds = float(os.environ.get("SOAK_SECONDS", "150"))
        self.seed = int(os.environ.get("SOAK_SEED", "1"))
        self.memory_period = float(os.environ.get("SOAK_MEMORY_PERIOD", "2"))
        nc = os.environ.get("SOAK_NC", os.path.join(self.folder, "soak_nc"))
        self.programs = sorted(glob.glob(os.path.join(nc, "*.ngc")))
        if not self.programs:
            raise RuntimeError("no programs in " + nc)
        self.rng = random.Random(self.seed)
        self.stat = linuxcnc.stat()
        self.command = linuxcnc.command()
        self.errors = linuxcnc.error_channel()
        self.comp = hal.component("soak-driver")
        self.comp.newpin("event", hal.HAL_S32, hal.HAL_OUT)
        self.comp.ready()
        hal.connect("soak-driver.event", "soak-event")
        self.start = time.time()
        self.deadline = self.start + self.seconds + 600  # nothing may hang beyond this
        self.counts = {}
        self.event_id = 0
        self.events = open(os.path.join(self.folder, "events.csv"), "w")
        self.events.write("id,seconds,kind,detail\n")
        self.memory = open(os.path.join(self.folder, "memory.csv"), "w")
        self.memory.write("seconds,samples,vm_rss_kb\n")
        self.trace = open(os.path.join(self.folder, "trace.bin"), "wb")
        with open(os.path.join(self.folder, "trace.columns"), "w") as f:
            f.write("\n".join(COLUMNS) + "\n")
        self.row = struct.Struct("<%dd" % len(COLUMNS))
        self.samples = 0
        self.pending0 = collections.deque()  # channel 0 rows waiting for their channel 1 row
        self.streams = None
        self.pid = None
        self.next_memory = 0.0
        self.background = False
        self.program_running = False
        self.enabled = True
        self.next_toggle = self.next_temperature = self.next_feed = 0.0
        self.sensor_fault_end = {}  # sensor -> time its faulty reading ends

    # --- recording ------------------------------------------------------------------------
    def now(self):
        return time.time() - self.start

    def event(self, kind, detail=""):
        self.event_id += 1
        self.comp["event"] = self.event_id
        self.counts[kind] = self.counts.get(kind, 0) + 1
        self.events.write("%d,%.3f,%s,%s\n" % (self.event_id, self.now(), kind, detail.replace(",", ";")))

    def start_trace(self):
        self.streams = (hal.stream(self.comp, SAMPLER_KEY), hal.stream(self.comp, SAMPLER_KEY + 1))
        subprocess.check_call(["halcmd", "sets", "soak-sampling", "1"])

    def drain(self):
        if self.streams is None:
            return
        s0, s1 = self.streams
        while True:
            a = s0.read()
            if a is None:
                break
            self.pending0.append(a)
        while self.pending0:
            b = s1.read()
            if b is None:
                break
            a = self.pending0.popleft()
            # Both rows carry the event marker (the test checks that they agree but where the
            # driver set it between the two samplers' functions of one period).
            self.trace.write(self.row.pack(*[float(v) for v in a], *[float(v) for v in b]))
            self.samples += 1

    def stop_trace(self):
        time.sleep(0.2)
        subprocess.check_call(["halcmd", "sets", "soak-sampling", "0"])
        time.sleep(0.05)
        for _ in range(100):
            self.drain()
            if not self.pending0:
                break
            time.sleep(0.01)
        overruns = sum(s.num_overruns for s in self.streams)
        if overruns:
            raise RuntimeError("the samplers overran %d times: samples are missing" % overruns)
        if self.pending0:
            raise RuntimeError("%d samples of channel 0 without their channel 1 row" % len(self.pending0))
        self.trace.close()

    def check_errors(self):
        while True:
            e = self.errors.poll()
            if not e:
                return
            kind = {linuxcnc.NML_ERROR: "error", linuxcnc.OPERATOR_ERROR: "error"}.get(e[0], "text")
            self.event("message", "%s: %s" % (kind, e[1].strip().replace("\n", " ")))

    def sample_memory(self):
        if time.time() < self.next_memory:
            return
        self.next_memory = time.time() + self.memory_period
        if self.pid is None:
            self.pid = rtapi_app_pid()
        rss = vm_rss_kb(self.pid) if self.pid is not None else None
        if rss is None:
            self.pid = None  # not (yet) the master: look again next time
            return
        self.memory.write("%.3f,%d,%d\n" % (self.now(), self.samples, rss))
        self.memory.flush()

    def pump(self):
        """One round of everything that runs while the driver waits."""
        self.drain()
        self.stat.poll()
        self.check_errors()
        self.sample_memory()
        if self.background:
            self.background_faults()
        if time.time() > self.deadline:
            raise RuntimeError("the soak hangs")

    def wait_for(self, condition, what, timeout=60.0):
        until = time.time() + timeout
        while True:
            self.pump()
            if condition():
                return
            if time.time() > until:
                raise RuntimeError("timed out waiting for " + what)
            time.sleep(0.003)

    def hold(self, seconds):
        until = time.time() + seconds
        self.wait_for(lambda: time.time() >= until, "time", seconds + 10)

    # --- background faults ----------------------------------------------------------------
    def schedule_background(self):
        t = time.time()
        self.next_toggle = t + self.rng.expovariate(1 / 4.0)
        self.next_temperature = t + self.rng.expovariate(1 / 4.0)
        self.next_feed = t + self.rng.expovariate(1 / 3.0)

    def set_enable(self, on, why):
        self.enabled = on
        hal.set_p("volkins.enable", "1" if on else "0")
        self.stat.poll()
        self.event("enable_toggle", "%s %s velocity %.3f" % ("on" if on else "off", why, self.stat.current_vel))

    def background_faults(self):
        t = time.time()
        if t >= self.next_toggle:
            self.set_enable(not self.enabled, "moving" if self.stat.current_vel > 1e-3 else "at rest")
            self.next_toggle = t + self.rng.expovariate(1 / 4.0)
        for sensor, end in list(self.sensor_fault_end.items()):
            if t >= end:
                hal.set_p(sensor + "-sensor.sel", "0")
                del self.sensor_fault_end[sensor]
                self.event("temperature_back", sensor)
        if t >= self.next_temperature:
            self.next_temperature = t + self.rng.expovariate(1 / 4.0)
            sensor = self.rng.choice(sorted(SENSORS))
            low, high = SENSORS[sensor]
            kind = self.rng.choice(["ramp", "nan", "out_of_range"])
            if kind == "ramp":
                target = self.rng.uniform(low + 0.5, high - 0.5)
                hal.set_p(sensor + "-ramp.in", "%.3f" % target)
                self.event("temperature_ramp", "%s %.3f" % (sensor, target))
            elif sensor not in self.sensor_fault_end:
                value = "nan" if kind == "nan" else "%.1f" % self.rng.choice([low - 5.0, high + 12.0, -40.0, 150.0])
                hal.set_p(sensor + "-sensor.in1", value)
                hal.set_p(sensor + "-sensor.sel", "1")
                self.sensor_fault_end[sensor] = t + self.rng.uniform(0.1, 2.0)
                self.event("temperature_" + kind, "%s %s" % (sensor, value))
        if t >= self.next_feed:
            self.next_feed = t + self.rng.expovariate(1 / 3.0)
            scale = self.rng.choice([0.25, 0.5, 0.8, 1.0, 1.0, 1.2, 1.5])
            self.command.feedrate(scale)
            self.event("feed_override", "%.2f %s" % (scale, "program" if self.program_running else "mdi or rest"))

    def end_temperature_faults(self):
        for sensor in list(self.sensor_fault_end):
            hal.set_p(sensor + "-sensor.sel", "0")
            del self.sensor_fault_end[sensor]
            self.event("temperature_back", sensor)

    # --- machine --------------------------------------------------------------------------
    def all_homed(self):
        return all(self.stat.homed[: self.stat.joints])

    def machine_on_and_home(self, first):
        self.command.state(linuxcnc.STATE_ESTOP_RESET)
        self.command.state(linuxcnc.STATE_ON)
        self.wait_for(lambda: self.stat.task_state == linuxcnc.STATE_ON, "machine on")
        self.command.mode(linuxcnc.MODE_MANUAL)
        self.command.wait_complete()
        if not first:
            self.command.teleop_enable(0)
            self.command.wait_complete()
            self.command.unhome(-1)
            self.wait_for(lambda: not any(self.stat.homed[: self.stat.joints]), "unhoming")
            self.event("unhomed")
        self.command.home(-1)
        self.wait_for(self.all_homed, "homing")
        self.event("homed", "first" if first else "again")
        # At rest: the joints must be the core's correction of the commanded position (the
        # test checks the samples between rest_check and rest_end).
        self.wait_for(lambda: self.stat.inpos, "rest after homing")
        self.hold(0.2)
        self.event("rest_check")
        self.hold(0.5)
        self.event("rest_end")

    def estop_and_rehome(self):
        self.stat.poll()
        self.event("estop", "velocity %.3f" % self.stat.current_vel)
        self.command.state(linuxcnc.STATE_ESTOP)
        self.wait_for(lambda: self.stat.task_state == linuxcnc.STATE_ESTOP, "estop")
        self.background = False
        self.end_temperature_faults()
        self.hold(self.rng.uniform(0.2, 1.0))
        self.machine_on_and_home(first=False)
        # After the e-stop the status may still show the aborted program's tool length offset
        # while the interpreter has dropped it (a 150 s run moved Z 150 mm below its limit on
        # that): start from a known offset, as an operator would.
        self.command.mode(linuxcnc.MODE_MDI)
        self.command.wait_complete()
        self.mdi("G49")
        self.background = True

    def idle(self):
        return (self.stat.interp_state == linuxcnc.INTERP_IDLE and self.stat.queue == 0
                and self.stat.inpos)

    def wait_until_moving(self, limit):
        """Waits until the commanded position moves (False if the program ends first or `limit` s pass)."""
        until = time.time() + limit
        while time.time() < until:
            self.pump()
            if self.stat.interp_state == linuxcnc.INTERP_IDLE:
                return False
            if self.stat.current_vel > 1.0:
                return True
            time.sleep(0.002)
        return False

    def run_program(self, fault):
        program = self.rng.choice(self.programs)
        self.command.mode(linuxcnc.MODE_AUTO)
        self.command.wait_complete()
        self.command.program_open(program)
        self.command.wait_complete()
        self.command.auto(linuxcnc.AUTO_RUN, 0)
        self.event("program", "%s fault %s" % (os.path.basename(program), fault))
        self.program_running = True
        self.wait_for(lambda: self.stat.interp_state != linuxcnc.INTERP_IDLE, "the program to start", 10)
        fault_at = time.time() + self.rng.uniform(0.3, 6.0)
        injected = False
        while self.stat.interp_state != linuxcnc.INTERP_IDLE:
            self.pump()
            time.sleep(0.003)
            if self.now() > self.seconds + 5.0:  # the soak's time is up: end the program
                self.event("end_abort")
                self.command.abort()
                self.wait_for(lambda: self.stat.interp_state == linuxcnc.INTERP_IDLE, "the abort", 10)
                break
            if injected or fault == "none" or time.time() < fault_at:
                continue
            injected = True
            if not self.wait_until_moving(2.0):
                continue
            if fault == "abort":
                self.event("abort", "velocity %.3f" % self.stat.current_vel)
                self.command.abort()
                self.wait_for(lambda: self.stat.interp_state == linuxcnc.INTERP_IDLE, "the abort", 10)
            elif fault == "estop":
                self.program_running = False
                self.estop_and_rehome()
                return
            elif fault == "pause":
                self.event("pause", "velocity %.3f" % self.stat.current_vel)
                self.command.auto(linuxcnc.AUTO_PAUSE)
                self.hold(self.rng.uniform(0.2, 1.5))
                self.event("resume")
                self.command.auto(linuxcnc.AUTO_RESUME)
        self.program_running = False
        self.wait_for(self.idle, "the program's end", 20)
        self.event("program_end")

    def mdi(self, line):
        self.event("mdi", line)
        self.command.mdi(line)
        self.command.wait_complete(0.2)  # at most 0.2 s without reading the samplers
        self.hold(0.02)
        self.wait_for(self.idle, "MDI " + line, 60)

    def mdi_block(self):
        self.command.mode(linuxcnc.MODE_MDI)
        self.command.wait_complete()
        for _ in range(self.rng.randint(2, 4)):
            choice = self.rng.choice(["move", "move", "g43", "g43.1", "g49", "tool", "dwell"])
            if choice == "move":
                self.stat.poll()
                offset = self.stat.tool_offset[2]
                x, y = self.rng.uniform(-580, -20), self.rng.uniform(-300, -20)
                z_axis = self.rng.uniform(-290, -20)
                b, c = self.rng.uniform(-100, 20), self.rng.uniform(-200, 200)
                g = self.rng.choice(["G0", "G1 F%d" % self.rng.choice([3000, 6000])])
                self.mdi("%s X%.3f Y%.3f Z%.3f B%.3f C%.3f" % (g, x, y, z_axis - offset, b, c))
            elif choice == "g43":
                self.mdi("G43 H%d" % self.rng.choice(sorted(TOOLS)))
            elif choice == "g43.1":
                self.mdi("G43.1 Z%.3f" % self.rng.uniform(20, 160))
            elif choice == "g49":
                self.mdi("G49")
            elif choice == "tool":
                self.mdi("T%d M6" % self.rng.choice(sorted(TOOLS)))
            else:
                self.mdi("G4 P%.2f" % self.rng.uniform(0.1, 0.5))
        # A safe Z for the next program's first G0 (the axis near its top whatever the offset).
        self.stat.poll()
        self.mdi("G0 Z%.3f" % (-20.0 - self.stat.tool_offset[2]))

    def run(self):
        self.stat.poll()
        self.wait_for(lambda: self.stat.task_state == linuxcnc.STATE_ESTOP, "LinuxCNC to start")
        hal.set_p("volkins.enable", "1")
        self.wait_for(lambda: hal.get_value("volkins.gain") == 1.0, "the compensation ramp")
        hal.set_p("coolant-ramp.load", "0")
        hal.set_p("spindle-ramp.load", "0")
        self.start_trace()
        self.machine_on_and_home(first=True)
        self.background = True
        self.schedule_background()
        bag = []
        while self.now() < self.seconds:
            if not bag:
                bag = ["none", "abort", "estop", "pause", "pause"]
                self.rng.shuffle(bag)
            self.run_program(bag.pop())
            if self.now() >= self.seconds:
                break
            self.mdi_block()
        self.background = False
        self.end_temperature_faults()
        self.command.feedrate(1.0)
        self.wait_for(self.idle, "the end")
        self.hold(0.5)
        self.event("end")
        self.stop_trace()
        self.events.close()
        self.memory.close()
        failures = hal.get_value("volkins.failures")
        if failures:
            raise RuntimeError("volkins refused %d kinematics calls" % failures)
        return " ".join("%s=%d" % kv for kv in sorted(self.counts.items()))


def main():
    ini_path = sys.argv[sys.argv.index("-ini") + 1]
    folder = os.path.dirname(os.path.abspath(ini_path))
    soak = None
    try:
        soak = Soak(ini_path)
        counts = soak.run()
        message = "ok %d samples %.1f s %s\n" % (soak.samples, soak.now(), counts)
        code = 0
    except Exception as e:  # reported to the caller through the result file
        message = "error: %s\n%s" % (e, traceback.format_exc())
        code = 1
    with open(os.path.join(folder, "result.txt"), "w") as out:
        out.write(message)
    if soak is not None:
        try:
            soak.command.state(linuxcnc.STATE_OFF)
        except linuxcnc.error:
            pass
    sys.exit(code)


if __name__ == "__main__":
    main()
