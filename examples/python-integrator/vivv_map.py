"""The loop of protocol vivv-map/1 for a one-step map written with mpmath.

vivv starts the program, writes one JSON object per line to its standard input and reads one
per line from its standard output (docs/process-protocol.md in vivv's source tree):

    vivv:    {"protocol": "vivv-map/1", "digits": D, "dimension": n, "system": {...}}
    program: {"protocol": "vivv-map/1"}                 (or {"error": "why not"})
    vivv:    {"h": "...", "q": ["...", ...], "p": ["...", ...]}
    program: {"q": ["...", ...], "p": ["...", ...]}      (one answer per request)

until vivv closes the program's input. Numbers are decimal strings with at least D significant
digits; this module computes at mp.dps = D and writes D digits, trailing zeros included.

serve(step) runs the loop for step(h, q, p, force) -> (q, p), where force(q) = -grad V(q) is the
force of a system L = |w|^2/2 - V(q) with unit mass, so p = w. The catalogue systems of that
form are known here by name; for any other system the program declines.
"""
import json
import sys

import mpmath
from mpmath import mp, mpf

PROTOCOL = "vivv-map/1"


def fraction(text):
    """A number such as "0.6" or "3/5" at the working precision (never through a float)."""
    numerator, _, denominator = text.partition("/")
    return mpf(numerator) / mpf(denominator) if denominator else mpf(numerator)


def force_of(system, dimension):
    """F(q) = -grad V(q) of the named system, or a reason why it cannot be stepped here."""
    name = system.get("name")
    k = {key: mpf(value) for key, value in system.get("params", {}).items()}
    forces = {
        ("harmonic_oscillator", 1): lambda q: [-k["omega"] ** 2 * q[0]],
        ("pendulum", 1): lambda q: [-k["k"] * mpmath.sin(q[0])],
        ("kepler", 2): lambda q: [-k["mu"] * x / mpmath.sqrt(q[0] ** 2 + q[1] ** 2) ** 3 for x in q],
        ("henon_heiles", 2): lambda q: [-q[0] - 2 * k["lambda"] * q[0] * q[1],
                                        -q[1] - k["lambda"] * (q[0] ** 2 - q[1] ** 2)],
    }
    if (name, dimension) not in forces:
        known = ", ".join(sorted(system for system, _ in forces))
        return None, f"this integrator steps L = |w|^2/2 - V(q) for {known}; not '{name}' in {dimension} dimensions"
    return forces[(name, dimension)], None


def reply(message):
    sys.stdout.write(json.dumps(message) + "\n")
    sys.stdout.flush()


def serve(step):
    greeting = json.loads(sys.stdin.readline())
    if greeting.get("protocol") != PROTOCOL:
        reply({"error": f"this program speaks {PROTOCOL}, not {greeting.get('protocol')!r}"})
        return
    digits = int(greeting["digits"])
    mp.dps = digits
    force, reason = force_of(greeting["system"], int(greeting["dimension"]))
    if force is None:
        reply({"error": reason})
        return
    reply({"protocol": PROTOCOL})
    write = lambda values: [mpmath.nstr(x, digits, strip_zeros=False, min_fixed=1, max_fixed=0) for x in values]
    for line in sys.stdin:
        request = json.loads(line)
        q, p = step(mpf(request["h"]), [mpf(x) for x in request["q"]], [mpf(x) for x in request["p"]], force)
        reply({"q": write(q), "p": write(p)})
