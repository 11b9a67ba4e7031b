"""Stormer-Verlet (leapfrog) as a one-step map on (q, p), for vivv's process protocol.

    p_half = p + kick·h·F(q);  q' = q + h·p_half;  p' = p_half + (1 - kick)·h·F(q')

kick = 1/2 is Stormer-Verlet: order 2 and symplectic. `--kick 0.6` is the bug this example's
negative case plants: still a composition of symplectic kicks and drifts, but order 1.
"""
import sys

from vivv_map import fraction, serve

KICK = "1/2"


def verlet(h, q, p, force, kick):
    f = force(q)
    p = [pi + kick * h * fi for pi, fi in zip(p, f)]
    q = [qi + h * pi for qi, pi in zip(q, p)]
    f = force(q)
    p = [pi + (1 - kick) * h * fi for pi, fi in zip(p, f)]
    return q, p


if __name__ == "__main__":
    kick = sys.argv[sys.argv.index("--kick") + 1] if "--kick" in sys.argv else KICK
    serve(lambda h, q, p, force: verlet(h, q, p, force, fraction(kick)))
