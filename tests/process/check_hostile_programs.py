"""Hostile map programs and hostile text (issue 42's classes 1 to 4 and 6): each VARIANT is one
ctest, run on the vivv given.

usage: check_hostile_programs.py VIVV WORK_DIR VARIANT

  escape-setsid, escape-setpgid, escape-double-fork
      a correct-protocol program starts a helper that leaves its process group (setsid,
      setpgid(0, 0), a double fork); once vivv has exited, no process of the program is left.
  deep-answer, deep-decline, deep-error
      JSON nested 120 000 deep in an answer, a refusal of the greeting and an error answer: the
      case could not run (exit 4, report.json and junit.xml record it) naming the depth, never a crash.
  stderr-bytes, terminal-escapes, cut-quote, logs-then-raises
      a program's stderr that is not UTF-8, one with terminal escape sequences, a line that
      vivv's quoting cuts inside a two-byte character, a long log and then an exception (whose
      line, the end of stderr, the record keeps: cut in the middle): under --keep-going the report is written,
      UTF-8 throughout, the bytes repaired (U+FFFD), the escapes kept in report.json and shown
      escaped on the terminal, the cut at a character boundary; without it the same record (the
      case could not run: exit 4), UTF-8 and no raw control character on the terminal.
  case-path-bytes, out-bytes
      a case file in a folder, or an --out, whose name holds bytes that are not UTF-8: the run
      ends with its verdicts and four files in UTF-8, the bytes shown as U+FFFD.
  relative-path-entry, empty-path-entry
      PATH holds a relative entry ("bin") or an empty one (the working directory): the program
      found there is the program run, not another of the same name in the case file's folder
      (it declines, naming itself: the case could not run, exit 4).
  overflow-float128, overflow-mpfr
      an answer of 1e999999999 (beyond float128's and MPFR's range, which would round it to
      infinity): the case could not run (exit 4, recorded) naming the program, the request, the
      field and the number.
  huge-number
      an answer of 1e300000000 in MPFR (in range; energy-behaviour once took cos(q) of it for
      minutes): within a minute, global-order and energy-behaviour inconclusive, each naming the
      divergence at that h with the program, the request, the field and the number; report written.
  honest-divergence
      explicit Euler on the oscillator with h = 4 (amplification 4.1 per step: 10^19 after 32
      steps): global-order inconclusive, the run diverged at h = 4, not a refusal.
"""
import json
import os
import pathlib
import re
import shutil
import stat
import subprocess
import sys
import time
import uuid

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from check_process_maps import could_not_run_problems, survivors, wait_for, write_case  # noqa: E402

FAULT = HERE / "fault.py"


def run(vivv, args, cwd=None, env=None):
    result = subprocess.run([vivv, "run", *args], capture_output=True, cwd=cwd, env=env, timeout=300)
    return result.returncode, result.stdout, result.stderr


def utf8(data, what):
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise AssertionError(f"{what} is not UTF-8: {error}")


def expect(condition, message, problems):
    if not condition:
        problems.append(message)


def kill_survivors(marker, seconds=10):
    """Kills every process with `marker` on its command line, looking again until a look finds none:
    a helper forked between one look and its parent's kill is found by the next."""
    deadline = time.monotonic() + seconds
    while survivors(marker) and time.monotonic() < deadline:
        for pid in survivors(marker):
            try:
                os.kill(pid, 9)
            except ProcessLookupError:
                pass
        time.sleep(0.05)


def escape(vivv, work, how, problems):
    marker = f"vivv-hostile-{uuid.uuid4().hex}"
    # The survivor search finds a helper that escaped the same way from a program vivv never saw.
    # Its output goes nowhere: a helper left holding this script's stderr would keep ctest reading
    # it for the hour the helper sleeps (a double fork's helper once outlived one look for it here
    # when it was forked just after, and the test timed out with every check held).
    control = subprocess.Popen([sys.executable, str(FAULT), "hang-greeting", "0", marker, how],
                               stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    helpers = lambda: [pid for pid in survivors(marker) if pid != control.pid]  # noqa: E731
    expect(wait_for(helpers, 10), f"the control: no helper with {marker} appeared", problems)
    control.kill()
    control.wait()
    expect(wait_for(helpers, 2),
           f"the control: the {how} helper did not outlive its program (the test would prove nothing)",
           problems)
    kill_survivors(marker)
    marker = f"vivv-hostile-{uuid.uuid4().hex}"
    case = write_case(work, f"escape-{how}", [str(FAULT), "none", "0", marker, how])
    code, out, err = run(vivv, [str(case), "--allow-process", "--out", str(work / "out"), "--quiet"])
    expect(code in (0, 1), f"exit {code}: {(out + err).decode(errors='replace')[-800:]}", problems)
    left = survivors(marker) if not wait_for(lambda: not survivors(marker), 2) else []
    expect(not left, f"processes of the program outlived vivv: {left}", problems)
    kill_survivors(marker)


def deep(vivv, work, mode, problems):
    case = write_case(work, mode, [str(FAULT), mode, "1"])
    code, out, err = run(vivv, [str(case), "--allow-process", "--out", str(work / "out"), "--quiet"])
    text = (out + err).decode(errors="replace")
    expect(code == 4, f"exit {code} (139 is a crash): {text[-600:]}", problems)
    expect(re.search(r"fault\.py " + mode + r".*nested deeper than 8 levels", text),
           f"the message does not name the depth: {text[-600:]}", problems)
    problems.extend(could_not_run_problems(work / "out", mode))


def hostile_text(vivv, work, mode, problems):
    case = write_case(work, mode, [str(FAULT), mode, "1"])
    out_dir = work / "kept"
    code, out, err = run(vivv, [str(case), "--allow-process", "--keep-going", "--out", str(out_dir), "--quiet"])
    terminal = utf8(out + err, "the terminal's text")
    expect(code == 4, f"--keep-going: exit {code}: {terminal[-600:]}", problems)
    problems.extend(could_not_run_problems(out_dir, mode))
    expect(not re.search("[\x00-\x08\x0b-\x1f\x7f\x80-\x9f]", terminal),
           f"a raw control character reached the terminal: {terminal[-400:]!r}", problems)
    report_path = out_dir / "report.json"
    if not report_path.exists():
        problems.append(f"--keep-going wrote no report: {terminal[-600:]}")
        return
    for name in ("report.json", "report.html", "junit.xml", "report.csv"):
        utf8((out_dir / name).read_bytes(), name)
    message = json.loads(report_path.read_text())["refused"][0]["message"]
    if mode == "stderr-bytes":
        expect("fault.py: \ufffd\ufffd bytes \ufffd" in message, f"the bytes are not repaired: {message!r}", problems)
    if mode == "terminal-escapes":
        expect("\x1b[2J\x1b[31mred" in message, f"report.json does not keep the text: {message!r}", problems)
        expect("\\x1b[2J" in terminal, f"the terminal does not show the escape: {terminal[-400:]!r}", problems)
    if mode == "logs-then-raises":
        for where, text in (("report.json", message), ("junit.xml", (out_dir / "junit.xml").read_text()),
                            ("the terminal", terminal)):
            expect("ValueError: the cause is at the end of stderr" in text,
                   f"{where} lost the exception's line: {text[-300:]!r}", problems)
        expect(len(message) <= 2000 and "bytes left out" in message, f"not cut in the middle: {message!r}",
               problems)
    if mode == "cut-quote":
        expect(re.search("x\u00e9+… \\(801 characters\\)", message) and "\ufffd" not in message,
               f"not cut at a character boundary: {message[-200:]!r}", problems)
    code, out, err = run(vivv, [str(case), "--allow-process", "--out", str(work / "plain"), "--quiet"])
    terminal = utf8(out + err, "the terminal's text without --keep-going")
    expect(code == 4 and "fault.py " + mode in terminal, f"without --keep-going: exit {code}: {terminal[-600:]}",
           problems)
    problems.extend(f"without --keep-going: {problem}" for problem in could_not_run_problems(work / "plain", mode))
    expect(not re.search("[\x00-\x08\x0b-\x1f\x7f\x80-\x9f]", terminal),
           f"without --keep-going, a raw control character reached the terminal: {terminal[-400:]!r}", problems)


def path_bytes(vivv, work, which, problems):
    folder = os.fsencode(work) + (b"/case-\xff\xfe-folder" if which == "case" else b"/case-folder")
    out_dir = os.fsencode(work) + (b"/out-\xff" if which == "out" else b"/out")
    shutil.rmtree(folder, ignore_errors=True)
    shutil.rmtree(out_dir, ignore_errors=True)
    os.makedirs(folder)
    case = {"name": "path-bytes", "system": {"name": "harmonic_oscillator"},
            "initial": {"q": ["1"], "w": ["0"]}, "T": "1", "steps": [8, 16, 32, 64], "scalar": "double",
            "discretization": {"kind": "midpoint"}, "claims": ["global-order"]}
    case_path = folder + b"/case.json"
    with open(case_path, "w") as file:
        json.dump(case, file)
    result = subprocess.run([os.fsencode(vivv), b"run", case_path, b"--out", out_dir, b"--quiet"],
                            capture_output=True, timeout=300)
    terminal = (result.stdout + result.stderr).decode(errors="replace")
    expect(result.returncode == 0, f"exit {result.returncode}: {terminal[-600:]}", problems)
    for name in (b"report.json", b"report.html", b"junit.xml", b"report.csv"):
        path = out_dir + b"/" + name
        if not os.path.exists(path):
            problems.append(f"{name.decode()} was not written")
            continue
        with open(path, "rb") as file:
            text = utf8(file.read(), name.decode())
        if name == b"report.json":
            report = json.loads(text)
            verdicts = [claim["verdict"] for c in report["cases"] for claim in c["claims"]]
            expect(verdicts == ["pass"], f"verdicts {verdicts}", problems)
            expect("\ufffd" in json.dumps(report, ensure_ascii=False),
                   "the report does not show the path's bytes as U+FFFD", problems)


def path_entry(vivv, work, entry, problems):
    # The right program declines with RIGHT; one of the same name in the case's folder with WRONG.
    name = "vivv-hostile-map"
    found_dir = work / ("bin" if entry == "relative" else "")
    case_dir = work / "cases"
    for directory, word in ((found_dir, "RIGHT"), (case_dir, "WRONG")):
        directory.mkdir(parents=True, exist_ok=True)
        program = directory / name
        program.write_text(f"#!{sys.executable}\nimport sys\nsys.stdin.readline()\n"
                           f"print('{{\"error\": \"{word} program\"}}', flush=True)\n")
        program.chmod(program.stat().st_mode | stat.S_IXUSR)
    case = write_case(case_dir, "path-entry", [name])
    path = ("bin:" if entry == "relative" else ":") + os.environ.get("PATH", "/usr/bin:/bin")
    code, out, err = run(vivv, [str(case), "--allow-process", "--out", str(work / "out"), "--quiet"],
                         cwd=work, env={**os.environ, "PATH": path})
    text = (out + err).decode(errors="replace")
    expect(code == 4 and "declined: RIGHT program" in text,
           f"PATH={path[:20]}…: exit {code}, expected the program found on PATH to decline: {text[-600:]}",
           problems)
    problems.extend(could_not_run_problems(work / "out", "path-entry"))


def overflow(vivv, work, scalar, problems):
    case = write_case(work, f"overflow-{scalar}", [str(FAULT), "overflow", "0"])
    spec = json.loads(case.read_text())
    spec["scalar"] = scalar
    case.write_text(json.dumps(spec))
    code, out, err = run(vivv, [str(case), "--allow-process", "--out", str(work / "out"), "--quiet"])
    text = (out + err).decode(errors="replace")
    expect(code == 4, f"exit {code}: {text[-600:]}", problems)
    problems.extend(could_not_run_problems(work / "out", f"overflow-{scalar}"))
    expect(re.search(r"fault\.py overflow.*request 1 .*q\[0\]: '1\.0+e999999999' is out of range for " + scalar,
                     text), f"the message does not name program, request, field and number: {text[-600:]}",
           problems)


def divergence(vivv, work, variant, problems):
    if variant == "huge-number":
        case = write_case(work, variant, [str(FAULT), "huge", "3"], ("global-order", "energy-behaviour"))
        spec = json.loads(case.read_text())
        spec.update(scalar="mpfr", digits=30)
        pattern = (r"the run diverged at h = 0\.125: the map program '.*fault\.py huge 3' \(in .*\), "
                   r"request [0-9]+ \{.*\}: q\[0\] = 1\.0+e\+?300000000 lies beyond 10\^10 times the reference "
                   r"orbit's size")
    else:
        case = write_case(work, variant, [str(FAULT), "euler"])
        spec = json.loads(case.read_text())
        spec.update(system={"name": "harmonic_oscillator"}, initial={"q": ["1"], "w": ["0"]}, T="128",
                    steps=[32, 64, 128, 256])
        pattern = r"the run diverged at h = 4: the map program .*: [qp]\[0\] = .* lies beyond 10\^10 times"
    case.write_text(json.dumps(spec))
    started = time.monotonic()
    code, out, err = run(vivv, [str(case), "--allow-process", "--out", str(work / "out"), "--quiet"])
    elapsed = time.monotonic() - started
    text = (out + err).decode(errors="replace")
    expect(code == 1, f"exit {code}: {text[-800:]}", problems)
    expect(elapsed < 60, f"took {elapsed:.0f} s", problems)
    report = work / "out" / "report.json"
    if not report.exists():
        problems.append("no report written")
        return
    for claim in json.loads(report.read_text())["cases"][0]["claims"]:
        expect(claim["verdict"] == "inconclusive", f"{claim['id']}: {claim['verdict']}, expected inconclusive",
               problems)
        expect(re.search(pattern, claim["explanation"]),
               f"{claim['id']}: the explanation does not match: {claim['explanation'][:600]}", problems)


def main(argv):
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    vivv, work, variant = os.path.abspath(argv[1]), pathlib.Path(argv[2]).resolve() / argv[3], argv[3]
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    problems = []
    try:
        if variant in ("escape-setsid", "escape-setpgid", "escape-double-fork"):
            escape(vivv, work, variant[len("escape-"):], problems)
        elif variant.startswith("deep-"):
            deep(vivv, work, variant, problems)
        elif variant in ("stderr-bytes", "terminal-escapes", "cut-quote", "logs-then-raises"):
            hostile_text(vivv, work, variant, problems)
        elif variant in ("case-path-bytes", "out-bytes"):
            path_bytes(vivv, work, variant.split("-")[0], problems)
        elif variant in ("relative-path-entry", "empty-path-entry"):
            path_entry(vivv, work, variant.split("-")[0], problems)
        elif variant in ("huge-number", "honest-divergence"):
            divergence(vivv, work, variant, problems)
        elif variant.startswith("overflow-"):
            overflow(vivv, work, variant[len("overflow-"):], problems)
        else:
            print(f"unknown variant {variant}", file=sys.stderr)
            return 2
    except AssertionError as error:
        problems.append(str(error))
    for problem in problems:
        print(f"{variant}: {problem}", file=sys.stderr)
    if not problems:
        print(f"{variant}: held")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
