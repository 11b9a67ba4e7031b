"""Yoshida's fourth-order composition of Stormer-Verlet, for vivv's process protocol.

    Phi_h = V(w1·h) ∘ V(w0·h) ∘ V(w1·h),  w1 = 1/(2 - 2^(1/3)),  w0 = -2^(1/3)/(2 - 2^(1/3))

Order 4 and symplectic. The weights are computed at the working precision on every step:
written as double literals they would hold the method to about 16 digits whatever D is
(vivv's precision-leak claim measures exactly that: `--double-weights` is that bug, the
example's second negative case). `--arithmetic numpy` computes the whole map in double (its
cases declare "precision": "double"), where double weights are exact enough.
"""
import argparse
import sys

from stormer_verlet import verlet, vivv_map
from systems import Force


def weights(number, double_weights):
    if type(number("1")).__module__.startswith("mpmath"):
        import mpmath
        cube_root = mpmath.cbrt(2)
    else:
        cube_root = 2 ** (1 / 3)
    w1 = 1 / (2 - cube_root)
    w0 = -cube_root * w1
    if double_weights:  # the bug of the example's negative case: the weights through a float
        w1, w0 = number(repr(float(w1))), number(repr(float(w0)))
    return w1, w0


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--double-weights", action="store_true")
    parser.add_argument("--arithmetic", default="mpmath", choices=["mpmath", "numpy"])
    args = parser.parse_args(sys.argv[1:])
    force = Force()
    constants = {}

    def setup(system, dimension, number):
        force.setup(system, dimension, number)
        constants["weights"], constants["half"] = weights(number, args.double_weights), number("0.5")

    def step(h, q, p):
        w1, w0 = constants["weights"]
        for weight in (w1, w0, w1):
            q, p = verlet(weight * h, q, p, force, constants["half"])
        return q, p

    vivv_map.serve(step, arithmetic=args.arithmetic, setup=setup)
