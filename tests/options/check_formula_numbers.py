"""Numbers written as formulas: a case with q = pi/4, w = 1/3, T = 2*pi and k = 1/2 runs as the
same case with those values written out to 60 digits (its global errors agree to 30 digits at
40-digit working precision: no fraction passed through a double), and its report records each
formula as written (the case's "written") and as used (initial, T, parameters: the value rounded
to the working precision's digits, checked against mpmath).

usage: check_formula_numbers.py VIVV CASE.json WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys

import mpmath


def run(vivv, case, out):
    result = subprocess.run([vivv, "run", case, "--out", out, "--quiet"], capture_output=True, text=True, timeout=600)
    if result.returncode != 0:
        raise AssertionError(f"{case}: exit {result.returncode}: {result.stdout[-600:]}{result.stderr[-600:]}")
    return json.load(open(os.path.join(out, "report.json")))["cases"][0]


def main(argv):
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    vivv, case_path, work = argv[1:]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    mpmath.mp.dps = 80
    values = {"initial.q[0]": mpmath.pi / 4, "initial.w[0]": mpmath.mpf(1) / 3, "T": 2 * mpmath.pi,
              "system.params.k": mpmath.mpf(1) / 2}
    written = {"initial.q[0]": "pi/4", "initial.w[0]": "1/3", "T": "2*pi", "system.params.k": "1/2"}
    spec = json.load(open(case_path))
    decimals = {field: mpmath.nstr(value, 60, strip_zeros=False) for field, value in values.items()}
    spec.update(name="pendulum-pi-decimals", initial={"q": [decimals["initial.q[0]"]], "w": [decimals["initial.w[0]"]]},
                T=decimals["T"], system={"name": "pendulum", "params": {"k": decimals["system.params.k"]}})
    spelled = os.path.join(work, "pendulum-pi-decimals.json")
    json.dump(spec, open(spelled, "w"))
    problems = []
    formula = run(vivv, case_path, os.path.join(work, "formula"))
    plain = run(vivv, spelled, os.path.join(work, "decimals"))
    if formula.get("written") != written:
        problems.append(f"written {formula.get('written')}, expected {written}")
    if "written" in plain:
        problems.append(f"the case of decimals records formulas: {plain['written']}")
    digits = int(mpmath.ceil(formula["precision"]["bits"] * mpmath.log10(2))) + 1
    used = {"initial.q[0]": formula["initial"]["q"][0], "initial.w[0]": formula["initial"]["w"][0],
            "T": formula["T"], "system.params.k": formula["parameters"]["k"]}
    for field, value in values.items():
        if abs(mpmath.mpf(used[field]) - value) > abs(value) * mpmath.mpf(10) ** (1 - digits):
            problems.append(f"{field}: recorded as used {used[field]}, not {written[field]} to {digits} digits")
    errors = [claim["series"][0]["error"] for claim in (formula["claims"][0], plain["claims"][0])]
    for a, b in zip(*errors):
        if abs(mpmath.mpf(a) - mpmath.mpf(b)) > abs(mpmath.mpf(b)) * mpmath.mpf(10) ** -30:
            problems.append(f"global errors differ: {a} (formulas) and {b} (decimals)")
    for problem in problems:
        print(problem)
    print("formulas in numbers: recorded as written and as used, and run as their values" if not problems else "")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
