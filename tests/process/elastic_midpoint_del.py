#!/usr/bin/env python3
"""The variational midpoint rule for the elastic pendulum
L = (vr^2 + r^2*vt^2)/2 - 2*(r - 1)^2 + r*cos(t), as its DEL map on (q, p) in plain Python floats:
a double program with an implicit solver (tests/process/CMakeLists.txt, elastic-midpoint-*).

    L_d(q, q') = h*L((q + q')/2, (q' - q)/h)
    p  = -dL_d/dq (q, q')   solved for q' by Newton to 1e-15 relative
    p' =  dL_d/dq'(q, q')

p' contains (q' - q)/h, so the solver's last digits in q' reach p' multiplied by 1/h: the map's
rounding grows as h falls while a truncation defect falls with h. Symplectic and of order 2.

usage: elastic_midpoint_del.py [--perturb EPS]

--perturb EPS scales each step's new momentum by 1 + EPS*h^2 (not symplectic by EPS*h^2 per step).
"""
import json
import math
import sys

perturb = float(sys.argv[sys.argv.index("--perturb") + 1]) if "--perturb" in sys.argv else 0.0


def gradients(m, v):
    """dL/dq and dL/dv at position m, velocity v."""
    r, t = m
    vr, vt = v
    return (r * vt * vt - 4 * (r - 1) + math.cos(t), -r * math.sin(t)), (vr, r * r * vt)


def sides(h, q, x):
    """(p_begin, p_end) of L_d at (q, x): -dL_d/dq and dL_d/dq'."""
    m = ((q[0] + x[0]) / 2, (q[1] + x[1]) / 2)
    v = ((x[0] - q[0]) / h, (x[1] - q[1]) / h)
    lq, lv = gradients(m, v)
    begin = tuple(-h / 2 * lq[i] + lv[i] for i in range(2))
    end = tuple(h / 2 * lq[i] + lv[i] for i in range(2))
    return begin, end


def step(h, q, p):
    x = [q[0] + h * p[0], q[1] + h * p[1] / (q[0] * q[0])]
    for _ in range(50):
        begin, _ = sides(h, q, x)
        residual = [begin[0] - p[0], begin[1] - p[1]]
        # d p_begin / d x by central differences of the residual's own formula would add noise of
        # its own; the exact derivative of p_begin with respect to q' is cheap here.
        m = ((q[0] + x[0]) / 2, (q[1] + x[1]) / 2)
        v = ((x[0] - q[0]) / h, (x[1] - q[1]) / h)
        r, t = m
        vr, vt = v
        # d(dL/dq)/dm, d(dL/dq)/dv, d(dL/dv)/dm, d(dL/dv)/dv
        lqq = ((vt * vt - 4, -math.sin(t)), (-math.sin(t), -r * math.cos(t)))
        lqv = ((0.0, 2 * r * vt), (0.0, 0.0))
        lvq = ((0.0, 0.0), (2 * r * vt, 0.0))
        lvv = ((1.0, 0.0), (0.0, r * r))
        jac = [[-h / 2 * (lqq[i][j] / 2 + lqv[i][j] / h) + lvq[i][j] / 2 + lvv[i][j] / h for j in range(2)]
               for i in range(2)]
        det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0]
        dx = [(jac[1][1] * residual[0] - jac[0][1] * residual[1]) / det,
              (-jac[1][0] * residual[0] + jac[0][0] * residual[1]) / det]
        x = [x[0] - dx[0], x[1] - dx[1]]
        if max(abs(dx[0]), abs(dx[1])) <= 1e-15 * max(abs(x[0]), abs(x[1])):
            break
    _, end = sides(h, q, x)
    scale = 1 + perturb * h * h
    return x, [end[0] * scale, end[1] * scale]


def send(message):
    sys.stdout.write(json.dumps(message) + "\n")
    sys.stdout.flush()


json.loads(sys.stdin.readline())
send({"protocol": "vivv-map/1"})
for line in sys.stdin:
    request = json.loads(line)
    h = float(request["h"])
    q_next, p_next = step(h, [float(v) for v in request["q"]], [float(v) for v in request["p"]])
    send({"q": [f"{v:.16e}" for v in q_next], "p": [f"{v:.16e}" for v in p_next]})
