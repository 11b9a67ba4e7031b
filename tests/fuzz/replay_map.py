#!/usr/bin/env python3
"""A map program that replays recorded answers (tests/fuzz/fuzz_inputs.py, kind "answers").

usage: replay_map.py ANSWERS_FILE

ANSWERS_FILE holds one line per answer: the first answers the greeting, the k-th after it
answers request k, whatever the request says; past the last line the last is repeated. Lines
are sent as bytes, as they are: a fuzzed file may hold anything.
"""
import sys

with open(sys.argv[1], "rb") as file:
    lines = file.read().split(b"\n")
while len(lines) > 1 and lines[-1] == b"":
    lines.pop()
out = sys.stdout.buffer


def send(line):
    out.write(line + b"\n")
    out.flush()


sys.stdin.buffer.readline()
send(lines[0])
k = 1
for request in sys.stdin.buffer:
    send(lines[min(k, len(lines) - 1)])
    k += 1
