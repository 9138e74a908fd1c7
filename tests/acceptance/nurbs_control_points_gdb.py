# gdb script (gdb -batch -x THIS --args rs274 ...): writes the control points of every
# NURBS_FEED call rs274 makes to the file named by $NURBS_POINTS, a line per call:
# "order x0 y0 w0 x1 y1 w1 ...", the numbers exact (Python repr of the doubles).
#
# rs274's own canon prints only "NURBS_FEED(n, ...)" for G5, G5.1 and G5.3 (and does not move);
# the arcs LinuxCNC makes of them come from the task's canon, which compare_corpus.py redoes
# from these points. rs274 exports NURBS_FEED(int, std::vector<CONTROL_POINT>, unsigned): on
# entry (x86-64 System V) rsi holds the vector's address (begin, end, capacity pointers), its
# elements are CONTROL_POINT {double X, Y, W}, and edx holds the order.
import os
import struct

import gdb

gdb.execute("set pagination off")
gdb.execute("set confirm off")
out = open(os.environ["NURBS_POINTS"], "w")


class NurbsFeed(gdb.Breakpoint):
    def stop(self):
        frame = gdb.selected_frame()
        vector = int(frame.read_register("rsi")) & 0xFFFFFFFFFFFFFFFF
        order = int(frame.read_register("rdx")) & 0xFFFFFFFF
        memory = gdb.selected_inferior()
        begin, end = struct.unpack("<QQ", bytes(memory.read_memory(vector, 16)))
        values = struct.unpack("<%dd" % ((end - begin) // 8), bytes(memory.read_memory(begin, end - begin)))
        out.write("%d %s\n" % (order, " ".join(repr(v) for v in values)))
        out.flush()
        return False  # go on


gdb.execute("break _start")  # the program is loaded (position independent): the address is known
gdb.execute("run")
address = int(gdb.parse_and_eval(
    "(long)&'NURBS_FEED(int, std::vector<CONTROL_POINT, std::allocator<CONTROL_POINT> >, unsigned int)'"))
gdb.execute("delete")
NurbsFeed("*%d" % address)  # the first instruction: the argument registers as the caller set them
gdb.execute("continue")
