#!/usr/bin/env python3
"""A map program on vivv_map.serve whose step() returns a malformed value (tests/fuzz/fuzz_inputs.py,
kind "steps"): what user code really gets wrong, after `good` proper steps of explicit Euler on the
harmonic oscillator (q' = q + h p, p' = p - h q; one coordinate, IEEE double).

usage: fuzzed_step.py VARIANT GOOD      (VARIANT an index into VARIANTS, or "count" to print their number)
"""
import decimal
import fractions
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from vivv_map import serve  # noqa: E402


class Unconvertible:
    def __float__(self):
        raise ValueError("no float here")


class Unprintable:
    def __repr__(self):
        raise RuntimeError("repr refused")

    def __iter__(self):
        raise RuntimeError("iteration refused")


class EndlessIterable:
    def __iter__(self):
        while True:
            yield 1.0


def exit_silently(q, p):
    os._exit(0)


def write_to_fd1(q, p):
    os.write(1, b"not the protocol\n")
    return [q[0]], [p[0]]


def raise_system_exit(q, p):
    sys.exit(3)


def raise_keyboard_interrupt(q, p):
    raise KeyboardInterrupt


def recurse(q, p):
    return recurse(q, p)


# Each a function of the proper (q', p') — as lists — giving what step() returns instead.
VARIANTS = [
    lambda q, p: None,
    lambda q, p: 1.0,
    lambda q, p: "abc",
    lambda q, p: b"q",
    lambda q, p: (q,),
    lambda q, p: (q, p, p),
    lambda q, p: (q, None),
    lambda q, p: (None, p),
    lambda q, p: ([], []),
    lambda q, p: (q + q, p),
    lambda q, p: ([complex(q[0], 1)], p),
    lambda q, p: ([str(q[0])], p),
    lambda q, p: ([True], p),
    lambda q, p: ([float("nan")], p),
    lambda q, p: (q, [float("inf")]),
    lambda q, p: ([10 ** 400], p),
    lambda q, p: ({"q": q[0]}, {"p": p[0]}),
    lambda q, p: (iter(q), iter(p)),
    lambda q, p: (x for x in (q, p)),
    lambda q, p: [q, p],
    lambda q, p: ([Unconvertible()], p),
    lambda q, p: (Unprintable(), p),
    lambda q, p: ([[[q[0]]]], p),
    lambda q, p: ([decimal.Decimal(repr(q[0]))], p),
    lambda q, p: ([fractions.Fraction(q[0])], p),
    lambda q, p: (q * 1000000, p),
    lambda q, p: ("1" * 1000000, p),
    lambda q, p: (EndlessIterable(), p),
    lambda q, p: ([1e308 * 10 - 1e308 * 10], p),
    exit_silently,
    write_to_fd1,
    raise_system_exit,
    raise_keyboard_interrupt,
    recurse,
]

if __name__ == "__main__":
    if sys.argv[1] == "count":
        print(len(VARIANTS))
        sys.exit(0)
    variant, good = VARIANTS[int(sys.argv[1])], int(sys.argv[2])
    taken = [0]

    def step(h, q, p):
        q_next, p_next = [q[0] + h * p[0]], [p[0] - h * q[0]]
        taken[0] += 1
        return (q_next, p_next) if taken[0] <= good else variant(q_next, p_next)

    sys.exit(serve(step, arithmetic="float"))
