"""The "verify your own integrator" start, run verbatim: the shell block between the markers
`<!-- start: verify your own integrator -->` and `<!-- end: verify your own integrator -->` in
README.md must be the same in docs/process-protocol.md, and run in an empty folder that has this
repository's python/ and the vivv tool at build/harness/vivv, it must end with exit 0, every claim
of its case passing in the report.json it writes, and the table printed.

usage: check_readme_start.py SOURCE_DIR VIVV WORK_DIR

Its negative control runs the same block with `h` where `h / 2` belongs in the program's first
kick: that start must not pass.
"""
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys

MARKERS = (r"<!-- start: verify your own integrator -->\s*```sh\n(.*?)```\s*"
           r"<!-- end: verify your own integrator -->")


def block(path):
    found = re.findall(MARKERS, pathlib.Path(path).read_text(), re.S)
    if len(found) != 1:
        raise AssertionError(f"{path}: expected one marked start block, found {len(found)}")
    return found[0]


def run(script, source, vivv, work):
    shutil.rmtree(work, ignore_errors=True)
    (work / "build" / "harness").mkdir(parents=True)
    (work / "build" / "harness" / "vivv").symlink_to(os.path.abspath(vivv))
    (work / "python").symlink_to(pathlib.Path(source).resolve() / "python")
    result = subprocess.run(["bash", "-e", "-c", script], cwd=work, capture_output=True, text=True, timeout=600)
    problems = []
    output = result.stdout + result.stderr
    if result.returncode != 0:
        problems.append(f"exit {result.returncode}:\n{output[-2000:]}")
    report = work / "vivv-report" / "report.json"
    if not report.exists():
        return problems + ["no vivv-report/report.json"]
    verdicts = {claim["id"]: claim["verdict"] for c in json.loads(report.read_text())["cases"] for claim in c["claims"]}
    if not verdicts or set(verdicts.values()) != {"pass"}:
        problems.append(f"verdicts {verdicts}")
    if not re.search(r"my-verlet +global-order +pass +2\.\d+ +2", output):
        problems.append(f"the table has no global-order row passing at order 2:\n{output[-2000:]}")
    return problems


def main(argv):
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    source, vivv, work = argv[1], argv[2], pathlib.Path(argv[3]).resolve()
    script = block(pathlib.Path(source) / "README.md")
    if block(pathlib.Path(source) / "docs" / "process-protocol.md") != script:
        print("the start in docs/process-protocol.md differs from README.md's")
        return 1
    problems = run(script, source, vivv, work / "start")
    # Its negative control: the same start with h where h / 2 belongs in the first kick.
    broken = script.replace("p_half = p[0] - h / 2 * sin(q[0])", "p_half = p[0] - h * sin(q[0])")
    if broken == script:
        problems.append("the self-test's planted bug did not apply: the program's first kick changed")
    elif not run(broken, source, vivv, work / "broken"):
        problems.append("the start with a wrong kick passed: the check cannot fail")
    for problem in problems:
        print(problem)
    print("the README's start runs verbatim and passes; with a wrong kick it fails" if not problems else "")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
