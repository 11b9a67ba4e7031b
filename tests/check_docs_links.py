"""README.md and docs/ stand alone: every relative link resolves inside the repository.

usage: check_docs_links.py REPOSITORY_ROOT

Checks markdown links [text](target) and inline-code paths that start with
"../" in README.md and docs/*.md, and in docs/architecture.md every inline-code
path under a top-level folder (`core/...`, `harness/...`): its table says which
files an addition touches, so each must exist. Exits 1 naming each link that
leaves the repository or names a file that does not exist.
"""
import pathlib
import re
import sys


def main(argv):
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    root = pathlib.Path(argv[1]).resolve()
    problems = []
    for page in [root / "README.md", *sorted((root / "docs").glob("*.md"))]:
        text = page.read_text()
        targets = re.findall(r"\[[^\]\n]*\]\(([^)#\s,]+)(?:#[^)\s]*)?\)", text) + re.findall(r"`(\.\./[^`\s]*)`", text)
        if page.name == "architecture.md":
            for path in re.findall(r"`((?:core|references|cases|harness|reports|tests|bench|examples|docs)/[^`\s*]*)`", text):
                if not (root / path).exists():
                    problems.append(f"{page.relative_to(root)}: `{path}` does not exist")
        for target in targets:
            if re.match(r"[a-z]+:", target):
                continue  # an absolute URL
            resolved = (page.parent / target).resolve()
            where = f"{page.relative_to(root)}: {target}"
            if root not in resolved.parents and resolved != root:
                problems.append(f"{where} leaves the repository")
            elif not resolved.exists():
                problems.append(f"{where} does not exist")
    for problem in problems:
        print(problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
