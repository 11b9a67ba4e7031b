#!/usr/bin/env bash
# vivv under an address-space cap (ulimit -v, RLIMIT_AS): a formula whose recording needs more than
# the cap leaves is refused while it is read — exit 2, the estimate and the limit named, no report,
# within seconds and without std::bad_alloc — and a case that fits completes under the same cap.
#   check_memory_limits.sh VIVV PYTHON WORK_DIR
# Not run under AddressSanitizer (tests/sanitize.sh): its shadow memory reserves terabytes of
# address space, which no cap below the machine's memory leaves.
set -euo pipefail
vivv=$1 python=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
cap_kib=1500000  # about 1.4 GiB of address space
# All pairs of N particles in space, a Lennard-Jones sum. N = 400 is 79,800 pairs, more than a
# million operations, whose recording (about 2 KiB an operation) passes the cap: refused while it is
# read. N = 300 (44,850 pairs) is read within the cap, and the run's estimate refuses it: the
# reference flow's Taylor coefficients in MPFR at 30 digits, some 5 GiB. N = 4 reads and runs in a
# few MiB.
"$python" - "$work" <<'EOF'
import json, sys
work = sys.argv[1]
for n, name in ((400, "pairs-beyond-the-cap"), (300, "reference-beyond-the-cap"), (4, "pairs-within-the-cap")):
    r2 = "(x[i,1]-x[j,1])^2 + (x[i,2]-x[j,2])^2 + (x[i,3]-x[j,3])^2"
    L = (f"sum(i = 1..{n}, sum(k = 1..3, v[i,k]^2))/2 - "
         f"sum(i = 1..{n}, sum(j = i+1..{n}, 1/({r2})^6 - 1/({r2})^3))")
    q = [str(1.5 * i + 0.1 * k) for i in range(n) for k in range(3)]
    case = {"name": name, "system": {"name": "pairs", "lagrangian": L, "coordinates": [{"x": [n, 3]}],
                                      "velocities": [{"v": [n, 3]}]},
            "initial": {"q": q, "w": ["0"] * (3 * n)}, "T": "0.5", "steps": [8, 16, 32, 64], "scalar": "mpfr", "digits": 30,
            "discretization": {"kind": "midpoint"}, "claims": ["global-order"]}
    json.dump(case, open(f"{work}/{name}.json", "w"))
EOF
# Runs the case $work/$1.json under the cap into $work/$2: its exit code in $code, its output in
# $work/$2.log (and shown).
run_capped() {
  code=0
  (ulimit -v $cap_kib; exec "$vivv" run "$work/$1.json" --out "$work/$2" --quiet) > "$work/$2.log" 2>&1 || code=$?
  cat "$work/$2.log"
}
# The run into $work/$1 refused as bad input ($2 names it): exit 2, no std::bad_alloc, no report.
expect_refused() {
  [ "$code" -eq 2 ] || { echo "expected exit 2 for $2, got $code"; exit 1; }
  if grep -q "bad_alloc" "$work/$1.log"; then echo "std::bad_alloc instead of the estimate"; exit 1; fi
  [ ! -e "$work/$1/report.json" ] || { echo "a report was written for a refused case"; exit 1; }
}
run_capped pairs-beyond-the-cap beyond
expect_refused beyond "the case beyond the cap"
grep -q "field 'system.lagrangian': reading this system needs more than the [0-9.]* GiB this process may take (what its address-space limit, RLIMIT_AS or ulimit -v, leaves)" "$work/beyond.log" ||
  { echo "the refusal does not name the estimate and the address-space limit"; exit 1; }
run_capped reference-beyond-the-cap reference
expect_refused reference "the reference beyond the cap"
grep -q "field 'system.coordinates': a system of 900 coordinates whose L takes [0-9]* operations needs about [0-9.]* GiB in mpfr, [0-9.]* GiB of it for reference flow (3 arrays x [0-9]* acceleration nodes x" "$work/reference.log" &&
  grep -q "or a scalar of fewer digits is what would fit" "$work/reference.log" ||
  { echo "the refusal does not name the reference flow's part and what would fit"; exit 1; }
run_capped pairs-within-the-cap within
[ "$code" -eq 0 ] || { echo "expected exit 0 for the case within the cap, got $code"; exit 1; }
grep -q '"verdict": "pass"' "$work/within/report.json" || { echo "global-order did not pass within the cap"; exit 1; }
# A case refused for what one claim keeps names the claim and what would fit: symplecticity on a
# 16-coordinate chain (the dense check, a 32 x 32 Jacobian a step) over a run of 400,000 steps keeps
# some 6.5 GiB of Jacobians in float128; without the claim, or with fewer steps, it fits.
"$python" - "$work" <<'EOF2'
import json, sys
work = sys.argv[1]
n = 16
L = f"sum(i = 1..{n}, v[i]^2)/2 - sum(i = 1..{n - 1}, (x[i+1] - x[i])^2)/2 - sum(i = 1..{n}, x[i]^4)/4"
case = {"name": "jacobians-beyond-the-cap", "system": {"name": "chain", "lagrangian": L, "coordinates": [{"x": [n]}],
                                                       "velocities": [{"v": [n]}]},
        "initial": {"q": [str(0.1 * i) for i in range(n)], "w": ["0"] * n}, "T": "1", "steps": [50000, 100000, 200000, 400000],
        "scalar": "float128", "discretization": {"kind": "midpoint"}, "claims": ["global-order", "symplecticity"]}
json.dump(case, open(f"{work}/jacobians-beyond-the-cap.json", "w"))
EOF2
run_capped jacobians-beyond-the-cap jacobians
expect_refused jacobians "the Jacobians beyond the cap"
grep -q "for symplecticity's Jacobians (a dense 2n x 2n matrix for each of the 400000 steps of the longest run)" "$work/jacobians.log" &&
  grep -q "without symplecticity the case needs about [0-9.e-]* [KMG]iB, and with it step counts up to [0-9]* fit" "$work/jacobians.log" ||
  { echo "the refusal does not name the claim and what would fit"; exit 1; }
echo "refused beyond the cap with its estimate (while read, and for the reference flow), completed within it; symplecticity's Jacobians named with what fits"
