#!/usr/bin/env python3
"""Stormer-Verlet for the Duffing oscillator L = w^2/2 - x^2/2 - x^4/4 in double, speaking the protocol
by hand, with the extension "steps" (k steps in one request, the last state answered): the program of
tests/process/check_steps.py.

usage: steps_verlet.py [--no-steps] [--log FILE] [--short-by M] [--steps-answer JSON] [--evaluations]
                       [--trajectory [--trajectory-fault missing|short|row|last]]

--no-steps does not take the extension up (every step crosses); --log FILE appends each request's
step count to FILE; --short-by M answers k - M steps taken (the state after them), as a program whose
state left the finite numbers on the way does; --steps-answer JSON sends JSON as the answer's "steps"
(the malformed answers vivv must refuse: "2", -1, 1.5, true, null, a count above k); --evaluations
takes up "evaluations" (two force evaluations a step). --trajectory takes up "trajectory" too (every
state of the k steps answered where the request asks for it); --trajectory-fault sends it malformed:
missing, one state short, a state of q alone, or a last state that is not the answer's q and p.
"""
import json
import sys

argv = sys.argv[1:]
option = lambda name: argv[argv.index(name) + 1] if name in argv else None
take_steps = "--no-steps" not in argv
log = option("--log")
short_by = int(option("--short-by") or 0)
steps_answer = option("--steps-answer")
count_evaluations = "--evaluations" in argv
take_trajectory = "--trajectory" in argv
trajectory_fault = option("--trajectory-fault")


def send(message):
    sys.stdout.write(json.dumps(message) + "\n")
    sys.stdout.flush()


def force(x):
    return -x - x * x * x


greeting = json.loads(sys.stdin.readline())
offered = greeting.get("extensions", [])
taken = [name for name, wanted in (("evaluations", count_evaluations), ("steps", take_steps),
                                   ("trajectory", take_steps and take_trajectory)) if wanted and name in offered]
send({"protocol": "vivv-map/1", **({"extensions": taken} if taken else {})})
for line in sys.stdin:
    request = json.loads(line)
    h, x, p = float(request["h"]), float(request["q"][0]), float(request["p"][0])
    count = request.get("steps", 1) if "steps" in taken else 1
    if log:
        with open(log, "a") as out:
            out.write(f"{count}\n")
    done = max(count - short_by, 0) if "steps" in request else count
    states = []
    for _ in range(done):
        half = p + h / 2 * force(x)
        x = x + h * half
        p = half + h / 2 * force(x)
        states.append(["%.16e" % x, "%.16e" % p])
    answer = {"q": ["%.16e" % x], "p": ["%.16e" % p]}
    if "trajectory" in taken and request.get("trajectory") is True and trajectory_fault != "missing":
        if trajectory_fault == "short":
            states = states[1:]
        elif trajectory_fault == "row":
            states[0] = states[0][:1]
        elif trajectory_fault == "last":
            states[-1] = [states[-1][0], "%.16e" % (p * (1 + 1e-10))]
        answer["trajectory"] = states
    if "evaluations" in taken:
        answer["evaluations"] = 2 * done
    if "steps" in taken and "steps" in request:
        answer["steps"] = json.loads(steps_answer) if steps_answer is not None else done
    send(answer)
