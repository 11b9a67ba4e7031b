#!/usr/bin/python3
"""The memory vivv estimates for a case against the peak it measures, at sizes n = 64 ... 1024.

    /usr/bin/python3 bench/memory_table.py VIVV [--systems chain,gravity,lj] [--sizes 64,128,...] [--check]

For each system and size it writes a case (below), asks `VIVV run CASE --plan` for the estimate,
runs the case and reads the process's peak resident memory (VmHWM of /proc/PID/status, polled
every 20 ms: vivv's own pages, not those of a program it starts), and prints one row of a
Markdown table: estimate, peak, their ratio, the reference's Taylor orders the plan states and
those the run's report names, wall time and the verdicts. docs/performance.md
holds a run of it. With --check it fails (exit 1) when a peak is outside [estimate / 2, 2 x
estimate], when the plan's reference orders differ from the run's, or when a verdict is not pass
(the ctest scale/memory-estimate runs it on small sizes).

The systems (formulas with indexed families, double unless said):
- chain: L = sum v_i^2/2 - sum (x_{i+1} - x_i)^2/2 - sum x_i^4/4, fixed ends, the midpoint rule,
  global-order, local-order and symplecticity over T = 1, N = 20 ... 160;
- gravity: bodies in space, masses 1/i, all pairs, on a cubic lattice of spacing 1, the midpoint
  rule, global-order over T = 1/4, N = 8 ... 64 (n = 3 x bodies);
- lj: the Lennard-Jones cluster of examples/python-integrator through its NumPy Verlet
  (a double program: vivv's side in float128), global-order over T = 1/4, N = 8 ... 64.
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def chain_case(n):
    return {
        "name": f"memory-chain-{n}",
        "system": {
            "name": f"quartic-chain-{n}",
            "coordinates": [{"x": [n]}],
            "velocities": [{"v": [n]}],
            "lagrangian": f"sum(i = 1..{n}, v[i]^2)/2 - (x[1]^2 + sum(i = 1..{n - 1}, (x[i+1] - x[i])^2) + "
                          f"x[{n}]^2)/2 - sum(i = 1..{n}, x[i]^4)/4",
        },
        "initial": {"q": [repr(math.sin(i + 1) / 10) for i in range(n)],
                    "w": [repr(math.cos(i + 1) / 10) for i in range(n)]},
        "T": "1",
        "steps": [20, 40, 80, 160],
        "scalar": "double",
        "discretization": {"kind": "midpoint"},
        "claims": ["global-order", "local-order", "symplecticity"],
    }


def lattice(bodies, spacing):
    side = math.ceil(bodies ** (1 / 3))
    points = [(i, j, k) for i in range(side) for j in range(side) for k in range(side)][:bodies]
    return [repr(spacing * c) for p in points for c in p]


def small_velocities(count):
    return [repr(math.cos(1.7 * i) / 20) for i in range(count)]


def bodies_case(kind, bodies, params, lagrangian, spacing, discretization):
    """All pairs of `bodies` in space on a cubic lattice of `spacing`, global-order over T = 1/4."""
    return {
        "name": f"memory-{kind}-{bodies}",
        "system": {"name": f"{kind}-{bodies}", "coordinates": [{"x": [bodies, 3]}],
                   "velocities": [{"v": [bodies, 3]}], "params": params, "lagrangian": lagrangian},
        "initial": {"q": lattice(bodies, spacing), "w": small_velocities(3 * bodies)},
        "T": "1/4",
        "steps": [8, 16, 32, 64],
        "scalar": "double",
        "discretization": discretization,
        "claims": ["global-order"],
    }


def gravity_case(n):
    bodies = n // 3
    return bodies_case(
        "gravity", bodies, {"m": [f"1/{i}" for i in range(1, bodies + 1)]},
        f"sum(i = 1..{bodies}, m[i]*sum(k = 1..3, v[i,k]^2))/2 + sum(i = 1..{bodies - 1}, "
        f"sum(j = i+1..{bodies}, m[i]*m[j]/sqrt(sum(k = 1..3, (x[i,k] - x[j,k])^2))))",
        1.0, {"kind": "midpoint"})


def lj_case(n):
    atoms = n // 3
    return bodies_case(
        "lj", atoms, {"eps": "1", "sigma": "1"},
        f"sum(i = 1..{atoms}, sum(k = 1..3, v[i,k]^2))/2 - 4*eps*sum(i = 1..{atoms - 1}, "
        f"sum(j = i+1..{atoms}, (sigma^2/sum(k = 1..3, (x[i,k] - x[j,k])^2))^6 - "
        f"(sigma^2/sum(k = 1..3, (x[i,k] - x[j,k])^2))^3))",
        1.12, {"kind": "process", "precision": "double", "order": 2,
               "command": ["/usr/bin/python3",
                           os.path.join(ROOT, "examples", "python-integrator", "lj_cluster_verlet.py")]})


SYSTEMS = {"chain": chain_case, "gravity": gravity_case, "lj": lj_case}


def peak_of(command, env):
    """Runs command; returns (its own peak resident bytes, seconds, stdout)."""
    started = time.monotonic()
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env, text=True)
    peak = 0
    status = f"/proc/{process.pid}/status"
    while process.poll() is None:
        try:
            with open(status) as f:
                for line in f:
                    if line.startswith("VmHWM:"):
                        peak = max(peak, int(line.split()[1]) * 1024)
        except OSError:
            pass
        time.sleep(0.02)
    out, err = process.communicate()
    if process.returncode not in (0, 1):
        sys.exit(f"{' '.join(command)} ended with {process.returncode}:\n{err}")
    return peak, time.monotonic() - started, out


def estimate_of(vivv, case_file, env):
    """The plan's memory estimate in bytes and its reference orders "flow/check"."""
    plan = subprocess.run([vivv, "run", case_file, "--plan", "--allow-process"], capture_output=True, text=True,
                          env=env)
    if plan.returncode != 0:
        sys.exit(f"vivv run --plan {case_file}: {plan.stderr}")
    match = re.search(r"memory: about ([0-9.]+) (KiB|MiB|GiB)", plan.stdout)
    orders = re.search(r"reference flow: Taylor series to T = \S+, order (\d+), and its cross-check, order (\d+)",
                       plan.stdout)
    if not match or not orders:
        sys.exit(f"vivv run --plan {case_file} printed no memory estimate or no reference orders:\n{plan.stdout}")
    scale = {"KiB": 1024, "MiB": 1024 ** 2, "GiB": 1024 ** 3}[match.group(2)]
    return float(match.group(1)) * scale, f"{orders.group(1)}/{orders.group(2)}"


def report_orders(report_text):
    """The reference orders "flow/check" the run's report names."""
    flow = re.search(r"Taylor-mode AD, order (\d+)", report_text)
    check = re.search(r"reruns the Taylor flow at step tolerance \S+ \(order (\d+)", report_text)
    return f"{flow.group(1) if flow else '?'}/{check.group(1) if check else '?'}"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("vivv")
    parser.add_argument("--systems", default="chain,gravity,lj")
    parser.add_argument("--sizes", default="64,128,256,512,1024")
    parser.add_argument("--check", action="store_true")
    # The check's negative control: the estimate multiplied by X must fail it for X = 3.
    parser.add_argument("--scale-estimate", type=float, default=1.0)
    args = parser.parse_args()
    failures = []
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python"))
    print("| system | n | estimate (MiB) | peak (MiB) | peak / estimate | reference orders: plan, run | wall (s) | "
          "verdicts |")
    print("|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as work:
        for system in args.systems.split(","):
            for n in (int(s) for s in args.sizes.split(",")):
                case = SYSTEMS[system](n)
                n = len(case["initial"]["q"])
                case_file = os.path.join(work, case["name"] + ".json")
                with open(case_file, "w") as f:
                    json.dump(case, f)
                estimate, planned_orders = estimate_of(args.vivv, case_file, env)
                estimate *= args.scale_estimate
                out = os.path.join(work, "out-" + case["name"])
                peak, seconds, _ = peak_of([args.vivv, "run", case_file, "--out", out, "--allow-process", "--quiet"],
                                           env)
                with open(os.path.join(out, "report.json")) as f:
                    text = f.read()
                report = json.loads(text)
                orders = report_orders(text)
                verdicts = ", ".join(f"{c['id']} {c['verdict']}" for c in report["cases"][0]["claims"])
                mib = 1024 ** 2
                print(f"| {system} | {n} | {estimate / mib:.1f} | {peak / mib:.1f} | {peak / estimate:.2f} | "
                      f"{planned_orders}, {orders} | {seconds:.1f} | {verdicts} |", flush=True)
                if not 0.5 <= peak / estimate <= 2:
                    failures.append(f"{case['name']}: peak {peak / mib:.1f} MiB against an estimate of "
                                    f"{estimate / mib:.1f} MiB")
                if planned_orders != orders:
                    failures.append(f"{case['name']}: the plan's reference orders {planned_orders}, the run's {orders}")
                if any(c["verdict"] != "pass" for c in report["cases"][0]["claims"]):
                    failures.append(f"{case['name']}: {verdicts}")
    if args.check and failures:
        sys.exit("\n".join(failures))


if __name__ == "__main__":
    main()
