"""Stormer-Verlet in Python's `decimal`, for the quartic oscillator L = v^2/2 - x^2/2 - x^4/4
(force -x - x^3), as a map program of protocol vivv-map/1: it computes with exactly the digits
each greeting asks for (decimal's context precision) and writes that many significant digits.
A correct program in a precision of its own, which precision-leak must pass at every digits
setting (its rounded answer can equal vivv's rounded F_h exactly: the zeros that once read as a
leak). With --model-error E the force is scaled by 1 + E: a program with a model error of E, an
order defect that more digits do not remove and no narrower format's rounding (local-order must
fail it, precision-leak must not call it a leak).

    decimal_verlet.py [--model-error E]
"""
import decimal
import json
import sys

from decimal import Decimal


MODEL_ERROR = Decimal(sys.argv[sys.argv.index("--model-error") + 1]) if "--model-error" in sys.argv else Decimal(0)


def force(q):
    return [(-x - x * x * x) * (1 + MODEL_ERROR) for x in q]


def verlet(h, q, p):
    half = h / 2
    f = force(q)
    p = [pi + half * fi for pi, fi in zip(p, f)]
    q = [qi + h * pi for qi, pi in zip(q, p)]
    f = force(q)
    p = [pi + half * fi for pi, fi in zip(p, f)]
    return q, p


def written(x, digits):
    return format(x, ".%dE" % (digits - 1))


def main():
    greeting = json.loads(sys.stdin.readline())
    digits = int(greeting["digits"])
    if greeting.get("dimension") != 1:
        print(json.dumps({"error": "this map steps the quartic oscillator in one dimension only"}), flush=True)
        return
    decimal.getcontext().prec = digits
    print(json.dumps({"protocol": "vivv-map/1"}), flush=True)
    for line in sys.stdin:
        request = json.loads(line)
        h = Decimal(request["h"])
        q = [Decimal(x) for x in request["q"]]
        p = [Decimal(x) for x in request["p"]]
        # Inputs rounded to the working digits first: the program computes in its own precision.
        h, q, p = +h, [+x for x in q], [+x for x in p]
        q, p = verlet(h, q, p)
        print(json.dumps({"q": [written(x, digits) for x in q], "p": [written(x, digits) for x in p]}), flush=True)


if __name__ == "__main__":
    main()
