"""run_vivv() against stand-in vivv programs written here: options given as one string, a vivv
that cannot be started, and a run beyond its timeout — ended by SIGTERM, so that the helper it
started in a process group of its own is ended too, and reported as VivvError."""
import json
import os
import pathlib
import signal
import sys
import time

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from vivv_map.testing import VivvError, assert_verdicts, run_vivv  # noqa: E402

REPORT = {"cases": [], "refused": []}


def stand_in(tmp_path, body):
    """An executable Python script standing in for vivv."""
    script = tmp_path / "vivv"
    script.write_text(f"#!{sys.executable}\nimport json, os, pathlib, signal, subprocess, sys, time\n{body}")
    script.chmod(0o755)
    return script


def test_options_given_as_one_string_are_split_as_a_shell_would(tmp_path):
    vivv = stand_in(tmp_path, f"""
out = pathlib.Path(sys.argv[sys.argv.index("--out") + 1])
out.mkdir(parents=True, exist_ok=True)
(out / "report.json").write_text(json.dumps({REPORT!r}))
(out / "argv.json").write_text(json.dumps(sys.argv[1:]))
""")
    run = run_vivv("case.json", vivv=vivv, out=tmp_path / "out", args="--verbose --scalar 'long double'")
    argv = json.loads((tmp_path / "out" / "argv.json").read_text())
    after = argv.index("--quiet") + 1
    assert argv[after:after + 3] == ["--verbose", "--scalar", "long double"]
    assert run.exit_code == 0


def test_a_vivv_that_cannot_be_started_is_a_vivv_error(tmp_path):
    with pytest.raises(VivvError, match="could not be started as 'no-such-vivv'"):
        run_vivv("case.json", vivv="no-such-vivv", out=tmp_path)


def test_a_timeout_ends_vivv_with_sigterm_and_its_helpers_with_it(tmp_path):
    pid_file = tmp_path / "helper.pid"
    vivv = stand_in(tmp_path, f"""
helper = subprocess.Popen(["sleep", "300"], start_new_session=True)  # a group of its own
pathlib.Path({str(pid_file)!r}).write_text(str(helper.pid))
def end(signum, frame):
    os.killpg(helper.pid, signal.SIGTERM)
    sys.exit(5)
signal.signal(signal.SIGTERM, end)
time.sleep(300)
""")
    with pytest.raises(VivvError, match="beyond the timeout of 2 s and was ended by SIGTERM"):
        run_vivv("case.json", vivv=vivv, out=tmp_path / "out", timeout=2)
    helper = int(pid_file.read_text())
    for _ in range(50):
        try:
            os.kill(helper, 0)
        except ProcessLookupError:
            break
        time.sleep(0.1)
    else:
        os.kill(helper, signal.SIGKILL)
        pytest.fail("the helper vivv started survived the timeout")


LONG = "the fitted order 1.03 is below 2 - 0.2: " + "x" * 5000 + " the end of vivv's reason"
REPORTED = {"cases": [{"name": "my-verlet", "claims": [
    {"id": "global-order", "verdict": "pass", "explanation": "",
     "baseline": {"status": "regressed", "series": [],
                  "explanation": "error x1.448 the baseline's error constant (allowed x1.1)"}},
    {"id": "symplecticity", "verdict": "fail", "explanation": LONG}]}],
    "refused": [{"name": "my-numpy-verlet", "file": "case.json", "kind": "could-not-run",
                 "message": "the map program 'python3 v.py' (in /tmp; python3 is /home/me/.pyenv/shims/python3), "
                            "the greeting: no answer: ModuleNotFoundError: No module named 'numpy'"}]}


def reported_run(tmp_path):
    vivv = stand_in(tmp_path, f"""
out = pathlib.Path(sys.argv[sys.argv.index("--out") + 1])
out.mkdir(parents=True, exist_ok=True)
(out / "report.json").write_text(json.dumps({REPORTED!r}))
sys.exit(4)
""")
    return run_vivv("case.json", vivv=vivv, out=tmp_path / "out")


def test_a_case_that_could_not_run_says_why_when_its_verdicts_are_asked_for(tmp_path):
    run = reported_run(tmp_path)
    with pytest.raises(KeyError, match="could not run: .*ModuleNotFoundError: No module named 'numpy'"):
        run.verdicts["my-numpy-verlet"]["global-order"]
    with pytest.raises(KeyError, match="no verdicts .*its cases: my-verlet; could not run: my-numpy-verlet"):
        run.verdicts["misspelt"]


def test_explain_names_the_regressed_claim_and_vivvs_ratio_in_short_lines(tmp_path):
    lines = reported_run(tmp_path).explain().split("\n")
    assert "my-verlet / global-order: regressed against the baseline: error x1.448 the baseline's error constant" \
        in lines[1]
    assert lines[0].startswith("my-verlet / symplecticity: fail: the fitted order 1.03")
    assert lines[0].endswith("the end of vivv's reason") and " … " in lines[0]
    assert "ModuleNotFoundError" in lines[2]
    assert max(len(line) for line in lines) < 400


def test_assert_verdicts_shows_a_short_difference(tmp_path):
    run = reported_run(tmp_path)
    assert_verdicts(run, {"my-verlet": {"global-order": "pass"}})
    with pytest.raises(AssertionError) as failure:
        assert_verdicts(run, {"my-verlet": "pass", "my-numpy-verlet": "pass"})
    message = str(failure.value)
    assert "my-verlet / symplecticity: expected pass, got fail: the fitted order 1.03" in message
    assert "my-numpy-verlet: could not run:" in message and "ModuleNotFoundError" in message
    assert "global-order" not in message
    assert len(message) < 1000
