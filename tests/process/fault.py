#!/usr/bin/env python3
"""A map program for vivv's process protocol (vivv-map/1) that breaks it in the way its first
argument names, after answering `good` requests properly (tests/process/check_process_maps.py).

usage: fault.py MODE [GOOD] [MARKER [ESCAPE]]

MODE: none (q' = q + h·p, p' = p), euler (explicit Euler on the harmonic oscillator), decline, hang-greeting, hang, exit, garbage,
dimension, digits, number, padded (computes in double, writes D digits), short (asked for more than
30 digits, computes in about D/2 + 3 and writes D), error, flood; and the hostile answers:
deep-answer, deep-decline, deep-error (JSON nested 120 000 deep), stderr-bytes (bytes that are not
UTF-8 on stderr, then exit 3), terminal-escapes (terminal escape sequences on stderr, then exit 3),
cut-quote (a line that is not JSON, of two-byte characters, cut by vivv's quoting), overflow (a
number beyond every scalar's range, 1e999999999, with the digits asked for), huge (1e300000000,
within MPFR's range, far beyond any orbit's), huge-once (symplectic Euler with a cubic force, as
short computes it, and 1e200, in every scalar's range, in the one answer to request GOOD + 1);
pipeline-error, pipeline-overflow and pipeline-huge-once are those by a program that takes up the
extension "pipeline".
With MARKER, it first starts a grandchild that sleeps for an hour with MARKER on its command line,
so that a test can look for survivors; ESCAPE says how that grandchild leaves the program's process
group: child (it does not), setsid, setpgid (setpgid(0, 0)) or double-fork (fork, setsid, fork,
as a daemon starts).
"""
import decimal
import json
import os
import subprocess
import sys
import time

mode = sys.argv[1]
good = int(sys.argv[2]) if len(sys.argv) > 2 else 0
if len(sys.argv) > 3:
    sleeper = [sys.executable, "-c", "import time; time.sleep(3600)", sys.argv[3]]
    escape = sys.argv[4] if len(sys.argv) > 4 else "child"
    if escape == "double-fork":  # as a daemon starts: fork, setsid, fork, the middle one exits
        if os.fork() == 0:
            os.setsid()
            if os.fork() == 0:
                os.execv(sys.executable, sleeper)
            os._exit(0)
        os.wait()
    elif escape not in ("child", "setsid", "setpgid"):
        sys.exit(f"fault.py: unknown ESCAPE {escape}")
    else:
        subprocess.Popen(sleeper, start_new_session=escape == "setsid",
                         process_group=0 if escape == "setpgid" else None,
                         stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL)
deep = "[" * 120000 + "]" * 120000


def send(message):
    sys.stdout.write((message if isinstance(message, str) else json.dumps(message)) + "\n")
    sys.stdout.flush()


greeting = json.loads(sys.stdin.readline())
if mode == "hang-greeting":
    time.sleep(3600)
if mode == "decline":
    send({"error": "this map steps the harmonic oscillator only"})
    sys.exit(0)
if mode == "deep-decline":
    send('{"error": ' + deep + '}')
    sys.exit(0)
# pipeline-error, pipeline-overflow: error and overflow, by a program that takes up the extension
# "pipeline" (vivv sends a Jacobian's requests ahead of their answers)
pipelined = mode.startswith("pipeline-") and "pipeline" in greeting.get("extensions", [])
mode = mode[len("pipeline-"):] if mode.startswith("pipeline-") else mode
send({"protocol": "vivv-map/1", **({"extensions": ["pipeline"]} if pipelined else {})})
digits = greeting["digits"]
decimal.getcontext().prec = digits + 5
for count, line in enumerate(sys.stdin):
    request = json.loads(line)
    h = decimal.Decimal(request["h"])
    q = [decimal.Decimal(x) for x in request["q"]]
    p = [decimal.Decimal(x) for x in request["p"]]
    if mode == "short" and digits > 30:  # asked for many digits, computes with about half of them
        decimal.getcontext().prec = digits // 2 + 3
    if mode in ("short", "huge-once"):  # symplectic Euler with a cubic force: products whose digits get rounded
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
        if mode == "deep-answer":
            answer = '{"q": ' + deep + ', "p": ' + json.dumps(write(p)) + '}'
        if mode == "deep-error":
            answer = '{"error": ' + deep + '}'
        if mode in ("stderr-bytes", "terminal-escapes"):
            sys.stderr.flush()
            sys.stderr.buffer.write(b"fault.py: \xff\xfe bytes \xe2\x82 cut" if mode == "stderr-bytes"
                                    else b"fault.py: \x1b[2J\x1b[31mred\x1b]0;title\x07 \xc2\x9b")
            sys.stderr.buffer.flush()
            sys.exit(3)
        if mode == "logs-then-raises":  # a long log on stderr, then the exception that says why
            for k in range(80):
                print(f"fault.py log line {k}: computing the step from q = {q}", file=sys.stderr)
            raise ValueError("the cause is at the end of stderr")
        if mode == "cut-quote":
            answer = "x" + "\u00e9" * 400
        if mode == "overflow":
            answer = {"q": ["1." + "0" * (digits - 1) + "e999999999"], "p": write(p)}
        if mode == "huge":
            answer = {"q": ["1." + "0" * (digits - 1) + "e300000000"], "p": write(p)}
        if mode == "huge-once" and count == good:
            answer = {"q": ["1." + "0" * (digits - 1) + "e200"], "p": write(p)}
        if mode == "flood":
            sys.stdout.write("x" * (3 << 20))
            sys.stdout.flush()
            time.sleep(3600)
    send(answer)
