#!/usr/bin/env python3
"""Störmer–Verlet for n independent oscillators of masses m[1..n] (L = sum m_i w_i^2/2 - q_i^2/2),
in Python floats: the process protocol's check that a parameter family reaches the greeting as
the case writes it — "m": [...], in index order — and not as keys m[1], m[2], … (a program that
read the masses another way fell back to unit masses and failed every claim of a correct map).
It declines a greeting whose "m" is not a list of n decimal strings (tests/process/CMakeLists.txt).
"""
import json
import sys


def send(message):
    sys.stdout.write(json.dumps(message) + "\n")
    sys.stdout.flush()


greeting = json.loads(sys.stdin.readline())
n = greeting["dimension"]
params = greeting["system"].get("params", {})
masses = params.get("m")
if not isinstance(masses, list) or len(masses) != n or not all(isinstance(m, str) for m in masses):
    send({"error": f"expected params.m as a list of {n} decimal strings, got {json.dumps(params)[:200]}"})
    sys.exit(0)
m = [float(x) for x in masses]
send({"protocol": "vivv-map/1"})
for line in sys.stdin:
    request = json.loads(line)
    h = float(request["h"])
    q = [float(x) for x in request["q"]]
    p = [float(x) for x in request["p"]]
    p = [pi - h / 2 * qi for pi, qi in zip(p, q)]
    q = [qi + h * pi / mi for qi, pi, mi in zip(q, p, m)]
    p = [pi - h / 2 * qi for pi, qi in zip(p, q)]
    send({"q": [f"{x:.16e}" for x in q], "p": [f"{x:.16e}" for x in p]})
