#!/usr/bin/env python3
"""Corpus-driven fuzzing of what vivv reads: case files (with their formulas), report.json, and
the answers of a map program speaking protocol vivv-map/1.

    fuzz_inputs.py VIVV CORPUS_DIR WORK_DIR [--mutations M] [--seed S]
    fuzz_inputs.py --self-test WORK_DIR

Kind "steps" needs no corpus: a program on vivv_map.serve (tests/fuzz/fuzzed_step.py) whose step()
returns each of its malformed values (None, a string, a wrong length, complex, NaN, an endless
iterable, an exit mid-run, …), at the first request and after three good ones. Besides the exit
codes below, a program that could not run must be recorded with the user's file named (serve
blames the user's function or line, never vivv_map's own).

CORPUS_DIR/cases/*.json are case files, CORPUS_DIR/reports/*.json report.json files, and
CORPUS_DIR/answers/*.jsonl a map program's answers, one line each (the greeting's first), with
the case they answer beside them (*.case.json, whose command is replaced by the replay program
tests/fuzz/replay_map.py serving the answers file). Every corpus file, and M deterministic
mutations of each (seeded: the same inputs every run; an answers file has one of its lines
mutated), goes through `vivv run` (cases and answers) or `vivv report` (reports). Each must end
with exit 0, 1, 2 or 4 — never a signal (abort, segfault), never a hang (each run has --max-seconds
5, --process-timeout 5 and a 60 s limit) — an exit 2 must say "vivv:" and leave no
report.json, and an exit 4 (a case that could not run) must leave report.json recording it and
junit.xml. A failing input is saved in WORK_DIR/failures/ to be added to the corpus once
fixed. Exit 0 when every input behaved, 1 otherwise.
"""
import json
import os
import random
import shutil
import subprocess
import sys

EXTREME_NUMBERS = ["1e5000", "-1e5000", "1e-400", "0", "-0", "nan", "inf", "+2", ".5", "2.", "1" * 400,
                   "0x10", "1/0", "", " 1", "1e", "-", "9" * 40,
                   # Long numbers in any numeric field (issue 51: std::regex recursed per character
                   # and a 50,000-digit number ended vivv with SIGSEGV): valid, with a stray letter,
                   # a long exponent, a long fraction.
                   "1." + "3" * 50000, "1." + "3" * 50000 + "x", "7" * 200000, "1e" + "9" * 50000,
                   "1/" + "3" * 50000, "-" + "0" * 100000 + "1"]
EXTREME_FORMULAS = ["", "(", "q^", "q^q^q^q^q^q^q", "sin(" * 200 + "q" + ")" * 200, "1/0", "sqrt(-1)",
                    "log(0)", "q*", "L(q, w)", "w^2/2 - cos(q", "w^1e9", "exp(exp(exp(q)))", "q/(q-q)",
                    "(" * 9990 + "q" + ")" * 9990, "-(" * 6600 + "q" + ")" * 6600, "q^" * 9990 + "q",
                    "(" * 501 + "q" + ")" * 501,
                    # Indexed families, sums and index arithmetic (issue 67): what would wrap in 64
                    # bits, bounds far past any family, sums too large to expand, reserved indices.
                    "x[4294967296*4294967296 + 1]", "sum(i = 1..4294967296*4294967296 + 3, x[i,1])",
                    "sum(i = 1..1099511627776, x[i,1])", "x[1099511627776*1099511627776]", "x[-9223372036854775807]",
                    "sum(i = 1..1000000, sum(j = 1..1000000, x[1,1]*x[1,2]))", "sum(pi = 1..2, x[pi,1])",
                    "sum(i = 1..3, sum(i = 1..3, x[i,1]))", "x[0,1]", "x[1]", "x[i,1]",
                    "sum(i = 1..1000000, " + "*".join(["x[1,1]"] * 500) + ")"]


def mutate_json(value, rng):
    """One structural edit somewhere in a parsed JSON value."""
    if isinstance(value, dict) and value and rng.random() < 0.8:
        key = rng.choice(sorted(value))
        choice = rng.random()
        if choice < 0.15:
            del value[key]
        elif choice < 0.3:
            value[key] = rng.choice([None, True, 3, -1, 1e308, "x", [], {}, [[[]]]])
        else:
            value[key] = mutate_json(value[key], rng)
        return value
    if isinstance(value, list) and value and rng.random() < 0.8:
        i = rng.randrange(len(value))
        choice = rng.random()
        if choice < 0.2:
            del value[i]
        elif choice < 0.35:
            value.append(value[i])
        else:
            value[i] = mutate_json(value[i], rng)
        return value
    if isinstance(value, str):
        if any(c.isalpha() for c in value) and rng.random() < 0.5:
            return rng.choice(EXTREME_FORMULAS)
        return rng.choice(EXTREME_NUMBERS)
    if isinstance(value, bool) or value is None:
        return rng.choice([0, "true", [], None])
    if isinstance(value, (int, float)):
        return rng.choice([0, -1, 2**31, 2**63, 10**30, 1e-320, 0.5, "4"])
    return rng.choice([None, 0, "", [], {}])


def mutate_text(text, rng):
    """One byte-level edit: truncation, deletion, duplication, deep nesting or a stray byte."""
    choice = rng.random()
    if choice < 0.2:
        return text[: rng.randrange(len(text) + 1)]
    i, j = sorted(rng.randrange(len(text) + 1) for _ in range(2))
    if choice < 0.4:
        return text[:i] + text[j:]
    if choice < 0.55:
        return text[:j] + text[i:j] + text[j:]
    if choice < 0.7:
        depth = rng.choice([100, 10000, 100000])
        return text[:i] + "[" * depth + "]" * depth + text[i:]
    if choice < 0.8:
        return text[:i] + '"a": 1, "a": 2, ' + text[i:]
    return text[:i] + chr(rng.choice([0, 1, 0x1F, 0x7F, 0xE9, 0x2028])) + text[i:]


def mutations(text, count, rng):
    try:
        parsed = json.loads(text)
    except ValueError:
        parsed = None
    for k in range(count):
        if parsed is not None and k % 2 == 0:
            edited = mutate_json(json.loads(text), rng)
            for _ in range(rng.randrange(2)):
                edited = mutate_json(edited, rng)
            yield json.dumps(edited)
        else:
            yield mutate_text(text, rng)


def answer_mutations(text, count, rng):
    """Answers files with one line mutated each: a structural edit of its JSON, a byte-level
    edit, or bytes that are not UTF-8 (written through surrogateescape)."""
    lines = text.split("\n")
    for _ in range(count):
        k = rng.randrange(len(lines))
        edited = list(lines)
        try:
            parsed = json.loads(lines[k])
        except ValueError:
            parsed = None
        choice = rng.random()
        if parsed is not None and choice < 0.5:
            edited[k] = json.dumps(mutate_json(parsed, rng))
        elif choice < 0.9:
            edited[k] = mutate_text(lines[k], rng)
        else:
            i = rng.randrange(len(lines[k]) + 1)
            edited[k] = lines[k][:i] + "\udcff\udcfe\udce2\udc82" + lines[k][i:]
        yield "\n".join(edited)


def check(vivv, kind, path, work, exits=None):
    out = os.path.join(work, "out")
    shutil.rmtree(out, ignore_errors=True)
    if kind == "cases":
        command = [vivv, "run", path, "--out", out, "--quiet", "--max-seconds", "5"]
    elif kind in ("answers", "steps"):
        command = [vivv, "run", path, "--out", out, "--quiet", "--max-seconds", "5", "--allow-process",
                   "--process-timeout", "5"]
    else:
        command = [vivv, "report", path, "--out", out]
    try:
        result = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=60)
    except subprocess.TimeoutExpired:
        return "ran past 60 s"
    stderr = result.stderr.decode(errors="replace")
    if exits is not None:
        exits[result.returncode] = exits.get(result.returncode, 0) + 1
    if result.returncode < 0:
        return "ended by signal %d: %s" % (-result.returncode, stderr[-300:])
    if result.returncode not in (0, 1, 2, 4):
        return "exit %d: %s" % (result.returncode, stderr[-300:])
    if result.returncode == 4:  # a map program that failed while its case ran: recorded, not lost
        try:
            refused = json.load(open(os.path.join(out, "report.json"))).get("refused", [])
        except (OSError, ValueError) as error:
            return "exit 4 without a readable report.json: %s" % error
        if not any(entry.get("kind") == "could-not-run" for entry in refused):
            return "exit 4 but report.json records no case that could not run"
        if not os.path.exists(os.path.join(out, "junit.xml")):
            return "exit 4 but no junit.xml"
        # The user's line (serve's message or a traceback), the answer's field, or an exit with nothing to say.
        named = ("fuzzed_step.py:", 'fuzzed_step.py", line', "q[0] =", "p[0] =", "exited with status 0")
        if kind == "steps" and not any(any(n in entry.get("message", "") for n in named) for entry in refused):
            return "exit 4 but the record names neither the user's line nor the answer's field: %s" % refused[:1]
    if result.returncode == 2:
        if "vivv:" not in stderr:
            return "exit 2 without a message: %r" % stderr[-300:]
        if os.path.exists(os.path.join(out, "report.json")):
            return "exit 2 but a report.json was written"
        if len(stderr) > 20000:
            return "a message of %d characters" % len(stderr)
    return None


def self_test(work):
    """The checker's negative control: a program that crashes, one that hangs past its
    limit is not tried (60 s), one that exits 2 silently, one that exits 2 but writes a report."""
    os.makedirs(work, exist_ok=True)
    path = os.path.join(work, "input.json")
    open(path, "w").write("{}")
    programs = {
        "segfault": "kill -SEGV $$",
        "silent exit 2": "exit 2",
        "report on exit 2": 'mkdir -p "$4"; echo {} > "$4/report.json"; echo "vivv: bad" >&2; exit 2',
        "exit 4 without a record": 'mkdir -p "$4"; echo {} > "$4/report.json"; echo "vivv: bad" >&2; exit 4',
    }
    problems = 0
    for name, body in programs.items():
        fake = os.path.join(work, "fake-vivv")
        open(fake, "w").write("#!/bin/sh\n" + body + "\n")
        os.chmod(fake, 0o755)
        if check(fake, "cases", path, work) is None:
            print("self-test: the checker accepted a program that does '%s'" % name)
            problems += 1
    print("fuzz self-test: %s" % ("ok" if not problems else "%d problems" % problems))
    return 1 if problems else 0


def main(argv):
    args = argv[1:]
    if len(args) == 2 and args[0] == "--self-test":
        return self_test(args[1])
    count, seed = 20, 1
    if "--mutations" in args:
        i = args.index("--mutations")
        count = int(args[i + 1])
        del args[i : i + 2]
    if "--seed" in args:
        i = args.index("--seed")
        seed = int(args[i + 1])
        del args[i : i + 2]
    if len(args) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    vivv, corpus, work = args
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(os.path.join(work, "failures"))
    rng = random.Random(seed)
    failures, inputs, exits = 0, 0, {}
    replay = os.path.join(os.path.dirname(os.path.abspath(__file__)), "replay_map.py")
    for kind in ("cases", "reports", "answers"):
        directory = os.path.join(corpus, kind)
        for name in sorted(os.listdir(directory)):
            if name.endswith(".case.json"):
                continue  # the case an answers file answers
            text = open(os.path.join(directory, name), encoding="utf-8", errors="surrogateescape").read()
            if kind == "answers":
                candidates = [text] + list(answer_mutations(text, count, rng))
                case = json.load(open(os.path.join(directory, name[: -len(".jsonl")] + ".case.json")))
                answers = os.path.join(work, "answers.jsonl")
                case["discretization"]["command"] = [sys.executable, replay, answers]
            else:
                candidates = [text] + list(mutations(text, count, rng))
            for k, candidate in enumerate(candidates):
                path = os.path.join(work, "input.json")
                if kind == "answers":
                    with open(answers, "w", encoding="utf-8", errors="surrogateescape") as f:
                        f.write(candidate)
                    candidate = json.dumps(case)
                with open(path, "w", encoding="utf-8", errors="surrogateescape") as f:
                    f.write(candidate)
                inputs += 1
                problem = check(vivv, kind, path, work, exits)
                if problem:
                    failures += 1
                    saved = os.path.join(work, "failures", "%s-%s-%d.json" % (kind, name.split(".")[0], k))
                    shutil.copy(answers if kind == "answers" else path, saved)
                    print("%s: %s" % (saved, problem))
    # A user's step() returning malformed values through vivv_map.serve.
    fuzzed = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fuzzed_step.py")
    variants = int(subprocess.run([sys.executable, fuzzed, "count"], capture_output=True, text=True).stdout)
    for variant in range(variants):
        for good in (0, 3):
            case = {"name": "fuzz-steps-%d-%d" % (variant, good),
                    "system": {"name": "harmonic_oscillator", "params": {"omega": "1"}},
                    "initial": {"q": ["1"], "w": ["0.5"]}, "T": "1", "steps": [4, 8, 16],
                    "discretization": {"kind": "process", "command": [sys.executable, fuzzed, str(variant), str(good)],
                                       "order": 1, "precision": "double"},
                    "claims": ["global-order"]}
            path = os.path.join(work, "input.json")
            with open(path, "w") as f:
                json.dump(case, f)
            inputs += 1
            problem = check(vivv, "steps", path, work, exits)
            if problem:
                failures += 1
                saved = os.path.join(work, "failures", "steps-%d-%d.json" % (variant, good))
                shutil.copy(path, saved)
                print("%s: %s" % (saved, problem))
    print("fuzz: %d inputs (%d corpus files, %d mutations each, seed %d), exit codes %s, %d failures"
          % (inputs, inputs // (count + 1), count, seed,
             ", ".join("%d: %d" % item for item in sorted(exits.items())), failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
