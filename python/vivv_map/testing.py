"""Run vivv on case files and read its verdicts, for a test suite that guards an integrator.

    from vivv_map.testing import run_vivv

    def test_my_integrator(tmp_path):
        run = run_vivv("cases/my-verlet.json", out=tmp_path, baseline="baseline/report.json")
        assert run.verdicts["my-verlet"]["symplecticity"] == "pass"
        assert not run.regressed          # no claim worse than in the baseline report

vivv is found as the argument `vivv`, else the environment variable VIVV, else on PATH.
Verdicts are read from the report.json vivv writes, never from its console. vivv runs with the
interpreter running this code first on PATH (a case's "python3" is that interpreter: a venv's,
where vivv_map is installed) and, where vivv_map is used from the source tree, with its folder on
PYTHONPATH: a program started by vivv imports the vivv_map its test imports.
"""
import json
import os
import pathlib
import shlex
import shutil
import subprocess
import sys
import tempfile

# After a timeout vivv gets SIGTERM, on which it ends the programs it started (their process groups
# included) and exits; SIGKILL only if it has not within this many seconds (SIGKILL would leave
# every helper a program started in a group of its own).
TERMINATION_GRACE_SECONDS = 20


class VivvError(RuntimeError):
    """vivv refused the input (exit 2: a malformed case, an unknown name, a bad option) or ended
    without a report (exit 3); the message is what vivv printed."""


# How much of one explanation an assertion's message carries (the rest is in report.json).
SHOWN_CHARACTERS = 300


def _shortened(text, limit=SHOWN_CHARACTERS):
    """`text` cut in the middle to `limit` characters: its start says what, its end says why."""
    if len(text) <= limit:
        return text
    half = (limit - 3) // 2
    return text[:half] + " … " + text[-half:]


class Verdicts(dict):
    """{case: {claim: verdict}}; a case without verdicts — one that could not run — raises a KeyError
    that says why, not only its name."""

    def __init__(self, verdicts, could_not_run, report):
        super().__init__(verdicts)
        self._could_not_run, self._report = could_not_run, report

    def __missing__(self, case):
        if case in self._could_not_run:
            raise KeyError(f"{case!r} has no verdicts: it could not run: {_shortened(self._could_not_run[case])}")
        raise KeyError(f"{case!r} has no verdicts in {self._report}; its cases: {', '.join(sorted(self)) or 'none'}"
                       + (f"; could not run: {', '.join(sorted(self._could_not_run))}" if self._could_not_run else ""))


class Run:
    """One `vivv run`: exit_code, console (stdout and stderr), report (report.json as a dict),
    out (the report directory), verdicts ({case: {claim: verdict}}), regressed ([(case, claim)]
    that regressed against the baseline), could_not_run ({case: message})."""

    def __init__(self, exit_code, console, out):
        self.exit_code, self.console, self.out = exit_code, console, pathlib.Path(out)
        self.report = json.loads((self.out / "report.json").read_text())
        self.could_not_run = {entry["name"]: entry["message"] for entry in self.report.get("refused", [])
                              if entry.get("kind") == "could-not-run"}
        self.verdicts = Verdicts({c["name"]: {claim["id"]: claim["verdict"] for claim in c["claims"]}
                                  for c in self.report["cases"]}, self.could_not_run, self.out / "report.json")
        self.regressed = [(c["name"], claim["id"]) for c in self.report["cases"] for claim in c["claims"]
                          if claim.get("baseline", {}).get("status") == "regressed"]

    def claim(self, case, claim):
        """The claim's whole record in report.json: verdict, explanation, series, evidence."""
        for c in self.report["cases"]:
            if c["name"] == case:
                for record in c["claims"]:
                    if record["id"] == claim:
                        return record
        raise KeyError(f"no claim {claim!r} of case {case!r} in {self.out / 'report.json'}")

    def explain(self):
        """Every claim that did not pass, every regression (with the claim and vivv's ratio) and every
        case that could not run (with its cause), one line each, each at most SHOWN_CHARACTERS of
        vivv's words: an assertion's message (report.json has the rest)."""
        lines = [f"{c['name']} / {claim['id']}: {claim['verdict']}: {_shortened(claim.get('explanation', ''))}"
                 for c in self.report["cases"] for claim in c["claims"] if claim["verdict"] not in ("pass", "xfail")]
        lines += [f"{case} / {claim}: regressed against the baseline: "
                  f"{_shortened(self.claim(case, claim)['baseline'].get('explanation', ''))}" for case, claim in self.regressed]
        lines += [f"{case}: could not run: {_shortened(message)}" for case, message in self.could_not_run.items()]
        return ("\n".join(lines) + f"\nreport: {self.out / 'report.html'}") if lines else "every claim passed"


def assert_verdicts(run, expected):
    """Asserts that `run` gave the `expected` verdicts, {case: {claim: verdict}} or {case: verdict}
    (every claim of the case), with a short difference: one line per claim that differs, vivv's
    reason beside it, a case that could not run with its cause, and the report's path."""
    __tracebackhide__ = True  # pytest shows the caller's line and this message, not this function
    differences = []
    for case, wanted in expected.items():
        if case in run.could_not_run:
            differences.append(f"{case}: could not run: {_shortened(run.could_not_run[case])}")
            continue
        if case not in run.verdicts:
            differences.append(f"{case}: not in the report (cases: {', '.join(sorted(run.verdicts)) or 'none'})")
            continue
        claims = wanted if isinstance(wanted, dict) else {claim: wanted for claim in run.verdicts[case]}
        for claim, verdict in claims.items():
            got = run.verdicts[case].get(claim)
            if got != verdict:
                why = run.claim(case, claim).get("explanation", "") if got is not None else "the case has no such claim"
                differences.append(f"{case} / {claim}: expected {verdict}, got {got}: {_shortened(why)}")
    if differences:
        raise AssertionError("verdicts differ:\n" + "\n".join(differences) + f"\nreport: {run.out / 'report.html'}")


def find_vivv(vivv=None):
    found = vivv or os.environ.get("VIVV") or shutil.which("vivv")
    if not found:
        raise VivvError("vivv not found: pass vivv=PATH, set VIVV, or put vivv on PATH "
                        "(cmake --build build --target vivv builds build/harness/vivv)")
    return str(found)


def vivv_environment(interpreter_folder, environment=None):
    """The environment vivv runs in: `environment` (default os.environ) with `interpreter_folder`
    first on PATH — a folder holding `python3` and `python`, each starting the interpreter running
    this code (a venv's: a script that execs it, since a symlink elsewhere would lose the venv), so
    a case's "command": ["python3", …] runs it and nothing else on PATH moves — and with the folder
    holding vivv_map on PYTHONPATH when vivv_map is not installed (used from the source tree with
    PYTHONPATH=python): the program imports the same vivv_map as the test."""
    environment = dict(os.environ if environment is None else environment)
    folder = pathlib.Path(interpreter_folder)
    for name in ("python3", "python"):
        script = folder / name
        script.write_text(f"#!/bin/sh\nexec {shlex.quote(sys.executable)} \"$@\"\n")
        script.chmod(0o755)
    environment["PATH"] = os.pathsep.join([str(folder)] + [entry for entry in environment.get("PATH", "").split(
        os.pathsep) if entry])
    package_parent = pathlib.Path(__file__).resolve().parent.parent
    if package_parent.name not in ("site-packages", "dist-packages"):
        entries = [entry for entry in environment.get("PYTHONPATH", "").split(os.pathsep) if entry]
        if str(package_parent) not in entries:
            environment["PYTHONPATH"] = os.pathsep.join([str(package_parent)] + entries)
    return environment


def run_vivv(*cases, vivv=None, out=None, baseline=None, allow_process=True, args=(), timeout=3600):
    """Run `vivv run CASES --out OUT` (a temporary directory when OUT is None) and return its Run.
    baseline: a report.json to compare every claim's orders and error constants with
    (--baseline). args: more options, a list (["--scalar", "mpfr"]) or one string split as a
    shell would ("--scalar mpfr"). Exit 2 or 3, a vivv that cannot be started, or a run beyond
    `timeout` seconds (vivv is then ended with SIGTERM, and SIGKILL only after
    TERMINATION_GRACE_SECONDS) raises VivvError."""
    out = pathlib.Path(out if out is not None else tempfile.mkdtemp(prefix="vivv-run-"))
    if isinstance(args, (str, bytes)):
        args = shlex.split(args if isinstance(args, str) else args.decode())
    command = [find_vivv(vivv), "run", *map(str, cases), "--out", str(out), "--quiet", *map(str, args)]
    if allow_process:
        command.append("--allow-process")
    if baseline is not None:
        command += ["--baseline", str(baseline)]
    with tempfile.TemporaryDirectory(prefix="vivv-interpreter-") as interpreter_folder:
        try:
            process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                       env=vivv_environment(interpreter_folder))
        except OSError as error:  # not found, not executable
            raise VivvError(f"vivv could not be started as {command[0]!r}: {error}") from None
        return _finished(process, command, out, timeout)


def _finished(process, command, out, timeout):
    """The Run of a started vivv, or VivvError (exit 2 or 3, beyond the timeout)."""
    try:
        stdout, stderr = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        process.terminate()
        try:
            stdout, stderr = process.communicate(timeout=TERMINATION_GRACE_SECONDS)
            ended = "ended by SIGTERM"
        except subprocess.TimeoutExpired:
            process.kill()
            stdout, stderr = process.communicate()
            ended = f"killed (it did not end within {TERMINATION_GRACE_SECONDS} s of SIGTERM)"
        console = (stdout or "") + (stderr or "")
        raise VivvError(f"vivv ran beyond the timeout of {timeout} s and was {ended}: {console.strip()[-2000:]}") \
            from None
    console = stdout + stderr
    if process.returncode not in (0, 1, 4):
        raise VivvError(f"vivv exited {process.returncode}: {console.strip()[-2000:]}")
    return Run(process.returncode, console, out)
