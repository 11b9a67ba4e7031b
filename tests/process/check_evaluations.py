#!/usr/bin/env python3
"""The protocol's extension "evaluations": a program's own count of its work.

usage: check_evaluations.py VIVV WORK_DIR

tests/process/duffing.py --evaluations 2 (Stormer-Verlet: two force evaluations a step) beside
vivv's own midpoint rule on the same Duffing oscillator, initial state and T, in one run: each run
of the program's sweep records program_evaluations = 2 N in the report's cost (and L_evaluations
null: vivv counted none), and the work-precision diagram by evaluations draws both methods, its
caption naming the program whose cost is its own count. The negative controls: a count written
as a string, a negative one, a fraction and a boolean are each a malformed answer (the case could
not run, exit 4, naming "evaluations"); and the program without --evaluations is left out of
that diagram, as before.
"""
import json
import pathlib
import re
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent
SYSTEM = {"name": "duffing", "lagrangian": "w^2/2 - x^2/2 - x^4/4", "coordinates": ["x"], "velocities": ["w"]}
COMMON = {"system": SYSTEM, "initial": {"q": ["0.8"], "w": ["0.3"]}, "T": "2", "steps": [16, 32, 64, 128],
          "scalar": "double", "claims": ["global-order"], "expect": {"global-order": 2}}


def write_case(work, name, discretization):
    path = work / f"{name}.json"
    path.write_text(json.dumps({"name": name, **COMMON, "discretization": discretization}))
    return path


def program(work, name, *options):
    return write_case(work, name, {"kind": "process", "order": 2,
                                   "command": [sys.executable, str(HERE / "duffing.py"), *options]})


def run(vivv, work, out, *cases):
    return subprocess.run([vivv, "run", *map(str, cases), "--allow-process", "--out", str(work / out), "--quiet"],
                          capture_output=True, text=True, timeout=600)


def main(argv):
    vivv, work = argv[1], pathlib.Path(argv[2])
    work.mkdir(parents=True, exist_ok=True)
    problems = []
    midpoint = write_case(work, "duffing-midpoint", {"kind": "midpoint"})
    counted = program(work, "duffing-verlet-counted", "--evaluations", "2")
    uncounted = program(work, "duffing-verlet-uncounted")
    done = run(vivv, work, "counted", midpoint, counted, uncounted)
    if done.returncode != 0:
        problems.append(f"the run ended {done.returncode}: {done.stdout[-600:]}{done.stderr[-600:]}")
    else:
        report = json.loads((work / "counted" / "report.json").read_text())
        cases = {case["name"]: case for case in report["cases"]}
        cost = {row["N"]: row for row in cases["duffing-verlet-counted"].get("cost", [])}
        if sorted(cost) != COMMON["steps"]:
            problems.append(f"the program's cost has runs {sorted(cost)}, expected {COMMON['steps']}")
        for N, row in cost.items():
            if row.get("program_evaluations") != 2 * N or row.get("L_evaluations") is not None:
                problems.append(f"N = {N}: cost {row}, expected program_evaluations {2 * N} and L_evaluations null")
        for row in cases["duffing-verlet-uncounted"].get("cost", []):
            if "program_evaluations" in row:
                problems.append(f"the program without the extension records {row}")
        page = (work / "counted" / "report.html").read_text()
        figure = re.search(r'<figure class="work-precision"><svg[^>]*data-work-precision="evaluations-[0-9]+"'
                           r'.*?</figure>', page, re.S)
        if not figure:
            problems.append("no work-precision diagram by evaluations")
        else:
            lines = re.findall(r'data-wp-line="([^"]*)"', figure.group(0))
            if sorted(lines) != ["duffing-midpoint", "duffing-verlet-counted"]:
                problems.append(f"the diagram by evaluations draws {lines}, expected the midpoint and the counted program")
            caption = re.search(r"<figcaption>(.*?)</figcaption>", figure.group(0), re.S).group(1)
            if "duffing-verlet-counted is the evaluations its program reports" not in caption or \
                    "duffing-verlet-uncounted" not in caption:
                problems.append(f"the caption does not name whose count is its own and who is left out: {caption}")
            if "evaluations, as the program counts them" not in figure.group(0):
                problems.append("the program's points do not say whose count they are")
    for bad in ['"2"', "-1", "1.5", "true"]:
        case = program(work, "duffing-verlet-bad-count", "--evaluations", bad)
        done = run(vivv, work, "bad", case)
        said = done.stdout + done.stderr
        if done.returncode != 4 or '"evaluations"' not in said or "not the count of evaluations" not in said:
            problems.append(f"a count of {bad}: exit {done.returncode} (expected 4, naming \"evaluations\"): {said[-400:]}")
    for problem in problems:
        print(problem)
    print("extension evaluations:", "problems above" if problems else
          "counted 2 N per run, drawn by its count; 4 malformed counts refused")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
