#!/usr/bin/env python3
"""A map program for vivv's process protocol (vivv-map/1) that breaks it in the way its first
argument names, after answering `good` requests properly (tests/process/check_process_maps.py).

usage: fault.py MODE [GOOD] [MARKER]

MODE: none (q' = q + h·p, p' = p), euler (explicit Euler on the harmonic oscillator), decline, hang-greeting, hang, exit, garbage,
dimension, digits, number, padded (computes in double, writes D digits), short (asked for more than
30 digits, computes in about D/2 + 3 and writes D), error, flood. With MARKER, it first starts a grandchild that sleeps
for an hour with MARKER on its command line, so that a test can look for survivors.
"""
import decimal
import json
import subprocess
import sys
import time

mode = sys.argv[1]
good = int(sys.argv[2]) if len(sys.argv) > 2 else 0
if len(sys.argv) > 3:
    subprocess.Popen([sys.executable, "-c", "import time; time.sleep(3600)", sys.argv[3]])


def send(message):
    sys.stdout.write((message if isinstance(message, str) else json.dumps(message)) + "\n")
    sys.stdout.flush()


greeting = json.loads(sys.stdin.readline())
if mode == "hang-greeting":
    time.sleep(3600)
if mode == "decline":
    send({"error": "this map steps the harmonic oscillator only"})
    sys.exit(0)
send({"protocol": "vivv-map/1"})
digits = greeting["digits"]
decimal.getcontext().prec = digits + 5
for count, line in enumerate(sys.stdin):
    request = json.loads(line)
    h = decimal.Decimal(request["h"])
    q = [decimal.Decimal(x) for x in request["q"]]
    p = [decimal.Decimal(x) for x in request["p"]]
    if mode == "short" and digits > 30:  # asked for many digits, computes with about half of them
        decimal.getcontext().prec = digits // 2 + 3
    if mode == "short":  # symplectic Euler with a cubic force: products whose digits get rounded
        q = [qi + h * pi for qi, pi in zip(q, p)]
        p = [pi - h * qi * qi * qi for qi, pi in zip(q, p)]
    elif mode == "euler":  # explicit Euler on the harmonic oscillator: order 1, not symplectic
        omega = decimal.Decimal(greeting["system"]["params"]["omega"])
        q, p = [qi + h * pi for qi, pi in zip(q, p)], [pi - h * omega**2 * qi for qi, pi in zip(q, p)]
    else:
        q = [qi + h * pi for qi, pi in zip(q, p)]
    decimal.getcontext().prec = digits + 5
    write = lambda values: [f"{x:.{digits - 1}e}" for x in values]
    answer = {"q": write(q), "p": write(p)}
    if count >= good:
        if mode == "hang":
            time.sleep(3600)
        if mode == "exit":
            print("fault.py: cannot go on", file=sys.stderr)
            sys.exit(3)
        if mode == "garbage":
            answer = "hello"
        if mode == "dimension":
            answer = {"q": write(q + q), "p": write(p)}
        if mode == "digits":
            answer = {"q": [repr(float(x)) for x in q], "p": [repr(float(x)) for x in p]}
        if mode == "number":
            answer = {"q": [float(x) for x in q], "p": write(p)}
        if mode == "padded":  # computes in double and writes the double's digits as if they were D
            q = [float(qi) + float(h) * float(pi) for qi, pi in zip(request["q"], request["p"])]
            answer = {"q": [f"{x:.{digits - 1}e}" for x in q], "p": write(p)}
        if mode == "error":
            answer = {"error": "step size too large"}
        if mode == "flood":
            sys.stdout.write("x" * (3 << 20))
            sys.stdout.flush()
            time.sleep(3600)
    send(answer)
