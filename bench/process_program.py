"""The program's side of the process protocol at n = 114: a NumPy step of the 38-atom Lennard-Jones
cluster (examples/python-integrator/lj_cluster_verlet.py) against the same step served through
vivv_map (the request's 2n decimal strings parsed, the step, the answer's 2n strings formatted), and
the same for its own Jacobian (4n^2 strings back). vivv's side and the pipes: `vivv bench process`.

    /usr/bin/python3 bench/process_program.py [--repeat K]

Prints microseconds per call and the ratios, medians of 5 batches.
"""
import argparse
import io
import json
import os
import statistics
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
sys.path.insert(0, os.path.join(ROOT, "examples", "python-integrator"))

import numpy as np  # noqa: E402

import lj_cluster_verlet  # noqa: E402
import vivv_map  # noqa: E402
from vivv_map.protocol import PROTOCOL  # noqa: E402


def per_call(function, repeat):
    """Median over 5 batches of `repeat` calls, in microseconds."""
    batches = []
    for _ in range(5):
        start = time.perf_counter()
        for _ in range(repeat):
            function()
        batches.append((time.perf_counter() - start) / repeat * 1e6)
    return statistics.median(batches)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=50, help="calls per batch (default 50)")
    args = parser.parse_args()
    case = json.load(open(os.path.join(ROOT, "examples", "python-integrator", "numpy-lj38-verlet.json")))
    n = len(case["initial"]["q"])
    h = float(case["T"]) / case["steps"][-1]
    cluster = lj_cluster_verlet.Cluster()
    cluster.setup(case["system"], n, float)
    q = np.array([float(x) for x in case["initial"]["q"]])
    p = np.array([float(x) for x in case["initial"]["w"]])

    def step(h, q, p):
        p_half = p + h / 2 * cluster.force(q)
        q_next = q + h * p_half
        return q_next, p_half + h / 2 * cluster.force(q_next)

    def jacobian(h, q, p):
        eye = np.eye(n)
        q_next = q + h * (p + h / 2 * cluster.force(q))
        k0, k1 = cluster.stiffness(q), cluster.stiffness(q_next)
        dq_dq, dq_dp = eye + h * h / 2 * k0, h * eye
        return np.block([[dq_dq, dq_dp], [h / 2 * k0 + h / 2 * k1 @ dq_dq, eye + h / 2 * k1 @ dq_dp]])

    greeting = {"protocol": PROTOCOL, "digits": 17, "dimension": n, "system": case["system"],
                "extensions": ["jacobian"]}
    request = {"h": repr(h), "q": [repr(x) for x in q], "p": [repr(x) for x in p]}

    def served(marked, repeat):
        lines = [json.dumps(greeting)] + [json.dumps({**request, **({"jacobian": True} if marked else {})})] * repeat
        source, sink = io.StringIO("\n".join(lines) + "\n"), io.StringIO()
        start = time.perf_counter()
        vivv_map.serve(step, jacobian=jacobian, arithmetic="numpy", setup=cluster.setup, input=source, output=sink)
        return (time.perf_counter() - start) / repeat * 1e6

    own_step = per_call(lambda: step(h, q, p), args.repeat)
    own_jacobian = per_call(lambda: jacobian(h, q, p), max(1, args.repeat // 5))
    served_step = statistics.median(served(False, args.repeat) for _ in range(5))
    served_jacobian = statistics.median(served(True, max(1, args.repeat // 5)) for _ in range(5))
    print(f"LJ38 (n = {n}), NumPy {np.__version__}, Python {sys.version.split()[0]}: microseconds per call")
    print(f"{'':28}{'own':>10}{'served':>10}{'ratio':>8}")
    print(f"{'step':28}{own_step:10.1f}{served_step:10.1f}{served_step / own_step:8.2f}")
    print(f"{'step with its Jacobian':28}{own_step + own_jacobian:10.1f}{served_jacobian:10.1f}"
          f"{served_jacobian / (own_step + own_jacobian):8.2f}")
    print("served = the request parsed, the call, the answer formatted (vivv_map.serve on in-memory lines)")
    print(json.dumps({"n": n, "own_step_us": own_step, "served_step_us": served_step,
                      "own_step_and_jacobian_us": own_step + own_jacobian, "served_jacobian_us": served_jacobian}))


if __name__ == "__main__":
    main()
