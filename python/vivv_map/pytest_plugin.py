"""vivv's pytest plugin: the fixture `vivv` and case files collected as tests.

It loads by itself where vivv_map is installed (its entry point); used from the source tree
(PYTHONPATH=python) load it with `-p vivv_map.pytest_plugin`, `addopts = -p vivv_map.pytest_plugin`
in the pytest configuration, or `pytest_plugins = ["vivv_map.pytest_plugin"]` in a conftest.py —
each of these also works, harmlessly, where it is installed.

vivv(*cases, **options) runs vivv into a temporary directory of the test and returns its
vivv_map.testing.Run."""
import hashlib
import json
import pathlib
import shutil
import sys
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
    parser.addini("vivv_cache", type="bool", default=False,
                  help="reuse a collected case file's vivv run while nothing it is keyed by changed (--vivv-cache)")
    parser.addoption("--vivv-cache", action="store_true", default=False,
                     help="reuse a collected case file's vivv run from pytest's cache while the case file, the files "
                          "its command names, vivv's binary, vivv_args and the interpreter are unchanged "
                          "(--cache-clear forgets them)")


# The opt-in result cache: a collected case file's report directory, kept in pytest's cache
# (.pytest_cache/d/vivv/KEY) under a hash of what the verdicts follow from — the case file's bytes,
# the bytes of every file its "command" names (a program, a module path given as an argument),
# vivv's binary, the options and the interpreter that runs "python3". What the key cannot see — a
# module the program imports without naming it, a file the case reads through another path — is
# the user's to clear with --cache-clear. Only runs that produced verdicts for every case are kept:
# a program that could not start (a missing module) is retried.
def cache_key(case_path, options):
    from .testing import find_vivv

    digest = hashlib.sha256()

    def add(label, data):
        digest.update(label.encode() + b"\0" + (data if isinstance(data, bytes) else data.encode()) + b"\0")

    case_bytes = case_path.read_bytes()
    add("case", case_bytes)
    try:
        discretization = json.loads(case_bytes).get("discretization", {})
        command = discretization.get("command", []) if isinstance(discretization, dict) else []
    except (ValueError, AttributeError):
        command = []
    for argument in command if isinstance(command, list) else []:
        named = case_path.parent / str(argument)
        if isinstance(argument, str) and named.is_file():
            add("file " + argument, named.read_bytes())
    vivv = pathlib.Path(shutil.which(find_vivv()) or find_vivv())
    add("vivv", vivv.read_bytes() if vivv.is_file() else str(vivv))
    add("options", json.dumps(list(options)))
    add("interpreter", sys.executable)
    return digest.hexdigest()[:32]


def cached_run(config, case_path, options, compute):
    """compute(reference_cache) through the cache when it is on — reference_cache the directory of the
    reference flows' answers, or None with the cache off: (Run or exception, whether it came from the cache)."""
    from .testing import Run

    if not (config.getoption("vivv_cache") or config.getini("vivv_cache")):
        return compute(None), False
    cache = getattr(config, "cache", None)
    if cache is None:
        raise pytest.UsageError("--vivv-cache (or vivv_cache = true) keeps runs in pytest's cache, which "
                                 "-p no:cacheprovider turned off")
    key = cache_key(case_path, options)
    kept = pathlib.Path(cache.mkdir("vivv")) / key
    if (kept / "report.json").is_file() and (kept / "exit-code").is_file():
        return Run(int((kept / "exit-code").read_text()), (kept / "console.txt").read_text(), kept), True
    # A run computed again (its program edited, say) reuses the reference flows' answers an earlier
    # run kept (vivv run --reference-cache: the same numbers to the bit, from the same vivv).
    outcome = compute(pathlib.Path(cache.mkdir("vivv-references")))
    if not isinstance(outcome, Exception) and not outcome.could_not_run:
        if kept.exists():
            shutil.rmtree(kept)
        shutil.copytree(outcome.out, kept)
        (kept / "console.txt").write_text(outcome.console)
        (kept / "exit-code").write_text(str(outcome.exit_code))
    return outcome, False


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
        """vivv run on this file, once (or from the cache): the Run, or the VivvError it raised."""
        if not hasattr(self, "_outcome"):
            options = self.config.getini("vivv_args")

            def compute(reference_cache):
                factory = getattr(self.config, "_tmp_path_factory", None)  # pytest's tmp_path_factory
                out = factory.mktemp("vivv-" + self.path.stem) if factory else tempfile.mkdtemp(prefix="vivv-")
                extra = ["--reference-cache", str(reference_cache)] if reference_cache else []
                try:
                    return run_vivv(str(self.path), out=out, args=list(options) + extra)
                except Exception as error:  # VivvError: refused, not started, beyond the timeout
                    return error

            self._outcome, self.from_cache = cached_run(self.config, self.path, options, compute)
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
        seconds = outcome.report.get("run", {}).get("claim_seconds", {}).get(case, {}).get(self.name)
        if isinstance(seconds, (int, float)):
            self.claim_seconds = seconds
            self.user_properties.append(("vivv_seconds", seconds))
        if self.parent.from_cache:
            self.user_properties.append(("vivv_cached", str(outcome.out)))
        if verdict in ("pass", "xpass"):  # an xpass: the item's strict xfail marker fails it
            return
        where = f"\nreport: {outcome.out / 'report.html'}" + (
            " (kept by --vivv-cache; --cache-clear recomputes it)" if self.parent.from_cache else "")
        if verdict == "xfail":  # the case's xfail: the failure it states (the item's marker reports it)
            raise VivvExpectedFailure(f"{case} / {self.name}: xfail, as the case states: "
                                   f"{_shortened(outcome.claim(case, self.name).get('explanation', ''))}")
        why = outcome.claim(case, self.name).get("explanation", "") if verdict is not None else "not in the report"
        raise VivvClaimFailure(f"{case} / {self.name}: {verdict}: {_shortened(why, 600)}{where}")

    def repr_failure(self, excinfo):
        if isinstance(excinfo.value, VivvClaimFailure):
            return str(excinfo.value)
        return super().repr_failure(excinfo)

    def reportinfo(self):
        return self.path, None, f"{self.parent.case_name}::{self.name}"


# JUnit (--junitxml) and --durations give a claim its own time: vivv's seconds for that claim (its
# judgement and the sweep runs it was the first to need; report.json's run.claim_seconds), not the
# whole case's run that its file's first selected claim waited for. pytest's own measurement stays
# in the item's user properties as "pytest_seconds".
@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    if isinstance(item, VivvClaimItem) and call.when == "call" and hasattr(item, "claim_seconds"):
        report = outcome.get_result()
        item.user_properties.append(("pytest_seconds", report.duration))
        report.user_properties = list(item.user_properties)
        report.duration = float(item.claim_seconds)
