"""The folders of vivv include only downwards.

usage: check_layering.py REPOSITORY_ROOT
       check_layering.py --self-test

Every folder that holds sources has a row in LAYERS naming the folders it may include from
(docs/architecture.md draws the same order). core/ is the numerics, its folders in the order
platform, numerics, automatic differentiation, the Lagrangian system, then Q×Q, TQ, one-step
maps, structure and formulas above them; cases/ (case files) and references/ build on core/;
reports/ (the result model and its renderers) on cases/ and core/, never on harness/. In
harness/ the verdicts and the process protocol come first, then the case made concrete, the
claims that measure it, running a case, the library API and the command line on top; no claim
includes the command line and the protocol never includes reports/. bench/ (the benchmarks and
the `vivv bench` commands) may use everything but the command line.

Exits 1 naming every include that reaches a folder not in its row, and every source folder
without a row. --self-test builds a small tree with such includes and checks that each is
caught (the check's negative control).
"""
import pathlib
import re
import sys
import tempfile

import tree_check

CORE = ["core/platform", "core/numerics", "core/autodiff", "core/lagrangian"]
CORE_ALL = CORE + ["core/qxq", "core/tq", "core/maps", "core/structure", "core/formulas"]
BELOW_HARNESS = CORE_ALL + ["cases", "references", "reports"]
HARNESS_LOW = BELOW_HARNESS + ["harness/verdicts", "harness/process"]

LAYERS = {
    "core/platform": [],
    "core/numerics": [],
    "core/autodiff": ["core/numerics"],
    "core/lagrangian": ["core/numerics", "core/autodiff"],
    "core/qxq": CORE,
    "core/tq": CORE + ["core/qxq"],
    "core/maps": CORE,
    "core/structure": CORE + ["core/qxq"],
    "core/formulas": CORE + ["core/qxq"],
    "cases": CORE_ALL,
    "references": CORE_ALL + ["cases"],
    "reports": CORE_ALL + ["cases"],
    "harness/verdicts": BELOW_HARNESS,
    "harness/process": CORE_ALL + ["cases", "references"],
    "harness/context": HARNESS_LOW,
    "harness/claims": HARNESS_LOW + ["harness/context"],
    "harness/run": HARNESS_LOW + ["harness/context", "harness/claims"],
    "harness/library": HARNESS_LOW + ["harness/context", "harness/claims", "harness/run"],
    "harness/command_line": HARNESS_LOW + ["harness/context", "harness/claims", "harness/run",
                                           "harness/library"],
    "bench": HARNESS_LOW + ["harness/context", "harness/claims", "harness/run", "harness/library"],
}
SOURCES = {".hpp", ".cpp", ".h"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"((?:core|cases|references|reports|harness|bench)/[^"]+)"',
                     re.MULTILINE)


def folder_of(path):
    """The LAYERS row a repository path belongs to: its longest prefix among the rows, or None."""
    rows = [row for row in LAYERS if path == row or path.startswith(row + "/")]
    return max(rows, key=len) if rows else None


def violations(root):
    found = []
    for top in sorted({row.split("/")[0] for row in LAYERS}):
        for source in sorted((root / top).rglob("*")):
            if source.suffix not in SOURCES:
                continue
            relative = source.relative_to(root).as_posix()
            layer = folder_of(relative)
            if layer is None:
                found.append(f"{relative} is in a folder with no row in check_layering.py's LAYERS")
                continue
            for target in INCLUDE.findall(source.read_text()):
                target_layer = folder_of(target) or target.rsplit("/", 1)[0]
                if target_layer != layer and target_layer not in LAYERS[layer]:
                    found.append(f"{relative} includes {target}: {layer}/ may not include from "
                                 f"{target_layer}/")
    return found


def self_test():
    with tempfile.TemporaryDirectory() as directory:
        root = pathlib.Path(directory)
        for folder in ["reports", "harness/process", "harness/claims", "harness/command_line",
                       "core/numerics", "core/autodiff", "core/stray"]:
            (root / folder).mkdir(parents=True)
        (root / "harness/command_line/run.hpp").write_text("#pragma once\n")
        (root / "core/numerics/scalar.hpp").write_text("#pragma once\n")
        (root / "core/autodiff/jet.hpp").write_text('#include "core/numerics/scalar.hpp"\n')
        (root / "core/numerics/newton.hpp").write_text('#include "core/autodiff/jet.hpp"\n')
        (root / "reports/report.hpp").write_text('#include "reports/x.hpp"\n#include "harness/command_line/run.hpp"\n')
        (root / "harness/claims/claim.hpp").write_text('#include "harness/command_line/run.hpp"\n')
        (root / "harness/process/program.hpp").write_text('#include "reports/report.hpp"\n')
        (root / "core/stray/x.hpp").write_text("#pragma once\n")
        found = violations(root)
        expected = [
            "core/numerics/newton.hpp includes core/autodiff/jet.hpp: core/numerics/ may not include "
            "from core/autodiff/",
            "core/stray/x.hpp is in a folder with no row in check_layering.py's LAYERS",
            "harness/claims/claim.hpp includes harness/command_line/run.hpp: harness/claims/ may not "
            "include from harness/command_line/",
            "harness/process/program.hpp includes reports/report.hpp: harness/process/ may not include "
            "from reports/",
            "reports/report.hpp includes harness/command_line/run.hpp: reports/ may not include from "
            "harness/command_line/",
        ]
        return tree_check.self_test_outcome(
            found, expected,
            "upward includes (core/numerics into core/autodiff, reports/ and a claim into the command "
            "line, the protocol into reports/) and a folder without a row are caught")


if __name__ == "__main__":
    sys.exit(tree_check.run(sys.argv, __doc__, violations, self_test))
