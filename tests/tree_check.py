"""What the checks of the repository tree share (check_docs_links.py, check_layering.py): the
command line `SCRIPT REPOSITORY_ROOT | --self-test`, and the self-test's comparison of what a
planted tree gave with what it must give."""
import pathlib
import sys


def self_test_outcome(found, expected, planted):
    """0 when the planted tree gave exactly `expected` (in any order), else 1, saying which."""
    if sorted(found) != sorted(expected):
        print("self-test: what was planted was not reported as expected; found:", file=sys.stderr)
        for line in found:
            print(f"  {line}", file=sys.stderr)
        return 1
    print(f"self-test: {planted}")
    return 0


def run(argv, usage, check, self_test):
    """The script's exit code: check(root) lists the problems of the tree at argv[1] (exit 1
    naming each, on stderr; 0 when none); --self-test runs self_test(); anything else is usage (2)."""
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) != 2:
        print(usage, file=sys.stderr)
        return 2
    problems = check(pathlib.Path(argv[1]).resolve())
    for problem in problems:
        print(problem, file=sys.stderr)
    return 1 if problems else 0
