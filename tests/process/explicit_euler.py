"""Explicit Euler, q' = q + h·p, p' = p + h·F(q), for vivv's process protocol (vivv-map/1): a
first-order map that is neither symplectic nor, on Kepler, angular-momentum conserving. Every
claim a program's map can be checked by fails or passes on it for the map's own reasons, and
tests/process/check_process_words.py reads each explanation for words of a discrete Lagrangian.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples",
                                "python-integrator"))
from systems import Force  # noqa: E402
from vivv_map import serve  # noqa: E402


def euler(h, q, p, force):
    f = force(q)
    return [qi + h * pi for qi, pi in zip(q, p)], [pi + h * fi for pi, fi in zip(p, f)]


if __name__ == "__main__":
    force = Force()
    serve(lambda h, q, p: euler(h, q, p, force), setup=force.setup)
