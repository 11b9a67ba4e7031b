"""The pytest guard of examples/python-integrator (test_verlet_guard.py) holds on the correct NumPy
Störmer–Verlet and fails on one with a larger error constant (numpy-verlet-pendulum-worse-constant.json
here: the same case with q' shifted by h^3/20 on every step: every claim still passes, but one
step errs 1.8 times as much and the energy 1.3 times), naming
the regression.

usage: check_guard.py VIVV EXAMPLES_DIR WORSE_CASE
"""
import os
import subprocess
import sys


def pytest(vivv, examples, case=None):
    environment = {**os.environ, "VIVV": vivv}
    if case:
        environment["VIVV_GUARD_CASE"] = case
    result = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                             os.path.join(examples, "test_verlet_guard.py")],
                            capture_output=True, text=True, env=environment, cwd=examples, timeout=600)
    return result.returncode, result.stdout + result.stderr


def main(argv):
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    vivv, examples, worse = argv[1:]
    problems = []
    code, text = pytest(vivv, examples)
    if code != 0:
        problems.append(f"the guard fails on the correct program (pytest exit {code}):\n{text[-2000:]}")
    code, text = pytest(vivv, examples, worse)
    if code != 1 or "regressed against the baseline" not in text:
        problems.append(f"the guard did not catch the worse error constant (pytest exit {code}):\n{text[-2000:]}")
    for problem in problems:
        print(problem)
    if not problems:
        print("the guard holds on the correct program and catches the worse error constant")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
