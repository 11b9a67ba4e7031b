"""Yoshida's fourth-order composition of Stormer-Verlet, for vivv's process protocol.

    Phi_h = V(w1·h) ∘ V(w0·h) ∘ V(w1·h),  w1 = 1/(2 - 2^(1/3)),  w0 = -2^(1/3)/(2 - 2^(1/3))

Order 4 and symplectic. The weights are computed at the working precision on every step:
written as double literals they would hold the method to about 16 digits whatever D is
(vivv's precision-leak claim measures exactly that: `--double-weights` is that bug, the
example's second negative case).
"""
import sys

import mpmath
from mpmath import mpf

from stormer_verlet import verlet
from vivv_map import fraction, serve


def yoshida4(h, q, p, force, double_weights=False):
    cube_root = mpmath.cbrt(2)
    w1 = 1 / (2 - cube_root)
    w0 = -cube_root * w1
    if double_weights:  # the bug of the example's negative case: the weights through a float
        w1, w0 = mpf(float(w1)), mpf(float(w0))
    for weight in (w1, w0, w1):
        q, p = verlet(weight * h, q, p, force, fraction("1/2"))
    return q, p


if __name__ == "__main__":
    double_weights = "--double-weights" in sys.argv
    serve(lambda h, q, p, force: yoshida4(h, q, p, force, double_weights))
