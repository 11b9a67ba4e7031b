#!/bin/sh
# Sharded and parallel runs give the serial run's report.
#
#   check_sharding.sh jobs   VIVV OUT CASE.json ...   --jobs 2 against a serial run
#   check_sharding.sh shards VIVV OUT CASE.json ...   two shards run by GNU parallel, merged
#                                                     by vivv report, against a serial run
#
# "The same" is tests/compare_reports.py: byte-identical apart from the run block.
set -eu
mode=$1 vivv=$2 out=$3
shift 3
here=$(dirname "$0")
rm -rf "$out"
mkdir -p "$out"
"$vivv" run "$@" --out "$out/serial" --quiet > /dev/null
case "$mode" in
  jobs)
    "$vivv" run "$@" --jobs 2 --out "$out/jobs" --quiet > /dev/null
    python3 "$here/compare_reports.py" "$out/serial/report.json" "$out/jobs/report.json"
    ;;
  shards)
    # GNU parallel starts the shards (on more machines: --sshlogin; docs/scale.md).
    parallel --will-cite --halt now,fail=1 -j 2 "$vivv" run "$@" --shard {}/2 --out "$out/shard{}" --quiet \
      ::: 1 2 > /dev/null
    "$vivv" report "$out/shard1/report.json" "$out/shard2/report.json" --out "$out/merged" > /dev/null
    python3 "$here/compare_reports.py" "$out/serial/report.json" "$out/merged/report.json"
    # Negative control: one shard alone is not the suite.
    if "$vivv" report "$out/shard2/report.json" --out "$out/incomplete" > "$out/incomplete.log" 2>&1; then
      echo "merging shard 2 of 2 alone was accepted"; exit 1
    fi
    grep -q "shard 1 of 2 is missing" "$out/incomplete.log" || { cat "$out/incomplete.log"; exit 1; }
    test ! -e "$out/incomplete/report.json"
    # ... nor does a shard of another list of cases (here the same cases, reversed).
    reversed=""
    for case_file in "$@"; do reversed="$case_file $reversed"; done
    # shellcheck disable=SC2086
    "$vivv" run $reversed --shard 1/2 --out "$out/reversed1" --quiet > /dev/null || true
    if "$vivv" report "$out/reversed1/report.json" "$out/shard2/report.json" --out "$out/foreign" \
         > "$out/foreign.log" 2>&1; then
      echo "merging shards of two different case lists was accepted"; exit 1
    fi
    grep -q "run.shard.suite: not the list of cases" "$out/foreign.log" || { cat "$out/foreign.log"; exit 1; }
    test ! -e "$out/foreign/report.json"
    # Shards run with the same --claims written in another order merge: the same set is the same
    # selection (issue 51). Each shard's exit is its verdicts'; the merge is what is checked.
    "$vivv" run "$@" --claims global-order,lagrangian-order --shard 1/2 --out "$out/claims1" --quiet > /dev/null || true
    "$vivv" run "$@" --claims lagrangian-order,global-order --shard 2/2 --out "$out/claims2" --quiet > /dev/null || true
    "$vivv" report "$out/claims1/report.json" "$out/claims2/report.json" --out "$out/claims-merged" \
      > "$out/claims.log" 2>&1 || { echo "shards with the same --claims in another order do not merge:"; cat "$out/claims.log"; exit 1; }
    ;;
  *) echo "usage: check_sharding.sh jobs|shards VIVV OUT CASE.json ..." >&2; exit 2 ;;
esac
