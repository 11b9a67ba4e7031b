#!/bin/sh
# Sharded and parallel runs give the serial run's report.
#
#   check_sharding.sh jobs   VIVV OUT CASE.json ...   --jobs 2 against a serial run
#   check_sharding.sh shards VIVV OUT CASE.json ...   two shards run by GNU parallel, merged
#                                                     by vivv report, against a serial run
#   check_sharding.sh alone  VIVV OUT CASE.json ...   each case in a shard of its own (no reference
#                                                     flow shared), merged, and --jobs 2, against a
#                                                     serial run
#   check_sharding.sh cache  VIVV OUT CASE.json ...   --reference-cache cold, warm and with a cut
#                                                     file, against a run without it
#
# "The same" is tests/compare_reports.py: byte-identical apart from the run block.
set -eu
mode=$1 vivv=$2 out=$3
shift 3
here=$(dirname "$0")
rm -rf "$out"
mkdir -p "$out"
[ "$mode" = alone ] || [ "$mode" = cache ] || "$vivv" run "$@" --out "$out/serial" --quiet > /dev/null
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
  alone)
    # Cases on one system share its reference flow in one process (the serial run above, and a
    # --jobs worker's batch); each case alone — as many shards as cases, one case each — makes its
    # own. The merged report is the serial one to the bit, and the serial run said it shared.
    "$vivv" run "$@" --out "$out/shared" --progress > /dev/null 2> "$out/shared.log" || test $? -eq 1
    grep -q "the flow an earlier case on this system made, kept for this one" "$out/shared.log" ||
      { echo "no case of the serial run shared a reference flow:"; cat "$out/shared.log"; exit 1; }
    count=$#
    shard=1
    reports=""
    while [ "$shard" -le "$count" ]; do
      "$vivv" run "$@" --shard "$shard/$count" --out "$out/alone$shard" --quiet > /dev/null || test $? -eq 1
      reports="$reports $out/alone$shard/report.json"
      shard=$((shard + 1))
    done
    # shellcheck disable=SC2086
    "$vivv" report $reports --out "$out/merged" > /dev/null || test $? -eq 1
    python3 "$here/compare_reports.py" "$out/shared/report.json" "$out/merged/report.json"
    # With --jobs 2 a worker that finished a case takes the next one on the same system.
    "$vivv" run "$@" --jobs 2 --out "$out/jobs" --progress > /dev/null 2> "$out/jobs.log" || test $? -eq 1
    grep -q "the flow an earlier case on this system made, kept for this one" "$out/jobs.log" ||
      { echo "no worker of the --jobs 2 run shared a reference flow:"; cat "$out/jobs.log"; exit 1; }
    python3 "$here/compare_reports.py" "$out/shared/report.json" "$out/jobs/report.json"
    ;;
  cache)
    # --reference-cache: a first run keeps the reference flows' answers, a second one is told them
    # (and says so) and writes the report a run without the cache writes, to the bit; a file
    # that is not what it claims to be (here: cut short) is said, not used, and replaced.
    "$vivv" run "$@" --out "$out/plain" --quiet > /dev/null || test $? -eq 1
    "$vivv" run "$@" --reference-cache "$out/cache" --out "$out/cold" --quiet > /dev/null || test $? -eq 1
    ls "$out/cache"/*.json > /dev/null
    "$vivv" run "$@" --reference-cache "$out/cache" --out "$out/warm" --progress > /dev/null 2> "$out/warm.log" || test $? -eq 1
    grep -q "with the answers an earlier run of this vivv kept" "$out/warm.log" ||
      { echo "the second run did not use the kept answers:"; cat "$out/warm.log"; exit 1; }
    python3 "$here/compare_reports.py" "$out/plain/report.json" "$out/cold/report.json"
    python3 "$here/compare_reports.py" "$out/plain/report.json" "$out/warm/report.json"
    for kept in "$out/cache"/*.json; do head -c 100 "$kept" > "$kept.cut" && mv "$kept.cut" "$kept"; done
    "$vivv" run "$@" --reference-cache "$out/cache" --out "$out/cut" --quiet > /dev/null 2> "$out/cut.log" || test $? -eq 1
    grep -q "not used (" "$out/cut.log" || { echo "a cut cache file was not reported:"; cat "$out/cut.log"; exit 1; }
    python3 "$here/compare_reports.py" "$out/plain/report.json" "$out/cut/report.json"
    ;;
  *) echo "usage: check_sharding.sh jobs|shards|alone|cache VIVV OUT CASE.json ..." >&2; exit 2 ;;
esac
