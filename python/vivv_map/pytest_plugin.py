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

        case = json.loads(self.path.read_text())
        self.case_name = case.get("name", self.path.stem)
        xfail = case.get("xfail", {}) if isinstance(case.get("xfail"), dict) else {}
        for claim in case.get("claims", []):
            item = VivvClaimItem.from_parent(self, name=str(claim))
            if claim in xfail:
                reason = xfail[claim] if isinstance(xfail[claim], str) else xfail[claim].get("reason", "")
                item.add_marker(pytest.mark.xfail(reason=f"the case expects it to fail: {reason}", strict=True))
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
            raise VivvClaimFailure(f"{case} / {self.name}: xfail, as the case states: "
                                   f"{_shortened(outcome.claim(case, self.name).get('explanation', ''))}")
        why = outcome.claim(case, self.name).get("explanation", "") if verdict is not None else "not in the report"
        raise VivvClaimFailure(f"{case} / {self.name}: {verdict}: {_shortened(why, 600)}")

    def repr_failure(self, excinfo):
        if isinstance(excinfo.value, VivvClaimFailure):
            return str(excinfo.value)
        return super().repr_failure(excinfo)

    def reportinfo(self):
        return self.path, None, f"{self.parent.case_name}::{self.name}"
