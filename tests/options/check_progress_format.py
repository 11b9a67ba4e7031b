"""Progress lines from one writer: `vivv run --jobs 2 --progress` on three cases writes to stderr
only lines of the documented format (README, "Progress"),

    [ELAPSED s] CASE: WHAT
    [ELAPSED s] … still: CASE: WHAT (N s so far)

each naming one of the cases — never two workers' text in one line — and at most one line per
case every few seconds plus one per phase change, not one per step count.

usage: check_progress_format.py VIVV OUT_DIR CASE.json CASE.json CASE.json
       check_progress_format.py --self-test   (interleaved lines, as workers once wrote them, fail)
"""
import json
import re
import subprocess
import sys

LINE = re.compile(r"\[(\d+\.\d) s\] (… still: )?([A-Za-z0-9_.-]+): (.+?)( \(\d+ s so far\))?")


def problems_of(lines, names):
    problems = []
    for line in lines:
        match = LINE.fullmatch(line)
        if not match or match.group(3) not in names:
            problems.append(f"not a progress line of one case: {line!r}")
        elif bool(match.group(2)) != bool(match.group(5)):
            problems.append(f"a 'still' line without its seconds, or seconds without 'still': {line!r}")
        elif sum(line.count(f"{name}:") for name in names) != 1:
            problems.append(f"more than one case in a line: {line!r}")
    return problems


def main(argv):
    if argv[1:] == ["--self-test"]:
        interleaved = ["[[0.00.0 s]  s] charged-midpoint: reference flow to T = 2double-pendulum-midpoint: claim x",
                       "[0.1 s] kepler-midpoint: claim global-order", "step 12 of 64"]
        found = problems_of(interleaved, {"charged-midpoint", "double-pendulum-midpoint", "kepler-midpoint"})
        print("self-test:", "ok" if len(found) == 2 else f"expected 2 problems, found {found}")
        return 0 if len(found) == 2 else 1
    if len(argv) != 6:
        print(__doc__, file=sys.stderr)
        return 2
    vivv, out, cases = argv[1], argv[2], argv[3:]
    names = {json.load(open(path))["name"] for path in cases}
    result = subprocess.run([vivv, "run", *cases, "--jobs", "2", "--progress", "--out", out],
                            capture_output=True, text=True, timeout=600)
    lines = result.stderr.splitlines()
    problems = problems_of(lines, names)
    if result.returncode != 0:
        problems.append(f"exit {result.returncode}: {result.stdout[-600:]}")
    seen = {LINE.fullmatch(line).group(3) for line in lines if LINE.fullmatch(line)}
    if seen != names:
        problems.append(f"progress named {sorted(seen)}, expected every case {sorted(names)}")
    for problem in problems[:20]:
        print(problem)
    print(f"{len(lines)} progress lines for {len(names)} cases" + ("" if problems else ", each of the documented format"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
