"""The pytest fixture `vivv` (loaded by the installed package's entry point, or by
`pytest_plugins = ["vivv_map.pytest_plugin"]` in a conftest.py): vivv(*cases, **options) runs
vivv into a temporary directory of the test and returns its vivv_map.testing.Run."""
import pytest

from .testing import run_vivv


@pytest.fixture
def vivv(tmp_path):
    counter = iter(range(1 << 30))

    def run(*cases, **options):
        options.setdefault("out", tmp_path / f"vivv-{next(counter)}")
        return run_vivv(*cases, **options)

    return run
