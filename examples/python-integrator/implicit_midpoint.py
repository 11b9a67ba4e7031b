"""The implicit midpoint rule as a one-step map on (q, p), for vivv's process protocol:

    q' = q + h·(p + p')/2,   p' = p + h·F((q + q')/2)

for L = |w|^2/2 - V(q) (unit mass). Order 2 and symplectic. The midpoint m = (q + q')/2 is found
by fixed-point iteration, m = q + h/2·(p + h/2·F(m)), until an iterate repeats (the working
precision's last digit) or 200 iterations have passed.

    python3 implicit_midpoint.py [--arithmetic mpmath|numpy]
"""
import argparse
import sys

from stormer_verlet import vivv_map
from systems import Force


def midpoint(h, q, p, force):
    half = h / 2
    m = [qi + half * pi for qi, pi in zip(q, p)]
    for _ in range(200):
        f = force(m)
        following = [qi + half * (pi + half * fi) for qi, pi, fi in zip(q, p, f)]
        if following == m:
            break
        m = following
    f = force(m)
    p_next = [pi + h * fi for pi, fi in zip(p, f)]
    q_next = [2 * mi - qi for mi, qi in zip(m, q)]
    return q_next, p_next


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--arithmetic", default="mpmath", choices=["mpmath", "numpy"])
    args = parser.parse_args(sys.argv[1:])
    force = Force()
    vivv_map.serve(lambda h, q, p: midpoint(h, q, p, force), arithmetic=args.arithmetic, setup=force.setup)
