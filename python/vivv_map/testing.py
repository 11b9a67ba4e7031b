"""Run vivv on case files and read its verdicts, for a test suite that guards an integrator.

    from vivv_map.testing import run_vivv

    def test_my_integrator(tmp_path):
        run = run_vivv("cases/my-verlet.json", out=tmp_path, baseline="baseline/report.json")
        assert run.verdicts["my-verlet"]["symplecticity"] == "pass"
        assert not run.regressed          # no claim worse than in the baseline report

vivv is found as the argument `vivv`, else the environment variable VIVV, else on PATH.
Verdicts are read from the report.json vivv writes, never from its console.
"""
import json
import os
import pathlib
import shutil
import subprocess
import tempfile


class VivvError(RuntimeError):
    """vivv refused the input (exit 2: a malformed case, an unknown name, a bad option) or ended
    without a report (exit 3); the message is what vivv printed."""


class Run:
    """One `vivv run`: exit_code, console (stdout and stderr), report (report.json as a dict),
    out (the report directory), verdicts ({case: {claim: verdict}}), regressed ([(case, claim)]
    that regressed against the baseline), could_not_run ({case: message})."""

    def __init__(self, exit_code, console, out):
        self.exit_code, self.console, self.out = exit_code, console, pathlib.Path(out)
        self.report = json.loads((self.out / "report.json").read_text())
        self.verdicts = {c["name"]: {claim["id"]: claim["verdict"] for claim in c["claims"]}
                         for c in self.report["cases"]}
        self.regressed = [(c["name"], claim["id"]) for c in self.report["cases"] for claim in c["claims"]
                          if claim.get("baseline", {}).get("status") == "regressed"]
        self.could_not_run = {entry["name"]: entry["message"] for entry in self.report.get("refused", [])
                              if entry.get("kind") == "could-not-run"}

    def claim(self, case, claim):
        """The claim's whole record in report.json: verdict, explanation, series, evidence."""
        for c in self.report["cases"]:
            if c["name"] == case:
                for record in c["claims"]:
                    if record["id"] == claim:
                        return record
        raise KeyError(f"no claim {claim!r} of case {case!r} in {self.out / 'report.json'}")

    def explain(self):
        """Every claim that did not pass, with vivv's explanation: an assertion's message."""
        lines = [f"{c['name']} / {claim['id']}: {claim['verdict']}: {claim.get('explanation', '')}"
                 for c in self.report["cases"] for claim in c["claims"] if claim["verdict"] not in ("pass", "xfail")]
        lines += [f"{case} / regressed against the baseline" for case, _ in self.regressed]
        lines += [f"{case}: could not run: {message}" for case, message in self.could_not_run.items()]
        return "\n".join(lines) or "every claim passed"


def find_vivv(vivv=None):
    found = vivv or os.environ.get("VIVV") or shutil.which("vivv")
    if not found:
        raise VivvError("vivv not found: pass vivv=PATH, set VIVV, or put vivv on PATH "
                        "(cmake --build build --target vivv builds build/harness/vivv)")
    return str(found)


def run_vivv(*cases, vivv=None, out=None, baseline=None, allow_process=True, args=(), timeout=3600):
    """Run `vivv run CASES --out OUT` (a temporary directory when OUT is None) and return its Run.
    baseline: a report.json to compare every claim's orders and error constants with
    (--baseline). args: more options, e.g. ["--scalar", "mpfr"]. Exit 2 or 3 raises VivvError."""
    out = pathlib.Path(out if out is not None else tempfile.mkdtemp(prefix="vivv-run-"))
    command = [find_vivv(vivv), "run", *map(str, cases), "--out", str(out), "--quiet", *map(str, args)]
    if allow_process:
        command.append("--allow-process")
    if baseline is not None:
        command += ["--baseline", str(baseline)]
    result = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    console = result.stdout + result.stderr
    if result.returncode not in (0, 1, 4):
        raise VivvError(f"vivv exited {result.returncode}: {console.strip()[-2000:]}")
    return Run(result.returncode, console, out)
