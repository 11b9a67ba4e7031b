#!/usr/bin/env python3
"""Stormer-Verlet for the Duffing oscillator L = w^2/2 - x^2/2 - x^4/4 (a formula system of the
test's own), in Python's decimal at the digits vivv asks for: a map program for the process
protocol's checks in every scalar (tests/CMakeLists.txt, process/duffing-*).

usage: duffing.py [--perturb EPS] [--padded]

--perturb EPS scales each step's new momentum by 1 + EPS·h²: a map that is not symplectic by
EPS·h² per step (symplecticity must fail; in double too). --padded computes in double and writes the digits of
its doubles as if they were the precision asked for (symplecticity must err: its Jacobian cannot
be measured).
"""
import decimal
import json
import sys

perturb = decimal.Decimal(sys.argv[sys.argv.index("--perturb") + 1]) if "--perturb" in sys.argv else 0
padded = "--padded" in sys.argv


def send(message):
    sys.stdout.write(json.dumps(message) + "\n")
    sys.stdout.flush()


greeting = json.loads(sys.stdin.readline())
digits = greeting["digits"]
decimal.getcontext().prec = digits + 5
send({"protocol": "vivv-map/1"})
for line in sys.stdin:
    request = json.loads(line)
    if padded:
        h, x, p = (float(request[k] if k == "h" else request[k][0]) for k in ("h", "q", "p"))
    else:
        h, x, p = (decimal.Decimal(request[k] if k == "h" else request[k][0]) for k in ("h", "q", "p"))
    force = lambda y: -y - y * y * y
    half = p + h / 2 * force(x)
    x = x + h * half
    p = half + h / 2 * force(x)
    p = p * (1 + (float(perturb) if padded else perturb) * h * h)
    send({"q": [f"{x:.{digits - 1}e}"], "p": [f"{p:.{digits - 1}e}"]})
