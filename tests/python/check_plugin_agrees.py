#!/usr/bin/env python3
"""The pytest plugin's outcome agrees with `vivv run` on the same case files, for every verdict.

    check_plugin_agrees.py VIVV SOURCE_DIR WORK_DIR

For each case file below — together they give the verdicts pass, fail, inconclusive, error, xfail,
xpass, a fail other than the one the case's xfail states, and a case that could not run — vivv runs
it (its exit status and report.json), then pytest collects the same file through the plugin
(vivv_map.pytest_plugin, loaded with -p as from the source tree). pytest must exit 0 exactly when
vivv does, and each claim must be PASSED on "pass", XFAIL on "xfail" and FAILED on anything else: a
failure pytest showed green (a strict xfail marker takes any exception) once exited 0 where vivv
exited 1. Exit 0 when they agree, 1 otherwise.
"""
import json
import os
import pathlib
import re
import subprocess
import sys


def cases(source, work):
    """(label, case file) pairs; the edited example is written into `work`."""
    wrong = json.loads((source / "cases/examples/wrong-weights-declared-order-2.json").read_text())
    for expected in wrong["xfail"].values():
        if isinstance(expected, dict) and "observed_order" in expected:
            expected["observed_order"] = ["0.1", "0.2"]  # the failure it states is not the one vivv sees
    otherwise = work / "wrong-weights-fails-otherwise.json"
    otherwise.write_text(json.dumps(wrong))
    return [("pass", source / "cases/suite/paper-midpoint.json"),
            ("fail and inconclusive", source / "tests/negative/local-order-off-centre-midpoint-double.json"),
            ("error", source / "tests/refused_claims/modified-energy-expression-rule.json"),
            ("xfail", source / "tests/expected_failures/weighted-known-to-fail.json"),
            ("xpass", source / "tests/expected_failures/known-failure-that-went-away.json"),
            ("fail otherwise than the xfail states", otherwise),
            ("could not run", source / "tests/process/module-missing-names-interpreter.json")]


def main():
    vivv, source, work = sys.argv[1], pathlib.Path(sys.argv[2]).resolve(), pathlib.Path(sys.argv[3]).resolve()
    work.mkdir(parents=True, exist_ok=True)
    (work / "pytest.ini").write_text("[pytest]\nvivv_cases = *.json\nvivv_args = --quiet\n")
    environment = dict(os.environ, VIVV=vivv, PYTHONPATH=str(source / "python"))
    problems, verdicts_seen = [], set()
    for label, case_file in cases(source, work):
        out = work / ("vivv-" + case_file.stem)
        run = subprocess.run([vivv, "run", str(case_file), "--out", str(out), "--quiet", "--allow-process"],
                             capture_output=True, text=True, timeout=900)
        report = json.loads((out / "report.json").read_text())
        verdicts = {claim["id"]: claim["verdict"] for c in report["cases"] for claim in c["claims"]}
        refused = [entry["name"] for entry in report.get("refused", [])]
        claims = json.loads(case_file.read_text())["claims"]
        verdicts_seen.update(verdicts.values())
        if refused:
            verdicts_seen.add("could-not-run")
        tested = subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-p", "vivv_map.pytest_plugin",
                                 "-c", str(work / "pytest.ini"), "--rootdir", str(work), "-rA", str(case_file)],
                                cwd=work, env=environment, capture_output=True, text=True, timeout=900)
        output = tested.stdout + tested.stderr
        outcomes = dict((claim, outcome) for outcome, claim in
                        re.findall(r"^(PASSED|FAILED|XFAIL|XPASS|ERROR) \S*::(\S+)", output, re.MULTILINE))
        print(f"{label}: vivv exit {run.returncode}, verdicts {verdicts or refused}; pytest exit {tested.returncode}, "
              f"{outcomes}")
        if (run.returncode == 0) != (tested.returncode == 0):
            problems.append(f"{label}: vivv exited {run.returncode}, pytest {tested.returncode}:\n{output[-3000:]}")
        for claim in claims:
            verdict = verdicts.get(claim, "could-not-run")
            wanted = {"pass": "PASSED", "xfail": "XFAIL"}.get(verdict, "FAILED")
            if outcomes.get(claim) != wanted:
                problems.append(f"{label}: {claim} is {verdict} in vivv's report, {outcomes.get(claim)} in pytest "
                                f"(expected {wanted})")
    for verdict in ("pass", "fail", "inconclusive", "error", "xfail", "xpass", "could-not-run"):
        if verdict not in verdicts_seen:
            problems.append(f"no case gave the verdict {verdict}: the check does not cover it")
    for problem in problems:
        print("PROBLEM:", problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
