#!/usr/bin/env bash
# The Python package python/ installs offline into a virtual environment that sees Debian's
# packages (python3-venv, python3-setuptools, python3-wheel), and the installed copy is the one
# imported there, with its pytest plugin registered.
#   check_install.sh PYTHON SOURCE_DIR WORK_DIR
set -euo pipefail
python=$1 source=$2 work=$3
rm -rf "$work"
"$python" -m venv --system-site-packages "$work/venv"
# pip builds in a copy of the package folder: nothing is written into the source tree.
cp -r "$source/python" "$work/package"
"$work/venv/bin/pip" install --quiet --no-index --no-build-isolation "$work/package"
cd "$work"
"$work/venv/bin/python" - <<'PYTHON'
import importlib.metadata, pathlib, sys
import vivv_map, vivv_map.testing
where = pathlib.Path(vivv_map.__file__).resolve()
assert str(where).startswith(sys.prefix), f"vivv_map imported from {where}, not from the venv {sys.prefix}"
plugins = [entry.value for entry in importlib.metadata.entry_points(group="pytest11") if entry.name == "vivv"]
assert plugins == ["vivv_map.pytest_plugin"], plugins
print(f"vivv_map {vivv_map.__version__} installed at {where.parent}")
PYTHON
