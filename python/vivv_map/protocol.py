"""The loop of protocol vivv-map/1 (docs/process-protocol.md in vivv's source tree).

    vivv:    {"protocol": "vivv-map/1", "digits": D, "dimension": n, "system": {...},
              "extensions": ["jacobian"]}
    program: {"protocol": "vivv-map/1"}   or, sending its own Jacobian,
             {"protocol": "vivv-map/1", "extensions": ["jacobian"]}   (or {"error": "why not"})
    vivv:    {"h": "...", "q": ["...", ...], "p": ["...", ...]}   (+ "jacobian": true where it reads one)
    program: {"q": [...], "p": [...]}   (+ "jacobian": [[...], ...] when agreed and asked for)

until vivv closes the program's input. Numbers are decimal strings with at least D significant
digits.
"""
import json
import sys
import traceback

from .arithmetic import arithmetic_named

PROTOCOL = "vivv-map/1"
JACOBIAN = "jacobian"


class Decline(Exception):
    """Raised by setup() when the program cannot step the system vivv greets it with: vivv ends
    the case with this reason."""


def _reply(output, message):
    output.write(json.dumps(message) + "\n")
    output.flush()


def serve(step, jacobian=None, *, arithmetic="mpmath", setup=None, input=None, output=None):
    """Answer vivv's requests with step(h, q, p) -> (q', p') until vivv closes the input.

    arithmetic: "mpmath" (mp.dps = D), "decimal" (the context's precision = D), "float" or
    "numpy" (IEEE double; the case declares "precision": "double"; q and p are NumPy arrays
    with "numpy"). jacobian(h, q, p), if given, returns the 2n x 2n matrix d(q', p')/d(q, p)
    (row i: the derivatives of the i-th component of (q', p') with respect to (q, p)), sent with
    each answer to a request marked "jacobian": true when vivv offers the extension. setup(system, dimension, number), if given, is
    called once with the greeting's system (a dict: "name", "params", or a formula's fields), the
    dimension n and number(text) converting a decimal string to the arithmetic's numbers; it
    raises Decline(reason) for a system the program cannot step. An exception in step() or
    jacobian() is sent to vivv as an error answer with its traceback's last line.
    """
    input = sys.stdin if input is None else input
    output = sys.stdout if output is None else output
    numbers = arithmetic_named(arithmetic)
    greeting = json.loads(input.readline() or "null")
    if not isinstance(greeting, dict) or greeting.get("protocol") != PROTOCOL:
        protocol = greeting.get("protocol") if isinstance(greeting, dict) else greeting
        _reply(output, {"error": f"this program speaks {PROTOCOL}, not {protocol!r}"})
        return 1
    digits, dimension = int(greeting["digits"]), int(greeting["dimension"])
    reason = numbers.start(digits)
    if reason is None and setup is not None:
        try:
            setup(greeting.get("system", {}), dimension, numbers.number)
        except Decline as decline:
            reason = str(decline)
    if reason is not None:
        _reply(output, {"error": reason})
        return 1
    send_jacobian = jacobian is not None and JACOBIAN in greeting.get("extensions", [])
    _reply(output, {"protocol": PROTOCOL, **({"extensions": [JACOBIAN]} if send_jacobian else {})})
    write = lambda values: [numbers.text(x) for x in values]  # noqa: E731
    for line in input:
        request = json.loads(line)
        h = numbers.number(request["h"])
        q = numbers.vector(numbers.number(x) for x in request["q"])
        p = numbers.vector(numbers.number(x) for x in request["p"])
        try:
            q_next, p_next = step(h, q, p)
            answer = {"q": write(q_next), "p": write(p_next)}
            if send_jacobian and request.get(JACOBIAN) is True:  # vivv asks where it reads one
                answer[JACOBIAN] = [write(row) for row in jacobian(h, q, p)]
        except Exception as error:  # the user's code: vivv names the request and this text
            where = traceback.extract_tb(error.__traceback__)[-1]
            _reply(output, {"error": f"{type(error).__name__}: {error} (at {where.filename}:{where.lineno})"})
            return 1
        _reply(output, answer)
    return 0
