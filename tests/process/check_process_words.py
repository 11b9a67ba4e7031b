#!/usr/bin/env python3
"""A program's map has no discrete Lagrangian inside vivv: no explanation in the report of a
process case may speak of "L_d" or "the DEL" (issue 39: causes only where the evidence supports
them, in the words of the case).

usage: check_process_words.py REPORT.json ...
       check_process_words.py --self-test   (the check's own negative control)

Reads each report, and for every case whose discretization is a process, every explanation,
to-decide, detection limit and evidence text of its claims and their series. Exit 1 naming each
text that speaks of a discrete Lagrangian; exit 2 when a report is missing or holds no process
case (the check would prove nothing).
"""
import json
import sys

WORDS = ("L_d", "the DEL", "DEL map")
FIELDS = ("explanation", "to_decide", "detection_limit")


def texts(claim):
    """(where, text) for every text of a claim that says why it decided as it did."""
    for field in FIELDS:
        yield field, claim.get(field, "")
    for i, series in enumerate(claim.get("series", [])):
        for field in FIELDS:
            yield f"series[{i}].{field}", series.get(field, "")
    stack = [("evidence", claim.get("evidence", {}))]
    while stack:
        where, value = stack.pop()
        if isinstance(value, dict):
            stack.extend((f"{where}.{key}", item) for key, item in value.items())
        elif isinstance(value, list):
            stack.extend((f"{where}[{i}]", item) for i, item in enumerate(value))
        elif isinstance(value, str):
            yield where, value


def main(paths):
    found, process_cases = [], 0
    for path in paths:
        try:
            with open(path, encoding="utf-8") as stream:
                report = json.load(stream)
        except (OSError, ValueError) as error:
            print(f"{path}: {error}", file=sys.stderr)
            return 2
        for case in report.get("cases", []):
            if case.get("case_file", {}).get("discretization", {}).get("kind") != "process":
                continue
            process_cases += 1
            for claim in case.get("claims", []):
                for where, text in texts(claim):
                    for word in WORDS:
                        if word in text:
                            found.append(f"{case['name']} / {claim['id']} / {where}: '{word}' in: {text[:200]}")
    if process_cases == 0:
        print("no process case in " + ", ".join(paths), file=sys.stderr)
        return 2
    for line in found:
        print(line)
    print(f"{process_cases} process cases, {len(found)} texts that speak of a discrete Lagrangian")
    return 1 if found else 0


def self_test():
    """A process case whose explanation blames L_d must fail the check, and the same words in a
    case with a discrete Lagrangian must not count: exit 0 when both hold."""
    import os
    import tempfile

    def case(kind, explanation):
        return {"name": f"{kind}-case", "case_file": {"discretization": {"kind": kind}},
                "claims": [{"id": "discrete-noether", "explanation": "pass",
                            "series": [{"explanation": explanation}], "evidence": {}}]}

    blamed = "the momentum map drifts beyond rounding: L_d is not invariant under the symmetry"
    with tempfile.TemporaryDirectory() as folder:
        results = []
        for cases in ([case("process", blamed)], [case("process", "holds"), case("expression", blamed)]):
            path = os.path.join(folder, f"report{len(results)}.json")
            with open(path, "w", encoding="utf-8") as stream:
                json.dump({"cases": cases}, stream)
            results.append(main([path]))
    print(f"self-test: a process case blaming L_d exits {results[0]} (expected 1), an L_d case "
          f"exits {results[1]} (expected 0)")
    return 0 if results == [1, 0] else 1


if __name__ == "__main__":
    sys.exit(self_test() if sys.argv[1:] == ["--self-test"] else main(sys.argv[1:]))
