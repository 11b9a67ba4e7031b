#!/usr/bin/env python3
"""vivv run --keep-going: a case refused while it runs is recorded, the others keep their results.

    check_keep_going.py VIVV OUT_DIR GOOD.json FAILING.json REFUSED.json

REFUSED.json must be a case vivv refuses as bad input while it runs (a DEL step that fails).
Checks, in OUT_DIR/plain and OUT_DIR/kept:
- without --keep-going (the negative control) the run exits 2 and writes no report.json;
- with it, the run exits 2 and writes report.json, valid against reports/schema.json, with the
  good and the failing case in order and the refused one under "refused" with its message;
  junit.xml has an error of type "refused"; report.html has a "Needs attention" section linking
  to the failing claim and naming the refused case, and its verdict badges link there; the
  console says how many cases were refused.
Exit 0 on success, 1 on a failed check.
"""
import json
import os
import re
import subprocess
import sys

import jsonschema


def run(vivv, out, cases, *options):
    return subprocess.run([vivv, "run", *cases, "--out", out, "--quiet", *options],
                          capture_output=True, text=True, timeout=600)


def main(argv):
    if len(argv) != 6:
        print(__doc__, file=sys.stderr)
        return 2
    vivv, out, good, failing, refused = argv[1:]
    cases = [good, failing, refused]
    names = [json.load(open(path))["name"] for path in cases]
    problems = []

    plain = os.path.join(out, "plain")
    result = run(vivv, plain, cases)
    if result.returncode != 2:
        problems.append(f"without --keep-going: exit {result.returncode}, expected 2")
    if os.path.exists(os.path.join(plain, "report.json")):
        problems.append("without --keep-going: a report.json was written")

    kept = os.path.join(out, "kept")
    result = run(vivv, kept, cases, "--keep-going")
    if result.returncode != 2:
        problems.append(f"with --keep-going: exit {result.returncode}, expected 2\n{result.stderr}")
    try:
        report = json.load(open(os.path.join(kept, "report.json")))
    except OSError as error:
        print(f"with --keep-going: no report.json ({error})")
        return 1
    schema_path = os.path.join(os.path.dirname(__file__), "..", "reports", "schema.json")
    try:
        schema = json.load(open(schema_path))
        schema.pop("$id", None)  # a version name, not a base URL (tests/validate_report_schema.py)
        jsonschema.validate(report, schema)
    except jsonschema.ValidationError as error:
        problems.append(f"report.json breaks the schema: {error.message}")
    if [c["name"] for c in report["cases"]] != names[:2]:
        problems.append(f"cases {[c['name'] for c in report['cases']]}, expected {names[:2]}")
    entries = report.get("refused", [])
    if [e["name"] for e in entries] != names[2:]:
        problems.append(f"refused {[e['name'] for e in entries]}, expected {names[2:]}")
    elif "DEL step" not in entries[0]["message"]:
        problems.append(f"the refused case's message does not say what failed: {entries[0]['message']}")
    verdicts = [claim["verdict"] for c in report["cases"] for claim in c["claims"]]
    if "fail" not in verdicts:
        problems.append(f"the failing case's verdicts are {verdicts}")

    junit = open(os.path.join(kept, "junit.xml")).read()
    if 'type="refused"' not in junit:
        problems.append("junit.xml has no error of type refused")

    page = open(os.path.join(kept, "report.html")).read()
    attention = re.search(r'<h2 id="attention">.*?</ul>', page, re.S)
    if not attention:
        problems.append("report.html has no 'Needs attention' section")
    else:
        section = attention.group(0)
        if 'data-attention="refused"' not in section or names[2] not in section:
            problems.append("the 'Needs attention' section does not name the refused case")
        if not re.search(r'data-attention="fail" data-attention-claim="[^"]*"><span[^>]*>[^<]*</span> <a href="#claim-1-0">', section):
            problems.append("the 'Needs attention' section does not link to the failing claim")
    if not re.search(r'<a class="verdict v-fail" data-count="fail" href="#attention">', page):
        problems.append("the fail badge does not link to the 'Needs attention' section")
    if "1 case refused (exit 2)" not in result.stdout:
        problems.append(f"the console does not count the refused case:\n{result.stdout}")
    if entries and (result.stdout + result.stderr).count(entries[0]["message"][:80]) != 1:
        problems.append("the refused case's message is not printed exactly once:\n"
                        f"{result.stdout}{result.stderr}")

    for problem in problems:
        print(problem)
    print(f"--keep-going: {len(report['cases'])} cases kept, {len(entries)} refused")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
