#!/usr/bin/env python3
"""The band volcomp_acceptance_test's noise test holds ISO 230-2's R to: a Monte Carlo of R
(the largest bidirectional R_i over the targets) for 5 runs each way of unit Gaussian noise at
11 targets, and of the mean R over 10 such lines. Prints the quantiles, in units of the noise.

    python3 tests/cli/repeatability_monte_carlo.py   # about 30 s
"""
import random
import statistics as st

random.seed(1)
RUNS, TARGETS, LINES = 5, 11, 4000
rs = []
for _ in range(LINES):
    r = 0.0
    for _ in range(TARGETS):
        up = [random.gauss(0, 1) for _ in range(RUNS)]
        down = [random.gauss(0, 1) for _ in range(RUNS)]
        s_up, s_down = st.stdev(up), st.stdev(down)
        b = abs(st.mean(up) - st.mean(down))
        r = max(r, 2 * s_up + 2 * s_down + b, 4 * s_up, 4 * s_down)
    rs.append(r)
q = lambda a, p: sorted(a)[int(p * (len(a) - 1))]
print("R / S, quantiles 0.1 %, 1 %, 50 %, 99 %, 99.9 %:", [round(q(rs, p), 2) for p in (0.001, 0.01, 0.5, 0.99, 0.999)])
random.shuffle(rs)
means = [st.mean(rs[i:i + 10]) for i in range(0, LINES, 10)]
print("mean R / S of 10 lines, quantiles 0.1 %, 50 %, 99.9 %:", [round(q(means, p), 2) for p in (0.001, 0.5, 0.999)])
