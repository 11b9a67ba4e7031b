#!/usr/bin/env python3
"""Two report.json files are byte-identical apart from their run block.

    compare_reports.py A/report.json B/report.json
    compare_reports.py --self-test

report.json is written with two-space indentation, so its top-level "run" block is the
lines from `  "run": {` up to the next line that opens another top-level key (two spaces
and a quote) or closes the document. Everything else is compared byte for byte; the
first differing line is printed. Exit 0 identical, 1 different, 2 unreadable input.
"""
import sys


def without_run_block(text):
    lines = text.split("\n")
    kept, in_run = [], False
    for line in lines:
        if line.startswith('  "run": '):
            in_run = True
            continue
        if in_run and (line.startswith('  "') or line.startswith("}")):
            in_run = False
        if not in_run:
            kept.append(line)
    return kept


def compare(a_text, b_text):
    """None when identical apart from the run block, else a description of the first difference."""
    a, b = without_run_block(a_text), without_run_block(b_text)
    for i, (x, y) in enumerate(zip(a, b)):
        if x != y:
            return "line %d (run block removed) differs:\n  %s\n  %s" % (i + 1, x[:200], y[:200])
    if len(a) != len(b):
        return "one report is longer: %d against %d lines (run block removed)" % (len(a), len(b))
    return None


def self_test():
    base = '{\n  "cases": [\n    1\n  ],\n  "run": {\n    "command_line": "%s"\n  },\n  "schema": "x"\n}'
    assert compare(base % "a", base % "b") is None, "run blocks must not count"
    assert compare(base % "a", base.replace("1", "2") % "a") is not None, "a changed case must count"
    assert compare(base % "a", base.replace('"x"', '"y"') % "a") is not None, "keys after run must count"
    print("compare_reports self-test: ok")
    return 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        texts = [open(path, encoding="utf-8").read() for path in argv[1:]]
    except OSError as error:
        print("compare_reports: %s" % error, file=sys.stderr)
        return 2
    difference = compare(*texts)
    if difference:
        print("%s and %s differ: %s" % (argv[1], argv[2], difference))
        return 1
    print("%s and %s are identical apart from the run block" % (argv[1], argv[2]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
