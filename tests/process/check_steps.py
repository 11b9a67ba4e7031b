#!/usr/bin/env python3
"""The protocol's extension "steps": k steps of a program's map in one request, only the last state
crossing the pipe (docs/process-protocol.md).

usage: check_steps.py VIVV WORK_DIR

tests/process/steps_verlet.py (Stormer-Verlet in double on a Duffing oscillator) with and without the
extension, in one run each:
  - global-order alone: one or two requests a run of the sweep (16 steps, then as many as take a second;
    its one-step measurements stay single requests), and
    report.json's global-order errors, observed order, verdict and the cost's program_evaluations
    are the same as with one request a step;
  - global-order beside energy-behaviour, which reads every state: no request asks for steps;
  - a program that answers fewer steps than asked (as one whose state left the finite numbers on the
    way does) is stepped one request a step instead, with the same errors;
  - the negative controls: an answer's "steps" written as a string, negative, a fraction, a boolean,
    null or above the count asked for is a malformed answer (the case could not run, exit 4, naming
    "steps");
  - with the extension "trajectory" taken up too, global-order beside energy-behaviour (which reads
    every state) asks for several steps a request, and both claims' measurements and verdicts are
    those of one request a step; a "trajectory" missing, a state short, a state of q alone or a last
    state that is not the answer's q and p is a malformed answer (exit 4, naming "trajectory").
"""
import json
import pathlib
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent
SYSTEM = {"name": "duffing", "lagrangian": "w^2/2 - x^2/2 - x^4/4", "coordinates": ["x"], "velocities": ["w"]}
STEPS = [16, 32, 64, 128]
COMMON = {"system": SYSTEM, "initial": {"q": ["0.8"], "w": ["0.3"]}, "T": "2", "steps": STEPS,
          "scalar": "double"}


def case(work, name, claims, *options):
    path = work / f"{name}.json"
    path.write_text(json.dumps({"name": name, **COMMON, "claims": claims, "discretization": {
        "kind": "process", "precision": "double", "order": 2,
        "command": [sys.executable, str(HERE / "steps_verlet.py"), *options]}}))
    return path


def run(vivv, work, out, path):
    return subprocess.run([vivv, "run", str(path), "--allow-process", "--out", str(work / out), "--quiet"],
                          capture_output=True, text=True, timeout=600)


def global_order(work, out):
    """(errors, observed order, verdict, program_evaluations by N) of the run's one case."""
    report = json.loads((work / out / "report.json").read_text())
    case_report = report["cases"][0]
    claim = next(c for c in case_report["claims"] if c["id"] == "global-order")
    cost = {row["N"]: row.get("program_evaluations") for row in case_report.get("cost", [])}
    return claim["error"], claim["observed_order"], claim["verdict"], cost


def logged(path):
    return [int(k) for k in path.read_text().split()] if path.exists() else []


def main(argv):
    vivv, work = argv[1], pathlib.Path(argv[2])
    work.mkdir(parents=True, exist_ok=True)
    problems = []
    results = {}
    for name, options in [("batched", ["--evaluations"]), ("stepped", ["--no-steps", "--evaluations"]),
                          ("short", ["--short-by", "1", "--evaluations"])]:
        log = work / f"{name}.log"
        log.unlink(missing_ok=True)
        done = run(vivv, work, name, case(work, f"steps-{name}", ["global-order"], *options, "--log", str(log)))
        if done.returncode != 0:
            problems.append(f"{name}: the run ended {done.returncode}: {done.stdout[-600:]}{done.stderr[-600:]}")
            continue
        results[name] = global_order(work, name), logged(log)
    if len(results) == 3:
        (batched, batched_log), (stepped, stepped_log), (short, short_log) = (results[k] for k in ("batched", "stepped", "short"))
        # The first request of a run asks for 16 steps and the next ones for more (as many as take a
        # second): here one or two requests a run. global-order's one-step measurements (local-order's,
        # from states along the orbit) stay single steps, as many as without the extension.
        runs = [k for k in batched_log if k > 1]
        if set(stepped_log) != {1}:
            problems.append(f"without the extension: requests of {sorted(set(stepped_log))} steps, expected 1 each")
        elif sum(runs) != sum(STEPS) or len(runs) > 2 * len(STEPS) or \
                batched_log.count(1) != len(stepped_log) - sum(STEPS):
            problems.append(f"with the extension the sweep made requests of {runs} steps and {batched_log.count(1)} "
                            f"single ones, expected one or two a run ({sum(STEPS)} steps in all) and "
                            f"{len(stepped_log) - sum(STEPS)} single (the one-step measurements)")
        if batched[:3] != stepped[:3]:
            problems.append(f"global-order with the extension {batched[:3]} differs from one request a step {stepped[:3]}")
        if batched[3] != {N: 2 * N for N in STEPS} or stepped[3] != batched[3]:
            problems.append(f"program_evaluations {batched[3]} (batched), {stepped[3]} (stepped): expected 2 N")
        if short[:3] != stepped[:3] or short_log.count(1) != len(stepped_log):
            problems.append(f"a program answering fewer steps than asked: {short[:3]} with {short_log.count(1)} single "
                            f"steps, expected {stepped[:3]} stepped one by one")
    log = work / "walked.log"
    log.unlink(missing_ok=True)
    done = run(vivv, work, "walked", case(work, "steps-walked", ["global-order", "energy-behaviour"], "--log", str(log)))
    if done.returncode not in (0, 1) or set(logged(log)) != {1}:
        problems.append(f"beside energy-behaviour: exit {done.returncode}, requests of {sorted(set(logged(log)))} steps "
                        "(expected 1 each: energy-behaviour reads every state)")
    for bad in ['"2"', "-1", "1.5", "true", "null", "1000"]:
        done = run(vivv, work, "bad", case(work, "steps-bad-answer", ["global-order"], "--steps-answer", bad))
        said = done.stdout + done.stderr
        if done.returncode != 4 or '"steps"' not in said or "not the count of steps it took" not in said:
            problems.append(f"an answer's steps {bad}: exit {done.returncode} (expected 4, naming \"steps\"): {said[-400:]}")
    walkers = ["global-order", "energy-behaviour"]
    walked = {}
    for name, options in [("trajectory", ["--trajectory"]), ("one-a-step", ["--no-steps"])]:
        log = work / f"{name}.log"
        log.unlink(missing_ok=True)
        done = run(vivv, work, name, case(work, f"steps-{name}", walkers, *options, "--log", str(log)))
        if done.returncode not in (0, 1):
            problems.append(f"{name}: the run ended {done.returncode}: {done.stdout[-600:]}{done.stderr[-600:]}")
            continue
        # The claims as the report gives them, the program's command line (which names its options)
        # written as PROGRAM: every number, verdict and explanation compared.
        text = (work / name / "report.json").read_text()
        command = " ".join([sys.executable, str(HERE / "steps_verlet.py"), *options, "--log", str(log)])
        claims = json.loads(text.replace(command, "PROGRAM"))["cases"][0]["claims"]
        walked[name] = {c["id"]: c for c in claims}, logged(log)
    if len(walked) == 2:
        (with_states, states_log), (one_a_step, _) = walked["trajectory"], walked["one-a-step"]
        if sum(k for k in states_log if k > 1) != sum(STEPS):
            problems.append(f"with \"trajectory\" the runs were asked in requests of {[k for k in states_log if k > 1]} "
                            f"steps, expected all {sum(STEPS)} steps of the sweep in batches")
        for claim in walkers:
            if with_states.get(claim) != one_a_step.get(claim):
                problems.append(f"{claim} with \"trajectory\" differs from one request a step")
    for fault in ["missing", "short", "row", "last"]:
        done = run(vivv, work, "bad", case(work, "trajectory-bad-answer", walkers, "--trajectory", "--trajectory-fault", fault))
        said = done.stdout + done.stderr
        if done.returncode != 4 or "trajectory" not in said:
            problems.append(f"a trajectory answer {fault}: exit {done.returncode} (expected 4, naming \"trajectory\"): "
                            f"{said[-400:]}")
    for problem in problems:
        print(problem)
    print("extension steps:", "problems above" if problems else
          "one or two requests a run, the same errors as one a step; kept whole beside energy-behaviour; "
          "a short answer stepped one by one; 6 malformed counts refused; with \"trajectory\" the walking claims "
          "batched and unchanged, 4 malformed trajectories refused")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
