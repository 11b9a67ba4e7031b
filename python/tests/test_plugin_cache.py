"""The pytest plugin's opt-in result cache (--vivv-cache): a second pytest run — `-k`, `--lf` —
reuses the first's vivv run while the case file, the program its command names, vivv and the
options are unchanged, and runs vivv again when one of them changed; JUnit gives each claim vivv's
own seconds for it; a failure names report.html; assert_verdicts hides its own frame."""
import json
import os
import pathlib
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

PYTHON_DIR = pathlib.Path(__file__).resolve().parent.parent

CASE = {"name": "my-verlet", "claims": ["global-order", "symplecticity"],
        "discretization": {"kind": "process", "command": ["python3", "verlet.py"]}}
REPORT = {"run": {"claim_seconds": {"my-verlet": {"global-order": 1.25, "symplecticity": 7.5}}},
          "cases": [{"name": "my-verlet", "claims": [
              {"id": "global-order", "verdict": "pass"},
              {"id": "symplecticity", "verdict": "fail", "explanation": "not symplectic"}]}], "refused": []}


def project(tmp_path):
    (tmp_path / "cases").mkdir()
    (tmp_path / "cases" / "my-verlet.json").write_text(json.dumps(CASE))
    (tmp_path / "cases" / "verlet.py").write_text("# the program\n")
    (tmp_path / "pytest.ini").write_text("[pytest]\nvivv_cases = cases/*.json\naddopts = -p vivv_map.pytest_plugin\n")
    vivv = tmp_path / "stand-in-vivv"
    vivv.write_text(f"""#!{sys.executable}
import json, pathlib, sys
with open({str(tmp_path / 'runs.log')!r}, "a") as log:
    log.write(" ".join(sys.argv[1:]) + "\\n")
out = pathlib.Path(sys.argv[sys.argv.index("--out") + 1])
out.mkdir(parents=True, exist_ok=True)
(out / "report.json").write_text(json.dumps({REPORT!r}))
(out / "report.html").write_text("<html></html>")
sys.exit(1)
""")
    vivv.chmod(0o755)
    return vivv


def pytest_in(tmp_path, vivv, *args):
    environment = dict(os.environ, VIVV=str(vivv), PYTHONPATH=str(PYTHON_DIR))
    result = subprocess.run([sys.executable, "-m", "pytest", "-rA", *args], cwd=tmp_path, env=environment,
                            capture_output=True, text=True, timeout=120)
    runs = (tmp_path / "runs.log").read_text().splitlines() if (tmp_path / "runs.log").exists() else []
    return result.stdout + result.stderr, len(runs)


def test_a_cached_run_serves_k_and_lf_until_what_it_is_keyed_by_changes(tmp_path):
    vivv = project(tmp_path)
    output, runs = pytest_in(tmp_path, vivv, "--vivv-cache")
    assert runs == 1 and "1 failed, 1 passed" in output, output
    output, runs = pytest_in(tmp_path, vivv, "--vivv-cache", "-k", "global-order")
    assert runs == 1 and "1 passed, 1 deselected" in output, output
    output, runs = pytest_in(tmp_path, vivv, "--vivv-cache", "--lf")
    assert runs == 1 and "1 failed" in output, output
    assert "kept by --vivv-cache" in output, output
    (tmp_path / "cases" / "verlet.py").write_text("# the program, changed\n")
    _, runs = pytest_in(tmp_path, vivv, "--vivv-cache")
    assert runs == 2  # the program changed: vivv ran again
    case = dict(CASE, T="3")
    (tmp_path / "cases" / "my-verlet.json").write_text(json.dumps(case))
    _, runs = pytest_in(tmp_path, vivv, "--vivv-cache")
    assert runs == 3  # the case changed
    _, runs = pytest_in(tmp_path, vivv, "--vivv-cache", "--cache-clear")
    assert runs == 4  # pytest's --cache-clear forgets it
    _, runs = pytest_in(tmp_path, vivv)
    assert runs == 5  # and without --vivv-cache nothing is reused


def test_the_cache_is_refused_without_pytests_cache(tmp_path):
    vivv = project(tmp_path)
    output, runs = pytest_in(tmp_path, vivv, "--vivv-cache", "-p", "no:cacheprovider")
    assert runs == 0 and "-p no:cacheprovider turned off" in output, output


def test_junit_gives_each_claim_vivvs_seconds_and_a_failure_names_the_report(tmp_path):
    vivv = project(tmp_path)
    output, _ = pytest_in(tmp_path, vivv, "-p", "no:cacheprovider", "--junitxml", "junit.xml")
    assert "report: " in output and "report.html" in output, output
    cases = {case.get("name"): case for case in ElementTree.parse(tmp_path / "junit.xml").iter("testcase")}
    # JUnit adds the item's setup and teardown (milliseconds) to the call's duration.
    assert abs(float(cases["global-order"].get("time")) - 1.25) < 0.05, cases["global-order"].attrib
    assert abs(float(cases["symplecticity"].get("time")) - 7.5) < 0.05, cases["symplecticity"].attrib


def test_assert_verdicts_shows_the_difference_not_its_own_source(tmp_path):
    report = tmp_path / "out"
    report.mkdir()
    (report / "report.json").write_text(json.dumps(REPORT))
    (tmp_path / "test_guard.py").write_text(f"""
from vivv_map.testing import Run, assert_verdicts

def test_guard():
    assert_verdicts(Run(1, "", {str(report)!r}), {{"my-verlet": "pass"}})
""")
    environment = dict(os.environ, PYTHONPATH=str(PYTHON_DIR))
    result = subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "test_guard.py"], cwd=tmp_path,
                            env=environment, capture_output=True, text=True, timeout=120)
    output = result.stdout + result.stderr
    assert "my-verlet / symplecticity: expected pass, got fail: not symplectic" in output, output
    assert f"report: {report / 'report.html'}" in output, output
    assert "differences = []" not in output, output  # the helper's own source is not shown
