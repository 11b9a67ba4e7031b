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
from vivv_map.testing import VivvError, run_vivv  # noqa: E402

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
