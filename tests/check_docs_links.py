"""README.md and docs/ stand alone, and every repository path they name exists.

usage: check_docs_links.py REPOSITORY_ROOT
       check_docs_links.py --self-test

Reads README.md, docs/*.md and the README.md or other .md files one folder down (examples/*/
included). Checks markdown links [text](target) and inline-code paths that start with "../":
each must resolve inside the repository. Checks every path under a top-level folder that the
prose names (`core/qxq/galerkin.hpp`, harness/command_line/, tests/negative/NAME-…), backticked
or not, outside fenced code blocks (those show a user's own files): it must exist, or be the
beginning of a name that exists (a family of test cases). A file that moves without its
mention in the docs fails here. Exits 1 naming each link or path that does not hold.
--self-test plants a moved file, a link out of the repository and a family prefix in a small
tree and checks that exactly the first two are reported (the check's negative control).
"""
import pathlib
import re
import sys
import tempfile

import tree_check

TOP = "core|references|cases|harness|reports|tests|bench|examples|docs|python"
PATH = re.compile(rf"(?<![\w./-])((?:{TOP})/[\w./-]*\w/?)")
LINK = re.compile(r"\[[^\]\n]*\]\(([^)#\s,]+)(?:#[^)\s]*)?\)")


def pages(root):
    found = [root / "README.md", *sorted((root / "docs").glob("*.md"))]
    found += sorted(root.glob("*/*.md")) + sorted(root.glob("examples/*/*.md"))
    return [page for page in dict.fromkeys(found) if page.exists()]


def without_fenced_code(text):
    return re.sub(r"^```.*?^```", "", text, flags=re.MULTILINE | re.DOTALL)


def names_something(root, path):
    target = root / path
    return target.exists() or any(target.parent.glob(target.name + "*"))


def problems_in(root):
    problems = []
    for page in pages(root):
        text = page.read_text()
        where = page.relative_to(root)
        for path in dict.fromkeys(PATH.findall(without_fenced_code(text))):
            if not names_something(root, path):
                problems.append(f"{where}: {path} does not exist")
        for target in LINK.findall(text) + re.findall(r"`(\.\./[^`\s]*)`", text):
            if re.match(r"[a-z]+:", target):
                continue  # an absolute URL
            resolved = (page.parent / target).resolve()
            if root not in resolved.parents and resolved != root:
                problems.append(f"{where}: {target} leaves the repository")
            elif not resolved.exists():
                problems.append(f"{where}: {target} does not exist")
    return problems


def self_test():
    with tempfile.TemporaryDirectory() as directory:
        root = pathlib.Path(directory)
        (root / "docs").mkdir()
        (root / "core" / "qxq").mkdir(parents=True)
        (root / "tests" / "negative").mkdir(parents=True)
        (root / "core" / "qxq" / "galerkin.hpp").write_text("")
        (root / "tests" / "negative" / "weight-off-double.json").write_text("")
        (root / "README.md").write_text("See core/qxq/galerkin.hpp and [the theory](../../theory.md).\n")
        (root / "docs" / "a.md").write_text("The rule is in `core/galerkin.hpp`; its negatives are "
                                            "tests/negative/weight-off-….\n```\nrun(cases/mine.json)\n```\n")
        return tree_check.self_test_outcome(
            problems_in(root),
            ["README.md: ../../theory.md leaves the repository", "docs/a.md: core/galerkin.hpp does not exist"],
            "a moved file and a link out of the repository are caught; a family prefix and a user's "
            "file in a code block are not")


if __name__ == "__main__":
    sys.exit(tree_check.run(sys.argv, __doc__, problems_in, self_test))
