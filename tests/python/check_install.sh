#!/usr/bin/env bash
# The Python package python/ installs offline into a virtual environment that sees Debian's
# packages (python3-venv, python3-setuptools, python3-wheel), and the installed copy is the one
# imported there, with its pytest plugin registered. Then every documented route loads the plugin
# once — the entry point alone, and beside it `-p vivv_map.pytest_plugin`, an `addopts` line or a
# conftest's `pytest_plugins` (named as the module, none registers it twice) — and from the source
# tree (PYTHONPATH, no install) each of those three. On each route a case whose command is
# "python3" runs the interpreter pytest runs, with vivv_map importable: a real vivv runs a program
# that imports vivv_map with no fallback, from a venv that is not activated.
#   check_install.sh PYTHON SOURCE_DIR WORK_DIR VIVV
set -euo pipefail
python=$1 source=$2 work=$3 vivv=$4
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
plugins = [entry.value for entry in importlib.metadata.entry_points(group="pytest11")
           if entry.name == "vivv_map.pytest_plugin"]
assert plugins == ["vivv_map.pytest_plugin"], plugins
print(f"vivv_map {vivv_map.__version__} installed at {where.parent}")
PYTHON

# A project of a user's: a Verlet that imports vivv_map plainly, and its case.
mkdir -p "$work/project/cases"
cat > "$work/project/cases/verlet.py" <<'PYTHON'
import mpmath
from vivv_map import serve

def step(h, q, p):
    p_half = p[0] - h / 2 * mpmath.sin(q[0])
    q_next = q[0] + h * p_half
    return [q_next], [p_half - h / 2 * mpmath.sin(q_next)]

serve(step)
PYTHON
cat > "$work/project/cases/verlet.json" <<'JSON'
{"name": "my-verlet", "system": {"name": "pendulum", "params": {"k": "1"}},
 "initial": {"q": ["1.1"], "w": ["0.25"]}, "T": "2", "steps": [16, 32, 64, 128],
 "discretization": {"kind": "process", "command": ["python3", "verlet.py"], "order": 2},
 "claims": ["global-order"]}
JSON
route() {  # route NAME PYTHON EXTRA-PYTHONPATH INI-EXTRA CONFTEST PYTEST-OPTIONS...
  local name=$1 interpreter=$2 pythonpath=$3 ini=$4 conftest=$5; shift 5
  printf '[pytest]\nvivv_cases = cases/*.json\n%s' "$ini" > "$work/project/pytest.ini"
  rm -f "$work/project/conftest.py"
  [ -z "$conftest" ] || echo 'pytest_plugins = ["vivv_map.pytest_plugin"]' > "$work/project/conftest.py"
  local output
  # /usr/bin first on PATH, as on a machine where "python3" is Debian's: it does not see the venv.
  if ! output=$(cd "$work/project" && PATH=/usr/bin:/bin PYTHONPATH=$pythonpath VIVV=$vivv \
                "$interpreter" -m pytest -rA -p no:cacheprovider "$@" 2>&1); then
    echo "route '$name': pytest failed"; echo "$output"; exit 1
  fi
  grep -q "PASSED cases/verlet.json::global-order" <<<"$output" ||
    { echo "route '$name': the case's claim did not run and pass"; echo "$output"; exit 1; }
  if grep -q "Unknown config option\|already registered" <<<"$output"; then
    echo "route '$name': the plugin was not loaded exactly once"; echo "$output"; exit 1
  fi
  echo "route '$name': the plugin loaded once, python3 ran the program with vivv_map"
}
venv_python=$work/venv/bin/python
route "installed" "$venv_python" "" "" ""
route "installed, -p" "$venv_python" "" "" "" -p vivv_map.pytest_plugin
route "installed, addopts" "$venv_python" "" "addopts = -p vivv_map.pytest_plugin" ""
route "installed, conftest" "$venv_python" "" "" "conftest"
route "source tree, -p" "$python" "$source/python" "" "" -p vivv_map.pytest_plugin
route "source tree, addopts" "$python" "$source/python" "addopts = -p vivv_map.pytest_plugin" ""
route "source tree, conftest" "$python" "$source/python" "" "conftest"
