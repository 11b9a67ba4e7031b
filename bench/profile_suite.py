#!/usr/bin/env python3
"""Where the default suite's time goes: runs `vivv run --progress --jobs 1` and stamps each
progress line as it arrives; a phase lasts until the next line. Prints seconds by case, by claim
(summed over cases) and the ten longest phases.

    python3 bench/profile_suite.py build/harness/vivv [CASE.json ...]
"""
import collections
import re
import subprocess
import sys
import tempfile
import time


def main():
    vivv, cases = sys.argv[1], sys.argv[2:]
    with tempfile.TemporaryDirectory() as out:
        process = subprocess.Popen([vivv, "run", *cases, "--out", out, "--progress", "--jobs", "1"],
                                   stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        stamps = [(time.monotonic(), line.rstrip("\n")) for line in process.stderr]
        end = time.monotonic()
        process.wait()
    by_case, by_claim, phases = collections.Counter(), collections.Counter(), []
    claim = {}
    for (start, line), (stop, _) in zip(stamps, stamps[1:] + [(end, "")]):
        match = re.match(r"(?:\[[^\]]*\]\s*)?([^:]+): (.*)", line)
        if not match:
            continue
        case, phase = match.groups()
        if phase.startswith("claim "):
            claim[case] = phase[len("claim "):]
        seconds = stop - start
        by_case[case] += seconds
        by_claim[claim.get(case, "(reference flow and set-up)")] += seconds
        phases.append((seconds, case, phase))
    total = sum(by_case.values())
    print(f"total {total:.1f} s over {len(by_case)} cases (--jobs 1)")
    print("by claim:")
    for name, seconds in by_claim.most_common():
        print(f"  {seconds:7.2f} s {100 * seconds / total:5.1f} %  {name}")
    print("by case (top 10):")
    for name, seconds in by_case.most_common(10):
        print(f"  {seconds:7.2f} s  {name}")
    print("longest phases:")
    for seconds, case, phase in sorted(phases, reverse=True)[:10]:
        print(f"  {seconds:7.2f} s  {case}: {phase[:100]}")


if __name__ == "__main__":
    main()
