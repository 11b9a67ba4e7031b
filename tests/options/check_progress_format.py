"""Progress lines from one writer: `vivv run --jobs 2 --progress` on three cases writes to stderr
only lines of the documented format (README, "Progress"),

    [ELAPSED s, case I of N] CASE: WHAT
    [ELAPSED s, case I of N] … still: CASE: WHAT (N s so far)

each naming one of the cases and its place I in the list of N — never two workers' text in one
line — and at most one line per case every few seconds plus one per phase change, not one per
step count.

usage: check_progress_format.py VIVV OUT_DIR CASE.json CASE.json CASE.json
       check_progress_format.py --self-test   (interleaved lines, as workers once wrote them, and lines
                                           without their case's place fail)
"""
import json
import re
import subprocess
import sys

LINE = re.compile(r"\[(\d+\.\d) s(?:, case (\d+) of (\d+))?\] (… still: )?([A-Za-z0-9_.-]+): (.+?)( \(\d+ s so far\))?")
NAME = 5


def problems_of(lines, names):
    """names: the cases' names in the run's order."""
    problems = []
    for line in lines:
        match = LINE.fullmatch(line)
        if not match or match.group(NAME) not in names:
            problems.append(f"not a progress line of one case: {line!r}")
        elif len(names) > 1 and (match.group(2), match.group(3)) != (str(names.index(match.group(NAME)) + 1),
                                                                    str(len(names))):
            problems.append(f"a line without its case's place in the run (case I of N): {line!r}")
        elif bool(match.group(4)) != bool(match.group(7)):
            problems.append(f"a 'still' line without its seconds, or seconds without 'still': {line!r}")
        elif sum(line.count(f"{name}:") for name in names) != 1:
            problems.append(f"more than one case in a line: {line!r}")
    return problems


def main(argv):
    if argv[1:] == ["--self-test"]:
        interleaved = ["[[0.00.0 s]  s] charged-midpoint: reference flow to T = 2double-pendulum-midpoint: claim x",
                       "[0.1 s, case 3 of 3] kepler-midpoint: claim global-order", "step 12 of 64",
                       "[0.2 s] kepler-midpoint: claim symplecticity", "[0.3 s, case 1 of 3] kepler-midpoint: x"]
        found = problems_of(interleaved, ["charged-midpoint", "double-pendulum-midpoint", "kepler-midpoint"])
        print("self-test:", "ok" if len(found) == 4 else f"expected 4 problems, found {found}")
        return 0 if len(found) == 4 else 1
    if len(argv) != 6:
        print(__doc__, file=sys.stderr)
        return 2
    vivv, out, cases = argv[1], argv[2], argv[3:]
    names = [json.load(open(path))["name"] for path in cases]
    result = subprocess.run([vivv, "run", *cases, "--jobs", "2", "--progress", "--out", out],
                            capture_output=True, text=True, timeout=600)
    lines = result.stderr.splitlines()
    problems = problems_of(lines, names)
    if result.returncode != 0:
        problems.append(f"exit {result.returncode}: {result.stdout[-600:]}")
    seen = {LINE.fullmatch(line).group(NAME) for line in lines if LINE.fullmatch(line)}
    if seen != set(names):
        problems.append(f"progress named {sorted(seen)}, expected every case {sorted(names)}")
    for problem in problems[:20]:
        print(problem)
    print(f"{len(lines)} progress lines for {len(names)} cases" + ("" if problems else ", each of the documented format"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
