#!/usr/bin/env bash
# The entry points of the README, for a fresh Debian 12 machine:
#   bash bootstrap.sh run       install what is missing, build the vivv tool, run the default suite
#                               (writes vivv-report/)
#   bash bootstrap.sh test      install what is missing, build everything, run every test (ctest)
#                               but those labelled slow
#   bash bootstrap.sh slow      the slow jobs: the tests labelled slow, then what sanitize does
#   bash bootstrap.sh sanitize  the vivv tool built again under AddressSanitizer and
#                               UndefinedBehaviorSanitizer, and the default suite, the test cases and
#                               the fuzz corpus run under them, after a negative control
#                               (tests/sanitize.sh)
set -euo pipefail
cd "$(dirname "$0")"

mode=${1:-}
case "$mode" in run|test|slow|sanitize) ;; *) echo "usage: bash bootstrap.sh run|test|slow|sanitize" >&2; exit 2 ;; esac

# Debian packages vivv builds with (nothing else, nothing downloaded): all `run` needs.
packages=(g++ cmake make ninja-build libeigen3-dev libboost-dev libmpfr-dev libgmp-dev nlohmann-json3-dev)
# Only needed to test: GoogleTest for the unit tests, python3-jsonschema to check reports against
# their schema a second way, the "browser" tests render report.html in headless Chromium, the
# "scale" tests start shards with GNU parallel, the "python" tests run the integrators of
# examples/python-integrator (mpmath, NumPy) through the process protocol, the package python/
# under pytest, and its offline installation into a venv (venv, setuptools, wheel). Google
# Benchmark only for the slow job, which builds the benchmarks.
if [ "$mode" != run ]; then
  packages+=(libgtest-dev python3-jsonschema chromium parallel python3-mpmath python3-numpy python3-pytest
             python3-venv python3-setuptools python3-wheel)
fi
if [ "$mode" = slow ]; then
  packages+=(libbenchmark-dev)
fi
sudo_cmd=""; [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
missing=()
for package in "${packages[@]}"; do
  dpkg -s "$package" >/dev/null 2>&1 || missing+=("$package")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq "${missing[@]}"
fi

# Valijson, the schema validator, is header-only, but Debian's libvalijson-dev depends on the
# libraries of all its adapters (Qt 5, Poco, yaml-cpp, jsoncpp, RapidJSON, picojson: 97 packages),
# of which vivv uses none (it validates nlohmann-json documents). Unless it is installed, its
# Debian package is fetched with apt-get download and unpacked into .deps/valijson (git-ignored),
# where CMake looks for it: the same Debian headers, without the 97 packages.
if ! dpkg -s libvalijson-dev >/dev/null 2>&1 && [ ! -f .deps/valijson/usr/include/valijson/validator.hpp ]; then
  mkdir -p .deps
  echo "unpacking Debian's libvalijson-dev (headers only) into .deps/valijson"
  (cd .deps && { apt-get download -qq libvalijson-dev 2>/dev/null ||
                 { $sudo_cmd apt-get update -qq && apt-get download -qq libvalijson-dev; }; })
  dpkg-deb -x .deps/libvalijson-dev_*.deb .deps/valijson
  rm -f .deps/libvalijson-dev_*.deb
fi

jobs=$(nproc)
if [ "$mode" = sanitize ]; then
  exec bash tests/sanitize.sh "$PWD" "$PWD/build-sanitize"
fi

# Ninja keeps both cores busy to the end of the build (make idles while the last unit of a
# target compiles); a build/ configured earlier keeps its generator.
generator=(); [ -f build/CMakeCache.txt ] || generator=(-G Ninja)
tests=ON; [ "$mode" = run ] && tests=OFF  # the run builds the tool alone: no GoogleTest needed
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DVIVV_TESTS=$tests >/dev/null
if [ "$mode" = run ]; then
  # The run needs the tool alone, not the unit tests or the benchmarks.
  cmake --build build -j "$jobs" --target vivv
  exec build/harness/vivv run --out vivv-report --jobs "$jobs" --progress
fi
cmake --build build -j "$jobs"
if [ "$mode" = slow ]; then
  # The slow jobs: the benchmarks built (not by the test command: docs/build.md), the tests
  # labelled "slow" (systems of a hundred coordinates and more, minutes each; `vivv bench`), then
  # the sanitizer build.
  cmake --build build -j "$jobs" --target benchmarks
  (cd build && ctest --output-on-failure -j "$jobs" -L slow)
  exec bash tests/sanitize.sh "$PWD" "$PWD/build-sanitize"
fi
cd build && exec ctest --output-on-failure -j "$jobs" -LE slow
