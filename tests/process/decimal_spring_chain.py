#!/usr/bin/env python3
"""Störmer–Verlet for a chain of particles in space (the system of spring_chain_3d.py, masses from
the greeting's params.m), in Python's decimal at exactly the digits each greeting asks for: a map
program of any size for the checks that run its second instance at 2D + 10 digits (long double,
float128, MPFR working precisions), where spring_chain_3d.py computes in double.

    decimal_spring_chain.py [--perturb EPS]

--perturb EPS scales each step's new momentum by 1 + EPS·h²: a map that is not symplectic by about
2·EPS·h² a step, however many digits it carries (symplecticity must fail it).
"""
import decimal
import json
import sys

from decimal import Decimal


def send(message):
    sys.stdout.write(json.dumps(message) + "\n")
    sys.stdout.flush()


def main():
    perturb = Decimal(sys.argv[sys.argv.index("--perturb") + 1]) if "--perturb" in sys.argv else Decimal(0)
    greeting = json.loads(sys.stdin.readline())
    digits = int(greeting["digits"])
    n = greeting["dimension"]
    masses = greeting["system"].get("params", {}).get("m")
    if not isinstance(masses, list) or 3 * len(masses) != n:
        send({"error": f"expected params.m as a list of {n // 3} masses"})
        return
    decimal.getcontext().prec = digits
    m = [Decimal(x) for x in masses]
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
        # Inputs rounded to the working digits first: the program computes in its own precision.
        h = +Decimal(request["h"])
        q = [+Decimal(x) for x in request["q"]]
        p = [+Decimal(x) for x in request["p"]]
        half = h / 2
        p = [pi + half * fi for pi, fi in zip(p, force(q))]
        q = [qi + h * pi / m[j // 3] for j, (qi, pi) in enumerate(zip(q, p))]
        p = [pi + half * fi for pi, fi in zip(p, force(q))]
        scale = 1 + perturb * h * h
        p = [pi * scale for pi in p]
        written = lambda x: format(x, ".%dE" % (digits - 1))
        send({"q": [written(x) for x in q], "p": [written(x) for x in p]})


if __name__ == "__main__":
    main()
