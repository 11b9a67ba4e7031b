"""The layers of vivv include only downwards.

usage: check_layering.py REPOSITORY_ROOT
       check_layering.py --self-test

core/ is the numerics and includes only itself; cases/ (case files, formulas)
and references/ build on core/; reports/ (the result model and its renderers)
on cases/ and core/, never on harness/; harness/ may use them all. Exits 1
naming every include that reaches upwards. --self-test builds a small tree with
one such include and checks that it is caught (the check's negative control).
"""
import pathlib
import re
import sys
import tempfile

ALLOWED = {
    "core": {"core"},
    "cases": {"core", "cases"},
    "references": {"core", "cases", "references"},
    "reports": {"core", "cases", "reports"},
    "harness": {"core", "cases", "references", "reports", "harness", "bench"},
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/', re.MULTILINE)


def violations(root):
    found = []
    for layer, allowed in ALLOWED.items():
        for source in sorted((root / layer).rglob("*")):
            if source.suffix not in {".hpp", ".cpp", ".h"}:
                continue
            for target in INCLUDE.findall(source.read_text()):
                if target not in allowed:
                    found.append(f"{source.relative_to(root)} includes from {target}/, above {layer}/")
    return found


def self_test():
    with tempfile.TemporaryDirectory() as directory:
        root = pathlib.Path(directory)
        (root / "reports").mkdir()
        (root / "harness").mkdir()
        (root / "harness" / "run.hpp").write_text("#pragma once\n")
        (root / "reports" / "report.hpp").write_text('#include "reports/x.hpp"\n#include "harness/run.hpp"\n')
        found = violations(root)
        if found != ["reports/report.hpp includes from harness/, above reports/"]:
            print(f"self-test: the upward include was not reported as expected: {found}", file=sys.stderr)
            return 1
    print("self-test: an upward include from reports/ into harness/ is caught")
    return 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    found = violations(pathlib.Path(argv[1]).resolve())
    for line in found:
        print(line, file=sys.stderr)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
