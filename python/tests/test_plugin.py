"""The pytest plugin's collector: case files named by `vivv_cases` become one test per claim, vivv
runs once per file (a stand-in vivv here, counting its runs), -k selects claims, a case's xfail is
honoured (and an xpass fails), and a case that could not run fails its claims with the cause."""
import json
import os
import pathlib
import subprocess
import sys

PYTHON_DIR = pathlib.Path(__file__).resolve().parent.parent

CASE = {"name": "my-verlet", "claims": ["global-order", "symplecticity", "energy-behaviour", "local-order"],
        "xfail": {"local-order": {"reason": "a known defect", "observed_order": ["1.9", "2.1"]}}}
BROKEN = {"name": "my-numpy-verlet", "claims": ["global-order"]}
REPORT = {"cases": [{"name": "my-verlet", "claims": [
    {"id": "global-order", "verdict": "pass"},
    {"id": "symplecticity", "verdict": "fail", "explanation": "the (q, p) map is not symplectic: " + "y" * 3000},
    {"id": "energy-behaviour", "verdict": "inconclusive", "explanation": "to decide: T >= 32"},
    {"id": "local-order", "verdict": "xfail", "explanation": "observed order 2.0, as the case states"}]}],
    "refused": [{"name": "my-numpy-verlet", "file": "broken.json", "kind": "could-not-run",
                 "message": "the map program 'python3 v.py' (in /tmp; python3 is /opt/python3): "
                            "ModuleNotFoundError: No module named 'numpy'"}]}


def pytest_in(tmp_path, *args, report=REPORT):
    (tmp_path / "cases").mkdir()
    (tmp_path / "cases" / "my-verlet.json").write_text(json.dumps(CASE))
    (tmp_path / "cases" / "broken.json").write_text(json.dumps(BROKEN))
    (tmp_path / "pytest.ini").write_text("[pytest]\nvivv_cases = cases/*.json\n")
    (tmp_path / "conftest.py").write_text('pytest_plugins = ["vivv_map.pytest_plugin"]\n')
    runs = tmp_path / "runs.log"
    vivv = tmp_path / "stand-in-vivv"
    vivv.write_text(f"""#!{sys.executable}
import json, pathlib, sys
with open({str(runs)!r}, "a") as log:
    log.write(" ".join(sys.argv[1:]) + "\\n")
out = pathlib.Path(sys.argv[sys.argv.index("--out") + 1])
out.mkdir(parents=True, exist_ok=True)
(out / "report.json").write_text(json.dumps({report!r}))
sys.exit(1)
""")
    vivv.chmod(0o755)
    environment = dict(os.environ, VIVV=str(vivv), PYTHONPATH=str(PYTHON_DIR))
    result = subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-rA", *args],
                            cwd=tmp_path, env=environment, capture_output=True, text=True, timeout=120)
    return result.stdout + result.stderr, runs.read_text().splitlines() if runs.exists() else []


def test_each_claim_is_a_test_and_vivv_runs_once_per_file(tmp_path):
    output, runs = pytest_in(tmp_path)
    assert "1 failed" not in output
    assert "PASSED cases/my-verlet.json::global-order" in output
    assert "FAILED cases/my-verlet.json::symplecticity" in output
    assert "FAILED cases/my-verlet.json::energy-behaviour" in output
    assert "XFAIL cases/my-verlet.json::local-order" in output
    assert "FAILED cases/broken.json::global-order" in output
    assert "ModuleNotFoundError: No module named 'numpy'" in output and "python3 is /opt/python3" in output
    assert "my-verlet / symplecticity: fail: the (q, p) map is not symplectic" in output
    assert "yyyyy" * 100 not in output  # vivv's reason cut, not 3000 characters
    assert len(runs) == 2  # one run per case file, not per claim
    assert "3 failed, 1 passed, 1 xfailed" in output


def test_k_selects_claims(tmp_path):
    output, runs = pytest_in(tmp_path, "-k", "global-order")
    assert "1 failed, 1 passed, 3 deselected" in output
    assert "symplecticity" not in output.split("short test summary")[0].split("collected")[1].split("\n", 1)[0]


def test_an_xpass_fails(tmp_path):
    report = json.loads(json.dumps(REPORT))
    report["cases"][0]["claims"][3]["verdict"] = "xpass"
    output, _ = pytest_in(tmp_path, "-k", "local-order", report=report)
    assert "1 failed" in output and "XPASS(strict)" in output


def test_only_the_cases_own_expected_failure_is_an_xfail(tmp_path):
    # A claim the case marks xfail that vivv judges otherwise — failing for another reason than
    # the one stated (vivv's "fail"), error or inconclusive — fails, as vivv's exit status does.
    for verdict in ("fail", "error", "inconclusive"):
        report = json.loads(json.dumps(REPORT))
        report["cases"][0]["claims"][3].update(verdict=verdict, explanation="fails otherwise — observed order 1.894")
        directory = tmp_path / verdict
        directory.mkdir()
        output, _ = pytest_in(directory, "-k", "local-order", report=report)
        assert "1 failed" in output and "xfailed" not in output, (verdict, output)
        assert f"my-verlet / local-order: {verdict}: fails otherwise" in output


def test_a_case_that_could_not_run_fails_its_expected_failures_too(tmp_path):
    report = json.loads(json.dumps(REPORT))
    report["cases"] = []
    report["refused"].append({"name": "my-verlet", "file": "my-verlet.json", "kind": "could-not-run",
                              "message": "the map program exited 1"})
    output, _ = pytest_in(tmp_path, "-k", "my-verlet", report=report)
    assert "4 failed" in output and "xfailed" not in output, output


def collected(tmp_path, case):
    """pytest's output on a directory with the one case file `case` (a JSON value, or text)."""
    (tmp_path / "cases").mkdir()
    (tmp_path / "cases" / "odd.json").write_text(case if isinstance(case, str) else json.dumps(case))
    (tmp_path / "pytest.ini").write_text("[pytest]\nvivv_cases = cases/*.json\n")
    (tmp_path / "conftest.py").write_text('pytest_plugins = ["vivv_map.pytest_plugin"]\n')
    environment = dict(os.environ, VIVV="/nonexistent/vivv", PYTHONPATH=str(PYTHON_DIR))
    result = subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-rA"], cwd=tmp_path,
                            env=environment, capture_output=True, text=True, timeout=120)
    return result.returncode, result.stdout + result.stderr


def test_a_case_vivv_refuses_is_a_collection_error_naming_file_and_field(tmp_path):
    rows = [({"name": "c", "claims": []}, "field 'claims': expected at least one claim"),
            ({"name": "c"}, "field 'claims': expected a list of claim names"),
            ([{"name": "c", "claims": ["global-order"]}], "expected a JSON object (a case), got list"),
            ({"name": "c", "claims": ["global-order"], "xfail": ["global-order"]}, "field 'xfail': expected an object"),
            ({"name": "c", "claims": ["global-order"], "xfail": {"global-order": ["why"]}},
             "field 'xfail.global-order': expected the reason"),
            ({"name": "c", "claims": ["global-order"], "xfail": {"symplecticity": "why"}},
             "field 'xfail.symplecticity': not a claim this case checks"),
            ({"name": "c", "claims": ["global-order", "global-order"]}, "field 'claims[1]': 'global-order' is listed twice"),
            ("{not json", "not valid JSON")]
    for k, (case, message) in enumerate(rows):
        directory = tmp_path / str(k)
        directory.mkdir()
        code, output = collected(directory, case)
        assert code != 0 and "1 error" in output, (case, output)
        assert "cases/odd.json: " in output and message in output, (case, output)
        assert "AttributeError" not in output and "Traceback" not in output, (case, output)
