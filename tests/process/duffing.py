#!/usr/bin/env python3
"""Stormer-Verlet for the Duffing oscillator L = w^2/2 - x^2/2 - x^4/4 (a formula system of the
test's own), in Python's decimal at the digits vivv asks for: a map program for the process
protocol's checks in every scalar (tests/CMakeLists.txt, process/duffing-*).

usage: duffing.py [--perturb EPS] [--padded [--float32-force | --force-bits B]] [--jacobian [--wrong-jacobian-after K] [--huge-jacobian-at K]]
                  [--evaluations JSON]

--perturb EPS scales each step's new momentum by 1 + EPS·h²: a map that is not symplectic by
EPS·h² per step (symplecticity must fail; in double too). --padded computes in double and writes the digits of
its doubles as if they were the precision asked for (symplecticity must err: its Jacobian cannot
be measured). --float32-force (with --padded) rounds the force to a float32, the bug of one NumPy
array left in float32: every answer still has a double's 17 digits, 8 of them noise; --force-bits B rounds it to B significant
bits (24 is float32's). --evaluations JSON takes up the extension "evaluations" and sends JSON (2 for its two
force evaluations a step; "2", -1, 1.5 or true are the malformed counts vivv must refuse) with
every answer.
"""
import decimal
import json
import math
import sys

perturb = decimal.Decimal(sys.argv[sys.argv.index("--perturb") + 1]) if "--perturb" in sys.argv else 0
padded = "--padded" in sys.argv
force_bits = 24 if "--float32-force" in sys.argv else None
if "--force-bits" in sys.argv:
    force_bits = int(sys.argv[sys.argv.index("--force-bits") + 1])
# --jacobian: take up the extension "jacobian" and send d(x', p')/d(x, p), derived by hand;
# --wrong-jacobian-after K: from the K-th Jacobian on, dp'/dx is 1 % too large (a planted bug).
own_jacobian = "--jacobian" in sys.argv
wrong_after = int(sys.argv[sys.argv.index("--wrong-jacobian-after") + 1]) if "--wrong-jacobian-after" in sys.argv else None
# --huge-jacobian-at K: the K-th Jacobian (one vivv does not compare with differences) has every
# entry 1e160, so that J^T Omega J overflows a double to NaN (a planted bug: no NaN may pass).
evaluations = json.loads(sys.argv[sys.argv.index("--evaluations") + 1]) if "--evaluations" in sys.argv else None
huge_at = int(sys.argv[sys.argv.index("--huge-jacobian-at") + 1]) if "--huge-jacobian-at" in sys.argv else None
jacobians = 0


def rounded(value, bits):
    """value rounded to `bits` significant bits (24: a float32's, in range)."""
    mantissa, exponent = math.frexp(value)
    return math.ldexp(round(mantissa * 2**bits) / 2**bits, exponent)


def send(message):
    sys.stdout.write(json.dumps(message) + "\n")
    sys.stdout.flush()


greeting = json.loads(sys.stdin.readline())
digits = greeting["digits"]
decimal.getcontext().prec = digits + 5
own_jacobian = own_jacobian and "jacobian" in greeting.get("extensions", [])
count_evaluations = evaluations is not None and "evaluations" in greeting.get("extensions", [])
taken = [name for name, taken in (("jacobian", own_jacobian), ("evaluations", count_evaluations)) if taken]
send({"protocol": "vivv-map/1", **({"extensions": taken} if taken else {})})
for line in sys.stdin:
    request = json.loads(line)
    if padded:
        h, x, p = (float(request[k] if k == "h" else request[k][0]) for k in ("h", "q", "p"))
    else:
        h, x, p = (decimal.Decimal(request[k] if k == "h" else request[k][0]) for k in ("h", "q", "p"))
    force = lambda y: -y - y * y * y
    if force_bits is not None:
        force = lambda y: rounded(-y - y * y * y, force_bits)
    stiffness = lambda y: -1 - 3 * y * y  # dF/dx
    x0 = x
    half = p + h / 2 * force(x)
    x = x + h * half
    p = half + h / 2 * force(x)
    scale = 1 + (float(perturb) if padded else perturb) * h * h
    p = p * scale
    answer = {"q": [f"{x:.{digits - 1}e}"], "p": [f"{p:.{digits - 1}e}"]}
    if count_evaluations:
        answer["evaluations"] = evaluations
    if own_jacobian and request.get("jacobian") is True:
        dhalf_dx = h / 2 * stiffness(x0)
        dx_dx, dx_dp = 1 + h * dhalf_dx, h
        dp_dx = (dhalf_dx + h / 2 * stiffness(x) * dx_dx) * scale
        dp_dp = (1 + h / 2 * stiffness(x) * dx_dp) * scale
        jacobians += 1
        if wrong_after is not None and jacobians > wrong_after:
            dp_dx = dp_dx * (decimal.Decimal("1.01") if not padded else 1.01)
        rows = ((dx_dx, dx_dp), (dp_dx, dp_dp))
        if huge_at is not None and jacobians == huge_at:
            rows = ((1e160, 1e160), (1e160, 1e160))
        answer["jacobian"] = [[f"{v:.{digits - 1}e}" for v in row] for row in rows]
    send(answer)
