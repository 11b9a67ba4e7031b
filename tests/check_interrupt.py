#!/usr/bin/env python3
"""Interrupting vivv run leaves the earlier report intact and nothing else behind.

    check_interrupt.py VIVV OUT QUICK.json SLOW.json [SLOW2.json]

For SIGINT and SIGTERM, serial and with --jobs 2, and SIGQUIT and SIGUSR1 with --jobs 2: a
quick run writes a report into a directory; a slow run into the same directory is interrupted
after 1.5 s (while it computes: SLOW.json must outlast that by a wide margin at any speed, as
tests/budget/exact-slow.json does, whose first long phase computes for about 30 s). Then the process must have ended by that signal, report.json,
report.html and junit.xml must be byte for byte the earlier ones, the directory must hold
nothing else, its private $TMPDIR must be empty, and no worker may survive. SIGKILL with --jobs
2 cannot be handled: the report must still be the earlier one and no worker may survive (the
kernel ends them, PR_SET_PDEATHSIG); the private directory may stay. A worker ended by SIGSEGV
ends the run with exit 3 naming the signal, leaving the earlier report and nothing else. Exit 0
when every combination holds, 1 otherwise.
"""
import os
import shutil
import signal
import subprocess
import sys
import time


def snapshot(directory):
    return {name: open(os.path.join(directory, name), "rb").read() for name in sorted(os.listdir(directory))}


def start_slow_run(vivv, root, quick, slow, jobs):
    """A report from the quick run in ROOT/out, then the slow run into the same directory,
    started 1.5 s ago with ROOT/tmp as its $TMPDIR: (process, out, tmp, the earlier report)."""
    out, tmp = os.path.join(root, "out"), os.path.join(root, "tmp")
    shutil.rmtree(root, ignore_errors=True)
    os.makedirs(tmp)
    env = dict(os.environ, TMPDIR=tmp)
    subprocess.run([vivv, "run", quick, "--out", out, "--quiet"], env=env, check=True, stdout=subprocess.DEVNULL)
    before = snapshot(out)
    process = subprocess.Popen([vivv, "run", *slow, "--jobs", str(jobs), "--out", out, "--quiet"], env=env,
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, preexec_fn=default_signals)
    time.sleep(1.5)
    return process, out, tmp, before


def check(vivv, root, quick, slow, sig, jobs):
    label = "%s, --jobs %d" % (signal.Signals(sig).name, jobs)
    process, out, tmp, before = start_slow_run(vivv, root, quick, slow, jobs)
    if process.poll() is not None:
        return ["%s: the slow run ended before it was interrupted (exit %d)" % (label, process.returncode)]
    process.send_signal(sig)
    try:
        _, stderr = process.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        process.kill()
        return ["%s: still running 30 s after the signal" % label]
    problems = []
    if process.returncode != -sig:
        problems.append("%s: exit status %d, expected death by the signal (%d); stderr: %s"
                        % (label, process.returncode, -sig, stderr.decode(errors="replace")[-300:]))
    after = snapshot(out)
    if after != before:
        problems.append("%s: the output directory changed: %s -> %s" % (label, sorted(before), sorted(after)))
    if os.listdir(tmp) and sig != signal.SIGKILL:
        problems.append("%s: left in $TMPDIR: %s" % (label, os.listdir(tmp)))
    # The kernel's SIGTERM reaches the orphans of a SIGKILL soon, not at once: wait for it (at
    # most 20 s, so that a loaded machine does not fail the check).
    survivors = vivv_processes(vivv, out)  # by its --out: other tests may run the same cases
    if sig == signal.SIGKILL:
        survivors = wait_until_gone(vivv, out, 20)
    if survivors:
        problems.append("%s: workers still running: %s" % (label, survivors))
        for pid in survivors:
            os.kill(pid, signal.SIGKILL)
    return problems


def check_worker_crash(vivv, root, quick, slow):
    """A --jobs worker ended by SIGSEGV: the run ends with exit 3 naming the case and the signal,
    the earlier report stays, nothing is left in $TMPDIR and no worker survives."""
    label = "a worker ended by SIGSEGV"
    process, out, tmp, before = start_slow_run(vivv, root, quick, slow, 2)
    workers = []
    deadline = time.monotonic() + 30  # a worker starts within the first second here
    while process.poll() is None and not workers and time.monotonic() < deadline:
        workers = [pid for pid in vivv_processes(vivv, out) if pid != process.pid]
        time.sleep(0.05)
    if process.poll() is not None or not workers:
        process.kill()
        return ["%s: no worker was running within 30 s" % label]
    os.kill(workers[0], signal.SIGSEGV)
    try:
        _, stderr = process.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        process.kill()
        return ["%s: still running 60 s after the crash" % label]
    problems = []
    message = stderr.decode(errors="replace")
    if process.returncode != 3 or "ended by signal %d" % signal.SIGSEGV not in message:
        problems.append("%s: exit %d, expected 3 naming signal %d; stderr: %s"
                        % (label, process.returncode, signal.SIGSEGV, message[-300:]))
    if snapshot(out) != before:
        problems.append("%s: the output directory changed" % label)
    if os.listdir(tmp):
        problems.append("%s: left in $TMPDIR: %s" % (label, os.listdir(tmp)))
    survivors = vivv_processes(vivv, out)
    if survivors:
        problems.append("%s: workers still running: %s" % (label, survivors))
        for pid in survivors:
            os.kill(pid, signal.SIGKILL)
    return problems


def wait_until_gone(vivv, argument, seconds):
    """The processes of vivv_processes(vivv, argument) still running after at most SECONDS."""
    deadline = time.monotonic() + seconds
    while True:
        found = vivv_processes(vivv, argument)
        if not found or time.monotonic() > deadline:
            return found
        time.sleep(0.05)


def default_signals():
    """In the child: the default action for the signals sent (a background shell may have left
    SIGINT and SIGQUIT ignored, and vivv keeps an ignored signal ignored), and no core file."""
    import resource
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    for sig in (signal.SIGINT, signal.SIGQUIT, signal.SIGTERM, signal.SIGUSR1):
        signal.signal(sig, signal.SIG_DFL)


def vivv_processes(vivv, argument):
    """Pids of processes running `vivv` with `argument` among their arguments."""
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            arguments = open("/proc/%s/cmdline" % entry, "rb").read().split(b"\0")
        except OSError:
            continue
        if arguments and arguments[0] == vivv.encode() and argument.encode() in arguments:
            found.append(int(entry))
    return found


def main(argv):
    if len(argv) < 5:
        print(__doc__, file=sys.stderr)
        return 2
    vivv, root, quick, slow = argv[1], argv[2], argv[3], argv[4:]
    problems = []
    combinations = [(signal.SIGINT, 1), (signal.SIGINT, 2), (signal.SIGTERM, 1), (signal.SIGTERM, 2),
                    (signal.SIGQUIT, 2), (signal.SIGUSR1, 2), (signal.SIGKILL, 2)]
    for sig, jobs in combinations:
        problems += check(vivv, os.path.join(root, "%s-%d" % (sig.name, jobs)), quick, slow, sig, jobs)
    problems += check_worker_crash(vivv, os.path.join(root, "crash"), quick, slow)
    for problem in problems:
        print(problem)
    print("interrupt: %s" % ("ok" if not problems else "%d problems" % len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
