#!/usr/bin/env bash
# The slow job, `bash bootstrap.sh sanitize` (issues 15 and 27): AddressSanitizer and
# UndefinedBehaviorSanitizer over the vivv tool, in a build of its own: one `vivv run` of the
# default suite, every negative control, inconclusive and bad case of tests/ (each with the exit
# code ctest expects of it), the fuzz corpus with seeded mutations (tests/fuzz), and the ctest
# tests labelled "timing" (the process protocol's faults among them). The unit
# tests are not instrumented: their build would add 1075 s of CPU to the tool's 1340 s
# (docs/build.md), and the job must fit in CI beside the test command.
#   bash tests/sanitize.sh SOURCE_DIR WORK_DIR
# First the negative control: a heap overflow and a signed overflow compiled with the same flags
# must be caught, or a clean run would prove nothing.
set -euo pipefail
source_dir=$1
work=$2
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
# A sanitizer report exits 86, which no vivv outcome uses (0, 1 and 2 are its own).
export ASAN_OPTIONS=detect_leaks=1:halt_on_error=1:abort_on_error=0:exitcode=86
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1:exitcode=86
mkdir -p "$work"

cat > "$work/broken.cpp" <<'CPP'
#include <climits>
int main(int argc, char**) {
  if (argc == 1) {  // a read past a heap array
    int* values = new int[4];
    int past = values[argc + 3];
    delete[] values;
    return past;
  }
  int sum = INT_MAX - 1 + argc;  // argc = 2: signed overflow
  return sum > 0 ? 0 : 1;
}
CPP
g++ $flags -O1 -o "$work/broken" "$work/broken.cpp"
for args in "" "overflow"; do
  if "$work/broken" $args > "$work/broken.log" 2>&1; then
    echo "negative control: the broken program ran clean under the sanitizers"; exit 1
  fi
  grep -qE "AddressSanitizer: heap-buffer-overflow|runtime error: (load of address|signed integer overflow)" "$work/broken.log" ||
    { echo "negative control: no sanitizer report"; cat "$work/broken.log"; exit 1; }
done
echo "negative control: heap overflow and signed overflow caught"

generator=(); [ -f "$work/build/CMakeCache.txt" ] || generator=(-G Ninja)
# GCC 12 warns "may be used uninitialized" inside libstdc++'s regex and Eigen's reductions only
# when instrumenting: silenced in this build alone.
cmake -S "$source_dir" -B "$work/build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  "-DCMAKE_CXX_FLAGS=$flags -Wno-maybe-uninitialized" "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined" \
  > "$work/configure.log"
cmake --build "$work/build" --target vivv -j "$(nproc)" > "$work/build.log" 2>&1 ||
  { tail -50 "$work/build.log"; exit 1; }
echo "built vivv with $flags"
vivv="$work/build/harness/vivv"

"$vivv" run --out "$work/suite" --jobs "$(nproc)" --quiet > "$work/suite.log" 2>&1 ||
  { tail -60 "$work/suite.log"; exit 1; }
grep "claims:" "$work/suite.log"

# Each case of tests/negative, tests/boundary and tests/inconclusive must exit 1, each of
# tests/controls 0 and each of tests/bad_cases 2, as in ctest, with no sanitizer report: one case
# per core at a time.
run_case() {  # run_case CASE_FILE EXPECTED_EXIT OUT_DIR
  local code=0
  "$vivv" run "$1" --out "$3" --quiet > "$3.log" 2>&1 || code=$?
  if [ "$code" != "$2" ] || grep -qE "AddressSanitizer|LeakSanitizer|runtime error:" "$3.log"; then
    echo "$1: exit $code (expected $2) under the sanitizers"; tail -40 "$3.log"; return 1
  fi
}
export -f run_case
export vivv
# The few long cases tests/sanitize_skip.txt names (with why) are left to ctest's plain run.
skip=()
while IFS= read -r line; do
  case "$line" in ''|'#'*) continue ;; esac
  [ -f "$source_dir/tests/$line" ] || { echo "tests/sanitize_skip.txt: no test case tests/$line"; exit 1; }
  skip+=("$line")
done < "$source_dir/tests/sanitize_skip.txt"
cases=0 skipped=0
for directory_exit in negative:1 boundary:1 inconclusive:1 controls:0 bad_cases:2; do
  directory=${directory_exit%:*} expected=${directory_exit#*:}
  mkdir -p "$work/cases/$directory"
  for case_file in "$source_dir/tests/$directory"/*.json; do
    if [[ " ${skip[*]} " == *" $directory/$(basename "$case_file") "* ]]; then skipped=$((skipped + 1)); continue; fi
    printf '%s\0%s\0%s\0' "$case_file" "$expected" "$work/cases/$directory/$(basename "$case_file" .json)"
    cases=$((cases + 1))
  done
done > "$work/cases.list"
xargs -0 -n 3 -P "$(nproc)" bash -c 'run_case "$@"' _ < "$work/cases.list" ||
  { echo "a test case ended otherwise than ctest expects (above)"; exit 1; }
echo "$cases negative, inconclusive and bad cases: the expected exit codes, no sanitizer report ($skipped long ones left to ctest: tests/sanitize_skip.txt)"
# Hostile inputs under the sanitizers: other mutations (seed 2) than ctest's fuzz/inputs (seed 1).
python3 "$source_dir/tests/fuzz/fuzz_inputs.py" "$vivv" "$source_dir/tests/fuzz/corpus" \
  "$work/fuzz" --mutations 8 --seed 2 > "$work/fuzz.log" 2>&1 || { tail -40 "$work/fuzz.log"; exit 1; }
tail -1 "$work/fuzz.log"
# The tests whose outcome involves wall time (ctest label "timing": --max-seconds budgets,
# progress heartbeats, signals while a run computes, and the process protocol's faults, timeouts
# and signals, tests/process/check_process_maps.py) and the hostile inputs' tests (label
# "hostile": programs that escape, nest, write bytes that are not UTF-8 or numbers out of range,
# CSV formulas, edited baselines and reports) run again here, at about a third of the plain build's
# speed: a check at another speed, with this build's vivv, and no sanitizer report allowed (one
# exits 86, which no expected exit code is). Those labelled "memory" run vivv under an
# address-space cap, which AddressSanitizer's shadow memory (terabytes reserved) cannot start
# under: the plain build runs them.
# AddressSanitizer would catch the SIGSEGV the interrupt check sends a --jobs worker and end it with
# its own report (exit 2 for the run instead of 3 naming the signal): here, and only here, a
# SIGSEGV is left to kill the process as it would in the plain build.
(cd "$work/build" && ASAN_OPTIONS="$ASAN_OPTIONS:handle_segv=0" ctest -L "timing|hostile" -LE memory --output-on-failure) \
  > "$work/timing.log" 2>&1 ||
  { tail -60 "$work/timing.log"; exit 1; }
grep -E "tests passed|tests failed" "$work/timing.log"
echo "sanitizers clean: the default suite, the test cases, the fuzz corpus, the timing and the hostile tests"
