"""The pytest fixture `vivv` (loaded by the installed package's entry point, or by
`pytest_plugins = ["vivv_map.pytest_plugin"]` in a conftest.py): vivv(*cases, **options) runs
vivv into a temporary directory of the test and returns its vivv_map.testing.Run."""
import tempfile

import pytest

from .testing import run_vivv


@pytest.fixture
def vivv(tmp_path):
    counter = iter(range(1 << 30))

    def run(*cases, **options):
        options.setdefault("out", tmp_path / f"vivv-{next(counter)}")
        return run_vivv(*cases, **options)

    return run


# Case files as tests: with `vivv_cases = cases/*.json` (glob patterns, relative to the rootdir)
# in the pytest configuration, each matching case file is collected as one test per claim it
# lists — `-k symplecticity` selects claims — and vivv runs once per file, when its first claim is
# run. A claim passes on "pass", is reported as xfail on "xfail" (the case's own "xfail"), and fails
# on anything else with vivv's reason; a case that could not run, or that vivv refused, fails each of
# its claims with the cause. `vivv_args` gives more options for those runs ("--scalar mpfr").
def pytest_addoption(parser):
    parser.addini("vivv_cases", type="args", default=[],
                  help="glob patterns of vivv case files to collect as tests, one per claim")
    parser.addini("vivv_args", type="args", default=[], help="options for the vivv runs of collected case files")


def pytest_collect_file(file_path, parent):
    import fnmatch

    patterns = parent.config.getini("vivv_cases")
    if file_path.suffix != ".json" or not patterns:
        return None
    relative = str(file_path.relative_to(parent.config.rootpath)) if file_path.is_relative_to(
        parent.config.rootpath) else str(file_path)
    if any(fnmatch.fnmatch(relative, pattern) or fnmatch.fnmatch(file_path.name, pattern) for pattern in patterns):
        return VivvCaseFile.from_parent(parent, path=file_path)
    return None


class VivvCaseFile(pytest.File):
    """A case file: its claims as items, one vivv run shared by them."""

    def collect(self):
        import json

        try:
            case = json.loads(self.path.read_text())
        except (OSError, UnicodeDecodeError, ValueError) as error:
            raise self.CollectError(f"{self.path}: not valid JSON: {error}") from None
        for field, problem in case_shape_problems(case):
            raise self.CollectError(f"{self.path}: " + (f"field '{field}': " if field else "") + problem)
        self.case_name = case.get("name", self.path.stem)
        xfail = case.get("xfail", {})
        for claim in case["claims"]:
            item = VivvClaimItem.from_parent(self, name=claim)
            if claim in xfail:
                reason = xfail[claim] if isinstance(xfail[claim], str) else xfail[claim].get("reason", "")
                # Only the case's own expected failure — vivv's verdict "xfail" — is pytest's expected
                # failure: raises= makes any other exception (a fail for another reason, an error, an
                # inconclusive verdict, a refused run) an ordinary failure, as vivv's exit status is.
                item.add_marker(pytest.mark.xfail(reason=f"the case expects it to fail: {reason}", strict=True,
                                                  raises=VivvExpectedFailure))
            yield item

    def run(self):
        """vivv run on this file, once: the Run, or the VivvError it raised."""
        if not hasattr(self, "_outcome"):
            factory = getattr(self.config, "_tmp_path_factory", None)  # pytest's tmp_path_factory
            out = factory.mktemp("vivv-" + self.path.stem) if factory else tempfile.mkdtemp(prefix="vivv-")
            try:
                self._outcome = run_vivv(str(self.path), out=out, args=self.config.getini("vivv_args"))
            except Exception as error:  # VivvError: refused, not started, beyond the timeout
                self._outcome = error
        return self._outcome


class VivvClaimFailure(Exception):
    """A claim that did not pass: vivv's verdict and reason, shown without a traceback."""


class VivvExpectedFailure(VivvClaimFailure):
    """vivv's verdict "xfail": the claim failed as the case's "xfail" states, and only that."""


def case_shape_problems(case):
    """(field, problem) for each part of a case file the collector reads — the file an object, its
    claims a non-empty list of distinct names, its xfail an object of claims it lists, each with a
    reason or an object — that vivv refuses (exit 2) before any computation; empty when none."""
    if not isinstance(case, dict):
        return [("", f"expected a JSON object (a case), got {type(case).__name__ if case is not None else 'null'}")]
    claims = case.get("claims")
    if not isinstance(claims, list) or not all(isinstance(claim, str) for claim in claims):
        return [("claims", "expected a list of claim names, got " + json_text(claims))]
    if not claims:
        return [("claims", "expected at least one claim")]
    for i, claim in enumerate(claims):
        if claim in claims[:i]:
            return [(f"claims[{i}]", f"'{claim}' is listed twice")]
    xfail = case.get("xfail", {})
    if not isinstance(xfail, dict):
        return [("xfail", "expected an object {claim: reason}, got " + json_text(xfail))]
    for claim, expected in xfail.items():
        if claim not in claims:
            return [(f"xfail.{claim}", "not a claim this case checks (its claims: " + ", ".join(claims) + ")")]
        if not isinstance(expected, (str, dict)):
            return [(f"xfail.{claim}", "expected the reason the claim is known to fail, or an object with it, got "
                     + json_text(expected))]
    return []


def json_text(value, limit=80):
    import json

    text = json.dumps(value, ensure_ascii=False)
    return text if len(text) <= limit else text[:limit - 1] + "…"


class VivvClaimItem(pytest.Item):
    def runtest(self):
        from .testing import _shortened

        outcome = self.parent.run()
        case = self.parent.case_name
        if isinstance(outcome, Exception):
            raise VivvClaimFailure(f"vivv did not run {self.parent.path.name}: {_shortened(str(outcome), 600)}")
        if case in outcome.could_not_run:
            raise VivvClaimFailure(f"{case} could not run: {_shortened(outcome.could_not_run[case], 600)}")
        verdict = outcome.verdicts[case].get(self.name)
        if verdict in ("pass", "xpass"):  # an xpass: the item's strict xfail marker fails it
            return
        if verdict == "xfail":  # the case's xfail: the failure it states (the item's marker reports it)
            raise VivvExpectedFailure(f"{case} / {self.name}: xfail, as the case states: "
                                   f"{_shortened(outcome.claim(case, self.name).get('explanation', ''))}")
        why = outcome.claim(case, self.name).get("explanation", "") if verdict is not None else "not in the report"
        raise VivvClaimFailure(f"{case} / {self.name}: {verdict}: {_shortened(why, 600)}")

    def repr_failure(self, excinfo):
        if isinstance(excinfo.value, VivvClaimFailure):
            return str(excinfo.value)
        return super().repr_failure(excinfo)

    def reportinfo(self):
        return self.path, None, f"{self.parent.case_name}::{self.name}"
