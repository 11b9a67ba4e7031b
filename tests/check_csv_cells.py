"""report.csv never hands a spreadsheet a formula (OWASP's CSV injection rule).

usage: check_csv_cells.py VIVV OUT_DIR CASE.json [CASE.json ...]
       check_csv_cells.py --self-test

Runs `VIVV run CASES --out OUT_DIR` (it must exit 0), checks every claim's verdict against the
NAME.verdicts beside each case file ("CASE CLAIM VERDICT" per line), and reads report.csv: a text
cell (case, claim, series) whose text begins with '=', '+', '-', '@', a tab or a carriage return
must be that text after an apostrophe, every other text cell the text itself, and the numeric
columns (h, error) numbers. Cases named =HYPERLINK(...), @SUM(1+1), +cmd|'calc'!A0 and -2+3
(tests/csv/) are the hostile inputs. --self-test checks that a CSV written without the apostrophe
is refused (the check's negative control). Exits 1 naming each problem, 2 on bad usage.
"""
import csv
import io
import json
import pathlib
import subprocess
import sys

FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")


def expected_cell(text):
    return "'" + text if text.startswith(FORMULA_STARTS) else text


def csv_problems(csv_text, names):
    """What is wrong with report.csv's text cells, given the case names report.json holds."""
    problems = []
    rows = list(csv.DictReader(io.StringIO(csv_text)))
    if not rows:
        return ["report.csv has no rows"]
    seen = set()
    for number, row in enumerate(rows, start=2):
        case = row["case"]
        matches = [name for name in names if expected_cell(name) == case]
        if not matches:
            problems.append(f"line {number}: case cell {case!r} is none of the names {names} as a "
                            "spreadsheet-safe cell")
        seen.update(matches)
        for column in ("case", "claim", "series"):
            if row[column].startswith(FORMULA_STARTS):
                problems.append(f"line {number}: {column} cell {row[column]!r} would be read as a formula")
        for column in ("h", "error"):
            try:
                float(row[column])
            except ValueError:
                problems.append(f"line {number}: {column} cell {row[column]!r} is not a number")
    problems += [f"no row of case {name!r}" for name in names if name not in seen]
    return problems


def verdict_problems(report, case_files):
    pinned = set()
    for case_file in case_files:
        for line in pathlib.Path(case_file).with_suffix(".verdicts").read_text().splitlines():
            if line.strip() and not line.startswith("#"):
                pinned.add(tuple(line.split()))
    found = {(case["name"], claim["id"], claim["verdict"])
             for case in report["cases"] for claim in case["claims"]}
    return [f"verdict {v} pinned but not found" for v in sorted(pinned - found)] + \
           [f"verdict {v} found but not pinned" for v in sorted(found - pinned)]


def self_test():
    names = ['=HYPERLINK("http:evil","click")', "plain"]
    header = "case,claim,series,h,N,error,floor,L_evaluations,seconds\n"
    safe = header + '"\'=HYPERLINK(""http:evil"",""click"")",global-order,e,0.1,8,1e-3,,,\n' + \
        "plain,global-order,e,0.1,8,-1e-3,,,\n"
    unsafe = safe.replace("\"'=HYPERLINK", "\"=HYPERLINK")
    if csv_problems(safe, names):
        print(f"self-test: a safe report.csv was refused: {csv_problems(safe, names)}", file=sys.stderr)
        return 1
    if not csv_problems(unsafe, names):
        print("self-test: a formula cell was let through", file=sys.stderr)
        return 1
    print("self-test: a case cell =HYPERLINK(...) without its apostrophe is refused; with it, and a "
          "negative number in a numeric column, it passes")
    return 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    vivv, out, cases = argv[1], pathlib.Path(argv[2]), argv[3:]
    run = subprocess.run([vivv, "run", *cases, "--out", str(out), "--quiet"], capture_output=True, text=True)
    if run.returncode != 0:
        print(f"vivv run exited {run.returncode}, expected 0:\n{run.stdout}{run.stderr}", file=sys.stderr)
        return 1
    report = json.loads((out / "report.json").read_text())
    names = [case["name"] for case in report["cases"]]
    problems = verdict_problems(report, cases) + csv_problems((out / "report.csv").read_text(), names)
    for problem in problems:
        print(problem, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
