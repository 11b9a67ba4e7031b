"""vivv run --claims A,B: only those claims of each case run; a case listing none of them is
skipped and reported as skipped (console, report.json run.skipped_cases, junit.xml); a name that
is not a claim, or that no case of the run lists, is refused with a did-you-mean (exit 2, no
report); vivv report merges shards run with the same --claims (a skipped case holds its position)
and refuses to merge shards run with different ones.

usage: check_claims_option.py VIVV WORK_DIR CASE_WITH_GLOBAL_ORDER.json CASE_WITHOUT.json
"""
import json
import os
import shutil
import subprocess
import sys


def run(vivv, *args):
    result = subprocess.run([vivv, *args], capture_output=True, text=True, timeout=600)
    return result.returncode, result.stdout + result.stderr


def main(argv):
    if len(argv) != 5:
        print(__doc__, file=sys.stderr)
        return 2
    vivv, work, with_order, without = argv[1:]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    names = [json.load(open(path))["name"] for path in (with_order, without)]
    problems = []

    out = os.path.join(work, "selected")
    code, text = run(vivv, "run", with_order, without, "--claims", "global-order", "--out", out, "--quiet")
    if code != 0:
        problems.append(f"--claims global-order: exit {code}: {text[-800:]}")
    report = json.load(open(os.path.join(out, "report.json")))
    claims = [(c["name"], claim["id"]) for c in report["cases"] for claim in c["claims"]]
    if claims != [(names[0], "global-order")]:
        problems.append(f"the claims run were {claims}, expected only {names[0]}'s global-order")
    skipped = report["run"].get("skipped_cases", [])
    if [entry["name"] for entry in skipped] != [names[1]]:
        problems.append(f"run.skipped_cases {skipped}, expected {names[1]}")
    if report["run"]["overrides"].get("claims") != ["global-order"]:
        problems.append(f"run.overrides.claims {report['run']['overrides'].get('claims')}")
    if f"{names[1]}: skipped: --claims selects none of its claims" not in text or "1 case skipped (--claims)" not in text:
        problems.append(f"the console does not report the skipped case: {text[-800:]}")
    junit = open(os.path.join(out, "junit.xml")).read()
    if f'<testcase classname="{names[1]}" name="skipped">' not in junit:
        problems.append("junit.xml has no skipped testcase for the skipped case")

    for selection, expected in (("global-ordr", "did you mean 'global-order'"),
                                ("discrete-noether", "no case of this run lists the claim 'discrete-noether'")):
        out = os.path.join(work, "refused")
        code, text = run(vivv, "run", with_order, without, "--claims", selection, "--out", out, "--quiet")
        if code != 2 or expected not in text or os.path.exists(os.path.join(out, "report.json")):
            problems.append(f"--claims {selection}: exit {code}, expected 2 saying \"{expected}\" and no report: {text[-600:]}")

    # Two shards of one split with the same --claims merge, the skipped case holding its position.
    for index in (1, 2):
        code, text = run(vivv, "run", with_order, without, "--claims", "global-order", "--shard", f"{index}/2",
                         "--out", os.path.join(work, f"same-{index}"), "--quiet")
        if code != 0:
            problems.append(f"same --claims, shard {index}: exit {code}: {text[-600:]}")
    code, text = run(vivv, "report", os.path.join(work, "same-1", "report.json"),
                     os.path.join(work, "same-2", "report.json"), "--out", os.path.join(work, "same-merged"))
    if code != 0:
        problems.append(f"merging shards with the same --claims: exit {code}: {text[-600:]}")
    else:
        merged = json.load(open(os.path.join(work, "same-merged", "report.json")))
        if [entry["name"] for entry in merged["run"].get("skipped_cases", [])] != [names[1]]:
            problems.append(f"the merged report's skipped cases: {merged['run'].get('skipped_cases')}")
    # Two shards of one split with different --claims do not merge.
    for index, selection in ((1, "global-order"), (2, "local-order")):
        code, text = run(vivv, "run", with_order, without, "--claims", selection, "--shard", f"{index}/2",
                         "--out", os.path.join(work, f"shard-{index}"), "--quiet")
        if code not in (0, 1):
            problems.append(f"shard {index}: exit {code}: {text[-600:]}")
    code, text = run(vivv, "report", os.path.join(work, "shard-1", "report.json"),
                     os.path.join(work, "shard-2", "report.json"), "--out", os.path.join(work, "merged"))
    if code != 2 or "--claims" not in text:
        problems.append(f"merging shards with different --claims: exit {code}: {text[-600:]}")

    for problem in problems:
        print(problem)
    print("--claims: as documented" if not problems else f"{len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
