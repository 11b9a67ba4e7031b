"""A map program that declines, hangs, dies or breaks protocol vivv-map/1 while its case runs: the
case could not run — exit 4 naming the program and the request, within the timeout, with
report.json recording it (kind could-not-run) and junit.xml an error of type could-not-run, and no
process of its left behind — also when vivv is ended by SIGINT or SIGTERM, alone or under --jobs.
Bad input found before anything computes (not allowed, not found, a bad option) is exit 2 with
no report.
One that pads its answers to the digits asked for is a finding instead: symplecticity errs
naming the evidence, the other claims are judged, and the report is written (exit 1).

usage: check_process_maps.py VIVV WORK_DIR

The map programs are tests/process/fault.py in its modes. Survivors are found by a marker on
the command line of a grandchild each program starts; the check first shows that it finds such
a process (its own negative control).
"""
import json
import os
import pathlib
import re
import shutil
import signal
import subprocess
import sys
import time
import uuid

HERE = pathlib.Path(__file__).resolve().parent.parent  # tests/
sys.path.insert(0, str(HERE))
# The signals' default action in the child: a background shell leaves SIGINT ignored, and vivv
# rightly keeps an ignored signal ignored (tests/check_interrupt.py).
from check_interrupt import default_signals  # noqa: E402

FAULT = HERE / "process" / "fault.py"
TIMEOUT = 2  # --process-timeout for the fault cases


def survivors(marker):
    found = []
    for entry in pathlib.Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            if marker.encode() in (entry / "cmdline").read_bytes():  # gone meanwhile: OSError
                found.append(int(entry.name))
        except OSError:
            pass
    return found


def wait_for(condition, seconds):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(0.05)
    return condition()


def could_not_run_problems(out, case_name):
    """What is missing of the record of a case that could not run in the report directory OUT:
    report.json refusing CASE_NAME with kind could-not-run and nothing else, junit.xml with an
    error of type could-not-run in its testsuite. Empty when the record is whole."""
    out = pathlib.Path(out)
    if not (out / "report.json").exists() or not (out / "junit.xml").exists():
        return [f"no report.json and junit.xml in {out}"]
    report = json.loads((out / "report.json").read_text())
    refused = report.get("refused", [])
    problems = []
    if [(entry["name"], entry.get("kind")) for entry in refused] != [(case_name, "could-not-run")]:
        problems.append(f"report.json refused {refused}, expected {case_name} as could-not-run")
    junit = (out / "junit.xml").read_text()
    if not re.search(r'<testsuite name="' + re.escape(case_name) + r'"[^>]*errors="1"[^<]*<testcase [^>]*'
                     r'name="could-not-run">\s*<error type="could-not-run"', junit):
        problems.append(f"junit.xml has no could-not-run error for {case_name}: {junit[:600]}")
    return problems


def write_case(directory, name, command, claims=("global-order",)):
    case = {"name": name, "system": {"name": "pendulum"}, "initial": {"q": ["1.1"], "w": ["0.25"]},
            "T": "1", "steps": [8, 16, 32], "scalar": "double",
            "discretization": {"kind": "process", "command": command, "order": 1},
            "claims": list(claims)}
    path = directory / f"{name}.json"
    path.write_text(json.dumps(case))
    return path


# mode, answers before the fault, what the message must say
FAULTS = [
    ("decline", 0, r"the greeting .*it declined: this map steps the harmonic oscillator only"),
    ("hang-greeting", 0, r"the greeting .*no answer within 2 s \(--process-timeout\)"),
    ("hang", 3, r"request 4 \{\"h\".*no answer within 2 s"),
    ("exit", 2, r"request 3 .*it exited with status 3; its standard error ended with: fault.py: cannot go on"),
    ("garbage", 1, r"request 2 .*it answered a line that is not JSON: hello"),
    ("dimension", 0, r"request 1 .*expected \"q\": an array of 1 decimal strings"),
    ("digits", 0, r"request 1 .*q\[0\] = \"1\.1\d*\" has \d+ significant digits, and the greeting asked for 17"),
    ("number", 0, r"request 1 .*q\[0\] is 1\.1\d*, not a decimal string"),
    ("error", 5, r"request 6 .*it answered with an error: step size too large"),
    ("flood", 0, r"request 1 .*a line longer than 1048576 characters"),
]

PIPELINED_FAULTS = [
    ("pipeline-error", 55, r"request 56 \{\"h\":\"1\.25\d*e-01\",\"p\":\[\"2\.50199\d*e-01\"\].*"
                           r"it answered with an error: step size too large"),
    ("pipeline-overflow", 55, r"request 56 \{\"h\".*\"p\":\[\"2\.50199\d*e-01\"\].*q\[0\]: "
                              r"'1\.0+e999999999' is out of range"),
]

# Programs that do not compute with the digits their greeting asked for: a finding, not bad input.
# symplecticity errs naming the evidence, global-order is judged, the report is written (exit 1).
PADDED = [
    # Symplecticity's second instance, asked for 44 digits, computes in double: its Jacobian by
    # differences at width 10^-15 sees no change at all, unlike the one at the coarse width 10^-6.
    ("padded", r"request 12 .*at width 10\^-15 differs by .* from the one at width 10\^-6 .*does not "
               r"compute with the 44 digits its greeting asked for\. Those digits, D2 = 2D \+ 10 for a "
               r"working precision of D = 17.*precision-leak"),
    # ... computes with 25 of the 44 digits: the narrow Jacobian changes with the width beyond epsilon.
    ("short", r"request 12 .*changes by .* between widths 10\^-15 and 10\^-14, more than the working "
              r"precision's epsilon .*does not compute with the 44 digits"),
]


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    vivv, work = argv[1], pathlib.Path(argv[2])
    work.mkdir(parents=True, exist_ok=True)
    problems = []

    # The survivor search finds a process that carries the marker (its negative control).
    marker = f"vivv-process-test-{uuid.uuid4().hex}"
    planted = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)", marker])
    if not wait_for(lambda: survivors(marker), 5):
        problems.append("the survivor search did not find a process planted for it")
    planted.kill()
    planted.wait()

    def run(args, expected_exit, pattern, name, within, case_name=None):
        out = work / name
        shutil.rmtree(out, ignore_errors=True)  # a report left by an earlier run is not this one's
        started = time.monotonic()
        result = subprocess.run([vivv, "run", *args, "--out", str(out), "--quiet"], capture_output=True, text=True,
                                timeout=120)
        elapsed = time.monotonic() - started
        message = result.stdout + result.stderr
        if result.returncode != expected_exit:
            problems.append(f"{name}: exit {result.returncode}, expected {expected_exit}: {message.strip()[:500]}")
        elif not re.search(pattern, message):
            problems.append(f"{name}: the message does not match '{pattern}': {message.strip()[:800]}")
        if re.search(r"AddressSanitizer|LeakSanitizer|runtime error:", message):
            problems.append(f"{name}: a sanitizer report: {message.strip()[-800:]}")
        if elapsed > within:
            problems.append(f"{name}: took {elapsed:.1f} s, more than {within} s")
        if expected_exit == 4:
            problems.extend(f"{name}: {problem}" for problem in could_not_run_problems(out, case_name))
        elif (out / "report.json").exists():
            problems.append(f"{name}: a report was written for bad input")
        print(f"{name}: exit {result.returncode} in {elapsed:.1f} s")

    for mode, good, pattern in FAULTS:
        marker = f"vivv-process-test-{uuid.uuid4().hex}"
        case = write_case(work, f"fault-{mode}", [str(FAULT), mode, str(good), marker])
        run([str(case), "--allow-process", "--process-timeout", str(TIMEOUT)], 4,
            r"fault\.py " + mode + r".* \(in .*\), " + pattern, mode, TIMEOUT + 10, f"fault-{mode}")
        if not wait_for(lambda: not survivors(marker), 10):
            problems.append(f"{mode}: processes of the map program survived vivv: {survivors(marker)}")

    # The same faults in a Jacobian's requests, which vivv sends ahead of their answers to a
    # program that took up "pipeline": the message names the request that failed (in a double
    # program, request 56 is the third of the second Jacobian's wide differences, p + 2δ, and
    # request 57, p − 2δ, is sent before its answer is read), not the last one sent.
    for mode, good, pattern in PIPELINED_FAULTS:
        case = write_case(work, f"fault-{mode}", [str(FAULT), mode, str(good)], ("symplecticity",))
        spec = json.loads(case.read_text())
        spec["discretization"]["precision"] = "double"
        case.write_text(json.dumps(spec))
        run([str(case), "--allow-process", "--process-timeout", str(TIMEOUT)], 4,
            r"fault\.py " + mode + r".* \(in .*\), " + pattern, mode, TIMEOUT + 10, f"fault-{mode}")

    # A divergence read inside a pipelined group (request 56, its answer 1e200, while request 57 is
    # already sent): symplecticity drops that run and goes on with the same program, whose next
    # answer must be its own — the one already sent for is read and left. The claims' verdicts and
    # errors equal those of the same program answering one request at a time (without that
    # reading, symplecticity errs and global-order's one-step series changes).
    reports = {}
    for mode in ("huge-once", "pipeline-huge-once"):
        case = write_case(work, f"fault-{mode}", [str(FAULT), mode, "55"], ("symplecticity", "global-order"))
        spec = json.loads(case.read_text())
        spec["discretization"]["precision"] = "double"
        case.write_text(json.dumps(spec))
        out = work / mode
        shutil.rmtree(out, ignore_errors=True)
        subprocess.run([vivv, "run", str(case), "--allow-process", "--out", str(out), "--quiet"], capture_output=True,
                       text=True, timeout=120)
        report = out / "report.json"
        claims = json.loads(report.read_text())["cases"][0]["claims"] if report.exists() else []
        reports[mode] = ({claim["id"]: (claim["verdict"], claim.get("error"), claim.get("series")) for claim in claims}
                         if report.exists() else None)
        symplecticity = next((claim for claim in claims if claim["id"] == "symplecticity"), {})
        if symplecticity.get("verdict") != "pass" or "runs that finished (N = 16, 32)" not in symplecticity.get(
                "explanation", ""):
            problems.append(f"{mode}: symplecticity not judged on N = 16, 32 after the divergence at N = 8: "
                            f"{symplecticity.get('verdict')}: {symplecticity.get('explanation', '')[:300]}")
    if reports["huge-once"] is None or reports["huge-once"] != reports["pipeline-huge-once"]:
        problems.append("a divergence in a pipelined group: the claims differ from one request at a time")
    print("divergence in a pipelined group: as one request at a time" if reports["huge-once"] ==
          reports["pipeline-huge-once"] else "divergence in a pipelined group: differs")

    for mode, pattern in PADDED:
        marker = f"vivv-process-test-{uuid.uuid4().hex}"
        case = write_case(work, f"fault-{mode}", [str(FAULT), mode, "0", marker], ("global-order", "symplecticity"))
        out = work / mode
        shutil.rmtree(out, ignore_errors=True)
        result = subprocess.run([vivv, "run", str(case), "--allow-process", "--process-timeout", str(TIMEOUT),
                                 "--out", str(out), "--quiet"], capture_output=True, text=True, timeout=120)
        verdicts = {}
        if (out / "report.json").exists():
            report = json.loads((out / "report.json").read_text())
            verdicts = {claim["id"]: claim for claim in report["cases"][0]["claims"]}
        if result.returncode != 1 or not (out / "junit.xml").exists():
            problems.append(f"{mode}: exit {result.returncode} (expected 1, a report and junit.xml): "
                            f"{(result.stdout + result.stderr).strip()[-500:]}")
        elif verdicts.get("symplecticity", {}).get("verdict") != "error" or \
                not re.search(r"fault\.py " + mode + r".* \(in .*\), " + pattern,
                              verdicts["symplecticity"].get("explanation", "")):
            problems.append(f"{mode}: symplecticity is not an error naming the evidence: "
                            f"{json.dumps(verdicts.get('symplecticity'))[:800]}")
        elif verdicts.get("global-order", {}).get("verdict") not in ("pass", "fail"):
            problems.append(f"{mode}: global-order was not judged: {verdicts.get('global-order')}")
        print(f"{mode}: exit {result.returncode}, symplecticity {verdicts.get('symplecticity', {}).get('verdict')}")
        if not wait_for(lambda: not survivors(marker), 10):
            problems.append(f"{mode}: processes of the map program survived vivv: {survivors(marker)}")

    # A case that could not run beside one that did, alone and in --jobs workers: the good case
    # keeps its verdicts in the report.
    for jobs in ("1", "2"):
        good = write_case(work, "good", [str(FAULT), "none"])
        spec = json.loads(good.read_text())
        spec["discretization"] = {"kind": "midpoint"}
        good.write_text(json.dumps(spec))
        crashing = write_case(work, "crashing", [str(FAULT), "exit", "2"])
        out = work / f"mixed-{jobs}"
        shutil.rmtree(out, ignore_errors=True)
        result = subprocess.run([vivv, "run", str(good), str(crashing), "--allow-process", "--jobs", jobs,
                                 "--out", str(out), "--quiet"], capture_output=True, text=True, timeout=120)
        problems.extend(f"mixed, --jobs {jobs}: {problem}" for problem in could_not_run_problems(out, "crashing"))
        if result.returncode != 4:
            problems.append(f"mixed, --jobs {jobs}: exit {result.returncode}, expected 4: {result.stdout[-400:]}")
        elif "1 case could not run (exit 4)" not in result.stdout:
            problems.append(f"mixed, --jobs {jobs}: the console does not count it: {result.stdout[-400:]}")
        if (out / "report.json").exists():
            cases = json.loads((out / "report.json").read_text())["cases"]
            if [(c["name"], [claim["verdict"] for claim in c["claims"]]) for c in cases] != [("good", ["pass"])]:
                problems.append(f"mixed, --jobs {jobs}: the good case's verdicts were not kept: {cases}")
        print(f"mixed, --jobs {jobs}: exit {result.returncode}")

    # Not allowed, not found, a relative program in the case file's folder.
    case = write_case(work, "not-allowed", [str(FAULT), "none"])
    run([str(case)], 2, r"discretization\.command.*fault\.py none.*vivv run --allow-process", "not-allowed", 10)
    case = write_case(work, "not-found", ["vivv-no-such-program", "x"])
    run([str(case), "--allow-process"], 2, r"the map program 'vivv-no-such-program' is not on PATH", "not-found", 10)
    run([str(HERE / "process" / "relative-program-declines.json"), "--allow-process"], 4,
        r"'\./fault\.py decline' \(in .*tests/process\), the greeting .*declined", "relative", 10,
        "process-relative-program-declines")
    run(["--allow-process", "--process-timeout", "0"], 2, r"--process-timeout: expected the seconds", "timeout-0", 10)

    # Ended by a signal while the program hangs: vivv alone, and the parent of --jobs workers.
    for sig, jobs in ((signal.SIGINT, 1), (signal.SIGTERM, 1), (signal.SIGTERM, 2), (signal.SIGINT, 2)):
        marker = f"vivv-process-test-{uuid.uuid4().hex}"
        cases = [write_case(work, f"signal-{k}", [str(FAULT), "hang", "1", marker]) for k in range(2)]
        name = f"{signal.Signals(sig).name} --jobs {jobs}"
        process = subprocess.Popen([vivv, "run", *map(str, cases), "--out", str(work / "signal"), "--quiet",
                                    "--allow-process", "--process-timeout", "60", "--jobs", str(jobs)],
                                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, preexec_fn=default_signals)
        expected = jobs  # one hanging program per running case
        if not wait_for(lambda: len(survivors(marker)) >= expected, 20):
            problems.append(f"{name}: the map programs' grandchildren never appeared")
        process.send_signal(sig)
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()
            problems.append(f"{name}: vivv did not end within 10 s of the signal")
        if not wait_for(lambda: not survivors(marker), 10):
            problems.append(f"{name}: processes survived vivv: {survivors(marker)}")
            for pid in survivors(marker):
                os.kill(pid, signal.SIGKILL)
        print(f"{name}: vivv ended with {process.returncode}")

    # A --max-seconds budget that runs out while the program hangs.
    marker = f"vivv-process-test-{uuid.uuid4().hex}"
    case = write_case(work, "budget", [str(FAULT), "hang", "1", marker])
    run([str(case), "--allow-process", "--process-timeout", "60", "--max-seconds", "2"], 2,
        r"ran past its budget of 2 s \(--max-seconds\)", "budget", 10)
    if not wait_for(lambda: not survivors(marker), 10):
        problems.append(f"budget: processes survived vivv: {survivors(marker)}")

    for problem in problems:
        print(problem, file=sys.stderr)
    if not problems:
        print(f"{len(FAULTS) + len(PIPELINED_FAULTS)} faults, {len(PADDED)} padded programs, 4 signals and a budget: as expected, "
              "no survivors")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
