#!/usr/bin/python3
"""The midpoint rule's DEL map on (q, p) for a charge in a uniform magnetic field that pulses,
B(t) = B(1 + a cos Ωt), in the symmetric gauge with a harmonic trap —
L = (u² + v²)/2 + B(t)/2 (x v − y u) − (x² + y²)/2, a Lagrangian that depends on time and is
invariant under rotations about the origin at every t — in mpmath at the digits vivv asks for: a
map program whose step reads the request's time t (tests/process/CMakeLists.txt,
process/pulsing-field-program-*).

L_d(q0, q1) = h L(t + h/2, (q0 + q1)/2, (q1 − q0)/h) is quadratic, so p = −D1 L_d(q, q') is linear in
q': Newton with its exact Jacobian [[1/h + h/4, −b], [b, 1/h + h/4]], b = B(t + h/2)/2, solves it
(twice, for the rounding); p' = D2 L_d(q, q').

usage: pulsing_field_midpoint.py [--break | --float-field]

--break adds 10⁻³·h·Δx·Δy to L_d (Δ = q' − q), which no rotation leaves alone: the momentum map
p·(−y, x) drifts (a planted bug). --float-field computes the field's cos(Ωt) in a Python float (a
double) whatever the digits asked for: a term carried in 53 bits (a planted bug precision-leak finds).
"""
import math
import os
import sys

from mpmath import cos, mp, mpf

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from vivv_map import Decline, serve  # noqa: E402

broken = "--break" in sys.argv
float_field = "--float-field" in sys.argv
B = a = W = None


def setup(system, dimension, number):
    global B, a, W
    if dimension != 2:
        raise Decline(f"a charge in a plane has 2 coordinates, not {dimension}")
    params = system.get("params", {})
    B, a, W = number(params["B"]), number(params["a"]), number(params["W"])


def half_field(t):
    pulse = mpf(math.cos(float(W * t))) if float_field else cos(W * t)
    return B * (1 + a * pulse) / 2


def momenta(t, q0, q1, h):
    """(−D1 L_d, D2 L_d) at (q0, q1) on the segment [t, t + h]."""
    b = half_field(t + h / 2)
    x, y = (q0[0] + q1[0]) / 2, (q0[1] + q1[1]) / 2
    u, v = (q1[0] - q0[0]) / h, (q1[1] - q0[1]) / h
    l_v = [u - b * y, v + b * x]
    l_q = [b * v - x, -b * u - y]
    begin = [l_v[i] - h / 2 * l_q[i] for i in range(2)]
    end = [l_v[i] + h / 2 * l_q[i] for i in range(2)]
    if broken:  # + 1e-3·h·(x1 − x0)(y1 − y0) in L_d
        e = mpf("1e-3") * h
        dx, dy = q1[0] - q0[0], q1[1] - q0[1]
        begin = [begin[0] + e * dy, begin[1] + e * dx]
        end = [end[0] + e * dy, end[1] + e * dx]
    return begin, end


def step(h, q, p, t=0):
    q0 = list(q)
    q1 = [q0[i] + h * p[i] for i in range(2)]  # a guess; the equations are linear in q1
    b = half_field(t + h / 2)
    d, c = 1 / h + h / 4, -b  # the Jacobian [[d, c], [-c, d]] of −D1 L_d in q1
    e = mpf("1e-3") * h if broken else 0
    for _ in range(2):
        begin, _ = momenta(t, q0, q1, h)
        r = [begin[i] - p[i] for i in range(2)]
        # --break adds e·Δy, e·Δx to −D1 L_d: e off the diagonal
        j00, j01, j10, j11 = d, c + e, -c + e, d
        det = j00 * j11 - j01 * j10
        q1 = [q1[0] - (j11 * r[0] - j01 * r[1]) / det, q1[1] - (-j10 * r[0] + j00 * r[1]) / det]
    _, end = momenta(t, q0, q1, h)
    return q1, end


sys.exit(serve(step, setup=setup))
