#!/usr/bin/env python3
"""Stormer-Verlet on the pendulum with mpmath, but with one term through a float: the force
-k*sin(q) is computed as math.sin(float(q)), the bug that is easiest to make in an mpmath
program. Every answer carries the digits asked for, yet one term of it is good to about 16.

vivv's verdicts on it (tests/process/float-in-one-term.json): symplecticity errs — the Jacobian
by differences at 2D + 10 digits sees the float's rounding, so it cannot be measured —,
precision-leak fails naming a double's 53 bits, and the case's other claims are judged.
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from mpmath import mpf  # noqa: E402
from vivv_map import serve  # noqa: E402


def verlet(h, q, p, k):
    force = lambda x: [-k * mpf(math.sin(float(x[0])))]  # noqa: E731 — the float in one term
    f = force(q)
    p = [pi + h * fi / 2 for pi, fi in zip(p, f)]
    q = [qi + h * pi for qi, pi in zip(q, p)]
    f = force(q)
    p = [pi + h * fi / 2 for pi, fi in zip(p, f)]
    return q, p


if __name__ == "__main__":
    serve(lambda h, q, p: verlet(h, q, p, mpf(1)))
