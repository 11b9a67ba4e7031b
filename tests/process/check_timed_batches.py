#!/usr/bin/env python3
"""A program's map of a Lagrangian that depends on time, stepped in batches and one request a step
(docs/process-protocol.md, "t"): the same runs.

usage: check_timed_batches.py VIVV WORK_DIR

kapitza_midpoint.py (the midpoint DEL of a Kapitza pendulum in mpmath, float128 case) three ways:
  - global-order and energy-balance alone: each run in batches of steps (extension "steps"), each
    request starting at its first state's time — the first run takes more than one request;
  - beside symplecticity, which reads every state: batches with every state (extension "trajectory");
  - with --no-batch: one request a step, each at t0 + k·h.
The three give the same global-order and energy-balance errors, to 10^-25 of each (an mpmath program
rounds its state to the digits asked for between requests, not within a batch), and the batched runs
did ask for more than one batch in a run. A batch sent at its run's start time instead of its first
state's made the first run's error ten times larger; the fit set that point aside as pre-asymptotic
and the verdicts stayed the same, which is why this compares the errors themselves.
"""
import json
import pathlib
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent


def run(vivv, work, name, claims, *options, log=None):
    base = json.loads((HERE / "kapitza-program-midpoint.json").read_text())
    command = ["./kapitza_midpoint.py", *options]
    if log:  # the requests as the program reads them
        command = ["/bin/sh", "-c", f"tee {log} | ./kapitza_midpoint.py " + " ".join(options)]
    case = dict(base, name=name, claims=claims, discretization={"kind": "process", "command": command, "order": 2})
    path = HERE / f".{name}.json"  # beside the program: the case's folder is its working directory
    path.write_text(json.dumps(case))
    try:
        out = work / name
        result = subprocess.run([vivv, "run", str(path), "--out", str(out), "--allow-process", "--quiet"],
                                capture_output=True, text=True, timeout=600)
    finally:
        path.unlink()
    if result.returncode != 0:
        sys.exit(f"{name}: vivv exited {result.returncode}: {result.stdout[-2000:]}{result.stderr[-2000:]}")
    report = json.loads((out / "report.json").read_text())
    return {c["id"]: [float(e) for e in c["series"][0]["error"]] for c in report["cases"][0]["claims"]
            if c["id"] in ("global-order", "energy-balance")}


def main():
    vivv, work = sys.argv[1], pathlib.Path(sys.argv[2])
    work.mkdir(parents=True, exist_ok=True)
    log = work / "end-states-requests.log"
    end_states = run(vivv, work, "timed-end-states", ["global-order", "energy-balance"], log=log)
    every_state = run(vivv, work, "timed-every-state", ["global-order", "symplecticity", "energy-balance"])
    single = run(vivv, work, "timed-single", ["global-order", "energy-balance"], "--no-batch")
    batches = [json.loads(line) for line in log.read_text().splitlines()[1:] if '"steps"' in line]
    first_run = [b for b in batches if b["h"] == batches[0]["h"]]
    if len(first_run) < 2:
        sys.exit(f"the first run took {len(first_run)} batch request(s); this check needs two or more")
    if float(first_run[1]["t"]) <= float(first_run[0]["t"]):
        sys.exit(f"the second batch of the first run starts at t = {first_run[1]['t']}, not after the first's")
    failures = []
    for claim in ("global-order", "energy-balance"):
        for name, errors in (("batches of every state", every_state), ("one request a step", single)):
            for k, (a, b) in enumerate(zip(end_states[claim], errors[claim])):
                if abs(a - b) > 1e-25 * max(abs(a), abs(b)):
                    failures.append(f"{claim} at the {k + 1}th h: {a!r} in batches of steps, {b!r} with {name}")
    if failures:
        sys.exit("\n".join(failures))
    print(f"the same errors three ways; the first run in {len(first_run)} batches, "
          f"starting at t = {', '.join(b['t'][:8] for b in first_run)}")


if __name__ == "__main__":
    main()
