"""Every claim `vivv list` names has a negative control that fails it, and one (the same or
another) on a system of at least six coordinates (issue 50: no path may assume a small n).

usage: check_negative_coverage.py VIVV NEGATIVE_CASES_DIR NEGATIVE_REPORTS_DIR

Reads the claims from `VIVV list` and, for every case file NAME.json in
NEGATIVE_CASES_DIR, the report of its run, NEGATIVE_REPORTS_DIR/NAME/report.json;
exits 1 naming each claim that no negative case fails, or none on six coordinates or more.
"""
LARGE = 6
import json
import pathlib
import re
import subprocess
import sys


def listed_claims(vivv):
    listing = subprocess.run([vivv, "list"], check=True, capture_output=True, text=True).stdout
    block = listing.split("claims:\n", 1)[1].split("\ncases", 1)[0]
    return {match.group(1) for match in re.finditer(r"^  ([a-z-]+) \[", block, re.M)}


def failed_claims(cases, reports):
    failed = {}
    for case_file in sorted(pathlib.Path(cases).glob("*.json")):
        report = json.loads((pathlib.Path(reports) / case_file.stem / "report.json").read_text())
        for case in report["cases"]:
            for claim in case["claims"]:
                if claim["verdict"] == "fail":
                    coordinates = len(case.get("initial", {}).get("q", []))
                    failed.setdefault(claim["id"], []).append((case["name"], coordinates))
    return failed


def main(argv):
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    claims = listed_claims(argv[1])
    failed = failed_claims(argv[2], argv[3])
    missing = sorted(claims - set(failed))
    small = sorted(claim for claim in claims & set(failed)
                   if all(coordinates < LARGE for _, coordinates in failed[claim]))
    for claim in sorted(claims & set(failed)):
        print(f"{claim}: failed by {', '.join(f'{name} ({n})' for name, n in failed[claim])}")
    for claim in missing:
        print(f"{claim}: no negative control in tests/negative fails it")
    for claim in small:
        print(f"{claim}: no negative control on {LARGE} coordinates or more fails it")
    return 1 if missing or small or not claims else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
