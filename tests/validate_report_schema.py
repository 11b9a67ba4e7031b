#!/usr/bin/env python3
"""Validates report.json files against reports/schema.json (JSON Schema 2020-12).

    validate_report_schema.py SCHEMA.json REPORT.json [REPORT.json ...]
    validate_report_schema.py SCHEMA.json --find DIR [DIR ...]   (every DIR/**/report.json)

Also checks what the schema cannot say: the summary counts the verdicts, case
names are unique, and every series' h and error lists have equal length with
fit indices inside them. Exit 0 when every report is valid, 1 otherwise.
"""
import glob
import json
import os
import sys

try:
    import jsonschema
except ImportError:
    print("python3-jsonschema is not installed (bash bootstrap.sh installs it)")
    sys.exit(77)


def semantic_errors(report):
    counts = {"pass": 0, "fail": 0, "inconclusive": 0, "error": 0, "xfail": 0, "xpass": 0}
    names = set()
    for case in report["cases"]:
        if case["name"] in names:
            yield f"case {case['name']}: name occurs twice"
        names.add(case["name"])
        for claim in case["claims"]:
            counts[claim["verdict"]] += 1
            if claim["series"] and claim["decisive_series"] >= len(claim["series"]):
                yield f"{case['name']}/{claim['id']}: decisive series {claim['decisive_series']} outside its series"
            if claim["verdict"] == "inconclusive" and "to decide" not in claim["explanation"]:
                yield f"{case['name']}/{claim['id']}: inconclusive without saying what would decide it"
            for series in claim["series"]:
                where = f"{case['name']}/{claim['id']}/{series['label']}"
                if len(series["h"]) != len(series["error"]):
                    yield f"{where}: {len(series['h'])} steps but {len(series['error'])} errors"
                points = series.get("fit_points", {"used": [], "dropped": []})
                for index in points["used"] + [d["index"] for d in points["dropped"]]:
                    if index >= len(series["h"]):
                        yield f"{where}: fit index {index} outside the series"
    if counts != report["summary"]:
        yield f"summary {report['summary']} does not count the verdicts {counts}"


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    with open(argv[1]) as f:
        schema = json.load(f)
    # "$id" names the schema's version ("vivv-report/6"), not a URL its "#/$defs/..." references
    # resolve against: Debian 12's jsonschema (4.10) would resolve them to "vivv-report/vivv-report/6".
    schema.pop("$id", None)
    validator_class = jsonschema.validators.validator_for(schema)
    validator_class.check_schema(schema)
    validator = validator_class(schema)
    paths = argv[2:]
    if paths[0] == "--find":
        paths = sorted(p for d in paths[1:] for p in glob.glob(os.path.join(d, "**", "report.json"),
                                                                 recursive=True))
        if not paths:
            print("no report.json found")
            return 1
    failed = False
    for path in paths:
        with open(path) as f:
            report = json.load(f)
        problems = [f"{'/'.join(map(str, e.absolute_path)) or '(root)'}: {e.message}"
                    for e in validator.iter_errors(report)]
        if not problems:
            problems = list(semantic_errors(report))
        for problem in problems:
            print(f"{path}: {problem}")
        failed = failed or bool(problems)
        print(f"{path}: {'INVALID' if problems else 'valid'} ({len(report.get('cases', []))} cases)")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
