#!/usr/bin/python3
"""The midpoint rule's DEL map on (q, p) for a Kapitza pendulum, a Lagrangian that depends on time
(L = v²/2 − aω sin(ωt) sin(x) v + g cos x: a pendulum whose pivot oscillates vertically), in mpmath
at the digits vivv asks for: a map program whose step reads the request's time t (vivv_map passes it
to a step with a parameter named t; tests/process/CMakeLists.txt, process/kapitza-*).

L_d(q0, q1) = h L(t + h/2, (q0 + q1)/2, (q1 − q0)/h); from (q, p) at t, q' solves p = −D1 L_d(q, q')
by Newton, and p' = D2 L_d(q, q').

usage: kapitza_midpoint.py [--time-at-start | --no-time] [--float] [--no-batch]

--time-at-start evaluates L at the segment's start t where t + h/2 belongs (a planted bug: order 1).
--no-time steps as if t were always 0, a program that ignores the time vivv sends (order 0 where
the pivot moves). --float computes in Python floats (a double program: "precision": "double").
--no-batch declines the extensions "steps" and "trajectory": vivv sends one request a step, each
with its own time.
"""
import math
import os
import sys

import mpmath

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from vivv_map import Decline, serve  # noqa: E402

in_float = "--float" in sys.argv
cos, sin = (math.cos, math.sin) if in_float else (mpmath.cos, mpmath.sin)
at_start = "--time-at-start" in sys.argv
no_time = "--no-time" in sys.argv
a = w = g = None


def setup(system, dimension, number):
    global a, w, g
    if dimension != 1:
        raise Decline(f"a pendulum has 1 coordinate, not {dimension}")
    params = system.get("params", {})
    a, w, g = number(params["a"]), number(params["w"]), number(params["g"])


def momenta(t, q0, q1, h):
    """(−D1 L_d, D2 L_d) and their derivatives in q1 at the segment's node time."""
    tm = t if at_start else t + h / 2
    amplitude = a * w * sin(w * tm)
    x, v = (q0 + q1) / 2, (q1 - q0) / h
    l_v = v - amplitude * sin(x)
    l_x = -amplitude * cos(x) * v - g * sin(x)
    dl_v = 1 / h - amplitude * cos(x) / 2
    dl_x = amplitude * sin(x) * v / 2 - amplitude * cos(x) / h - g * cos(x) / 2
    return l_v - h / 2 * l_x, l_v + h / 2 * l_x, dl_v - h / 2 * dl_x


def step(h, q, p, t=0):
    t = 0 if no_time else t
    q0, p0 = q[0], p[0]
    q1 = q0 + h * (p0 + a * w * sin(w * t) * sin(q0))  # an explicit Euler guess: v = p + A sin q
    tolerance = sys.float_info.epsilon if in_float else mpmath.mpf(10) ** (-mpmath.mp.dps)
    for _ in range(60):  # Newton: quadratic, a few iterations
        before, _, slope = momenta(t, q0, q1, h)
        correction = (before - p0) / slope
        q1 -= correction
        if abs(correction) <= tolerance * max(1, abs(q1)):
            break
    _, after, _ = momenta(t, q0, q1, h)
    return [q1], [after]


sys.exit(serve(step, setup=setup, arithmetic="float" if in_float else "mpmath", batch="--no-batch" not in sys.argv))
