"""A CI guard for an integrator, in pytest: vivv checks the NumPy Störmer–Verlet of this folder
(numpy-verlet-pendulum.json) and compares every fitted order and error constant with the report
kept in baseline/ (written by `vivv run numpy-verlet-pendulum.json --allow-process --out
baseline`). A change that keeps every claim passing but makes the method less accurate — a
larger error constant — fails the guard as a regression.

    VIVV=path/to/vivv python3 -m pytest test_verlet_guard.py

VIVV_GUARD_CASE names another case file of the same case name (the project's own test of this
guard runs it on a Verlet with a worse error constant, which must fail).
"""
import os
import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
try:
    import vivv_map  # noqa: F401
except ImportError:  # run from vivv's source tree: the package beside the examples
    sys.path.insert(0, str(HERE.parent.parent / "python"))
from vivv_map.testing import run_vivv  # noqa: E402

CASE = os.environ.get("VIVV_GUARD_CASE", str(HERE / "numpy-verlet-pendulum.json"))
BASELINE = HERE / "baseline" / "report.json"


def test_verlet_keeps_its_verdicts_and_error_constants(tmp_path):
    run = run_vivv(CASE, out=tmp_path, baseline=BASELINE)
    assert run.verdicts == {"numpy-verlet-pendulum": {"local-order": "pass", "global-order": "pass",
                                                      "symplecticity": "pass", "energy-behaviour": "pass"}}, \
        run.explain()
    assert not run.regressed, run.explain()
    assert run.exit_code == 0, run.console
