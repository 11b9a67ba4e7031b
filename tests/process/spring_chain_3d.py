#!/usr/bin/env python3
"""Störmer–Verlet for a chain of particles in space, in Python floats: particle i (mass m[i], from
the greeting's array) sits in a harmonic well and is tied to its neighbours by springs,
    L = sum_i m[i]|v_i|²/2 − sum_i |x_i|²/2 − sum_i |x_{i+1} − x_i|²/2,
coordinates x[i, k] (k = 1, 2, 3), in vivv's order x[1,1], x[1,2], x[1,3], x[2,1], …

    spring_chain_3d.py [--unit-mass I] [--antidamping D] [--perturb EPS]

--unit-mass I is the many-body user's bug: the program reads particle I's mass as 1 (a default
where the case's value was not found). The map is then a correct Verlet of another system — one
step errs like h, not h³ — and vivv must say so and name x[I,*] as where the error sits.
--antidamping D multiplies p by 1 + D/h after each step (a friction term with h where h·γ
belongs, of the wrong sign): after T/h steps p grows like exp(D·T/h²), so the finest runs leave
the problem's scale while the coarser ones finish — with errors that grow as h falls.
--perturb EPS scales each step's new momentum by 1 + EPS·h²: a map that is not symplectic by about
2·EPS·h² a step (a lower-order term; symplecticity's probes above 16 coordinates must find it).
"""
import json
import sys


def send(message):
    sys.stdout.write(json.dumps(message) + "\n")
    sys.stdout.flush()


unit_mass = int(sys.argv[sys.argv.index("--unit-mass") + 1]) if "--unit-mass" in sys.argv else None
antidamping = float(sys.argv[sys.argv.index("--antidamping") + 1]) if "--antidamping" in sys.argv else 0.0
perturb = float(sys.argv[sys.argv.index("--perturb") + 1]) if "--perturb" in sys.argv else 0.0
greeting = json.loads(sys.stdin.readline())
n = greeting["dimension"]
masses = greeting["system"].get("params", {}).get("m")
if not isinstance(masses, list) or 3 * len(masses) != n:
    send({"error": f"expected params.m as a list of {n // 3} masses"})
    sys.exit(0)
m = [1.0 if unit_mass == i + 1 else float(x) for i, x in enumerate(masses)]
particles = len(m)
send({"protocol": "vivv-map/1"})


def force(q):
    f = [-x for x in q]
    for i in range(particles - 1):
        for k in range(3):
            stretch = q[3 * (i + 1) + k] - q[3 * i + k]
            f[3 * i + k] += stretch
            f[3 * (i + 1) + k] -= stretch
    return f


for line in sys.stdin:
    request = json.loads(line)
    h = float(request["h"])
    q = [float(x) for x in request["q"]]
    p = [float(x) for x in request["p"]]
    p = [pi + h / 2 * fi for pi, fi in zip(p, force(q))]
    q = [qi + h * pi / m[j // 3] for j, (qi, pi) in enumerate(zip(q, p))]
    p = [pi + h / 2 * fi for pi, fi in zip(p, force(q))]
    p = [pi * (1 + antidamping / h + perturb * h * h) for pi in p]
    send({"q": [f"{x:.17e}" for x in q], "p": [f"{x:.17e}" for x in p]})
