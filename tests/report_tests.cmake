# Reports (reports/), included from tests/CMakeLists.txt where this section stood: the default
# suite's report in one run, its schema and its page in headless Chromium, the console, --keep-going,
# --baseline and `vivv report` merging.
# Reports (reports/): the default suite in one run (exit 0 or 1: verdicts are
# the verification tests' business), its report.json and those of every
# verification and negative run validated against reports/schema.json, its
# report.html rendered in headless Chromium (DOM checked, screenshot saved in
# reports-suite/), and `vivv report` merging and refusing to merge.
find_package(Python3 COMPONENTS Interpreter)
set(VIVV_SUITE_REPORT ${CMAKE_BINARY_DIR}/reports-suite)
# Its console is terse: on this all-pass run (one xfail) at most 30 lines — the xfail's row, the
# count of passes left out, the summary, the report's paths — where every pass's detection limit
# once made 240 (--verbose lists them).
add_test(NAME reports/suite_run
         COMMAND sh -c "mkdir -p \"$1\"; \"$0\" run --out \"$1\" --jobs 2 --quiet > \"$1.console\"; code=$?;
                        cat \"$1.console\"; test $code -eq 0 && test $(wc -l < \"$1.console\") -le 30 &&
                        grep -q '^claims: [0-9]* pass, 0 fail, 0 inconclusive, 0 error' \"$1.console\""
                 $<TARGET_FILE:vivv> ${VIVV_SUITE_REPORT})
set_tests_properties(reports/suite_run PROPERTIES LABELS "schema;browser" FIXTURES_SETUP "vivv_reports;vivv_suite_report")
add_test(NAME reports/schema
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/validate_report_schema.py
                 ${CMAKE_SOURCE_DIR}/reports/schema.json --find ${CMAKE_BINARY_DIR}/verification
                 ${CMAKE_BINARY_DIR}/negative ${CMAKE_BINARY_DIR}/controls ${CMAKE_BINARY_DIR}/inconclusive ${CMAKE_BINARY_DIR}/expected_failures ${CMAKE_BINARY_DIR}/refine ${VIVV_SUITE_REPORT} ${CMAKE_BINARY_DIR}/reports-merged
                 ${CMAKE_BINARY_DIR}/scale-jobs ${CMAKE_BINARY_DIR}/scale-shards)
set_tests_properties(reports/schema PROPERTIES LABELS "schema" FIXTURES_REQUIRED "vivv_reports;vivv_merged_report"
                     SKIP_RETURN_CODE 77)
add_test(NAME reports/browser
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/check_report_in_browser.py chromium
                 ${VIVV_SUITE_REPORT} ${VIVV_SUITE_REPORT}/screenshot.png)
set_tests_properties(reports/browser PROPERTIES LABELS "browser" FIXTURES_REQUIRED vivv_suite_report
                     SKIP_RETURN_CODE 77 TIMEOUT 400)
# The browser test's badge check can fail: a badge too wide for its cell is found.
add_test(NAME reports/browser-badges-self-test
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/check_report_in_browser.py chromium --badge-self-test)
set_tests_properties(reports/browser-badges-self-test PROPERTIES LABELS "browser;negative" SKIP_RETURN_CODE 77)
# --keep-going: one good, one failing and one refused case; without it (the control) no report.
set(VIVV_KEEP_GOING ${CMAKE_BINARY_DIR}/keep-going)
add_test(NAME reports/keep-going
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/check_keep_going.py $<TARGET_FILE:vivv>
                 ${VIVV_KEEP_GOING} ${CMAKE_SOURCE_DIR}/cases/examples/anharmonic-chain-4d.json
                 ${CMAKE_CURRENT_SOURCE_DIR}/negative/sign-slip-alpha.json
                 ${CMAKE_CURRENT_SOURCE_DIR}/bad_cases/step-too-large.json)
set_tests_properties(reports/keep-going PROPERTIES LABELS "schema;browser" FIXTURES_SETUP vivv_keep_going_report)
# The failures-first section in a real browser, on a report with a failure and a refused case.
add_test(NAME reports/browser-failures-first
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/check_report_in_browser.py chromium
                 ${VIVV_KEEP_GOING}/kept ${VIVV_KEEP_GOING}/kept/screenshot.png)
set_tests_properties(reports/browser-failures-first PROPERTIES LABELS "browser"
                     FIXTURES_REQUIRED vivv_keep_going_report SKIP_RETURN_CODE 77 TIMEOUT 400)
# What the page says of undecided and failing claims, in a real browser: two inconclusive cases
# (energy-behaviour too short, global-order starting early) and a local-order failing from each of
# its four states; the run exits 1 (inconclusive), and the page must not dress an inconclusive
# claim as a pass, say "fails" of an undecided series, or repeat a failure's meaning per state.
set(VIVV_UNDECIDED_REPORT ${CMAKE_BINARY_DIR}/reports-undecided)
add_test(NAME reports/undecided_run
         COMMAND sh -c "\"$0\" run \"$1\" \"$2\" \"$3\" --out \"$4\" --quiet; test $? -eq 1"
                 $<TARGET_FILE:vivv> ${CMAKE_CURRENT_SOURCE_DIR}/inconclusive/energy-behaviour-toda-too-short.json
                 ${CMAKE_CURRENT_SOURCE_DIR}/inconclusive/global-order-early-start-elastic-pendulum-double.json
                 ${CMAKE_SOURCE_DIR}/cases/suite/argon-crystal-midpoint-stray-term.json ${VIVV_UNDECIDED_REPORT})
set_tests_properties(reports/undecided_run PROPERTIES LABELS "browser" FIXTURES_SETUP vivv_undecided_report)
add_test(NAME reports/browser-undecided
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/check_report_in_browser.py chromium
                 ${VIVV_UNDECIDED_REPORT} ${VIVV_UNDECIDED_REPORT}/screenshot.png)
set_tests_properties(reports/browser-undecided PROPERTIES LABELS "browser"
                     FIXTURES_REQUIRED vivv_undecided_report SKIP_RETURN_CODE 77 TIMEOUT 400)
# --baseline: a rerun of the same case is unchanged (exit 0); the same rule with a term of size h²
# added keeps every order and passes every claim, but its error constants grow by 1.5-2.4x: it
# regresses (exit 1). A baseline that is not a report is bad input before anything computes.
set(VIVV_BASELINE ${CMAKE_BINARY_DIR}/baseline)
add_test(NAME baseline/write
         COMMAND ${CMAKE_COMMAND} -DEXPECTED_EXIT=0
                 "-DCOMMAND=$<TARGET_FILE:vivv>;run;${CMAKE_CURRENT_SOURCE_DIR}/baseline/pendulum-midpoint.json;--out;${VIVV_BASELINE}/before;--quiet"
                 -P ${VIVV_EXPECT})
set_tests_properties(baseline/write PROPERTIES LABELS "baseline" FIXTURES_SETUP vivv_baseline)
add_test(NAME baseline/unchanged
         COMMAND ${CMAKE_COMMAND} -DEXPECTED_EXIT=0
                 "-DPATTERN=against the baseline: 0 regressed, 0 improved, 3 unchanged, 0 not compared"
                 "-DCOMMAND=$<TARGET_FILE:vivv>;run;${CMAKE_CURRENT_SOURCE_DIR}/baseline/pendulum-midpoint.json;--out;${VIVV_BASELINE}/again;--quiet;--baseline;${VIVV_BASELINE}/before/report.json"
                 -P ${VIVV_EXPECT})
add_test(NAME baseline/regressed
         COMMAND ${CMAKE_COMMAND} -DEXPECTED_EXIT=1
                 "-DPATTERN=global-order +regressed +[12]\\.[0-9]+ +2[^\n]*\n.*global-order: regressed against the baseline: [^\n]*error ×1\\.[4-5].*3 pass, 0 fail.*3 regressed"
                 "-DCOMMAND=$<TARGET_FILE:vivv>;run;${CMAKE_CURRENT_SOURCE_DIR}/baseline/pendulum-midpoint-larger-constant.json;--out;${VIVV_BASELINE}/larger;--quiet;--baseline;${VIVV_BASELINE}/before/report.json"
                 -P ${VIVV_EXPECT})
add_test(NAME baseline/within-a-wider-tolerance
         COMMAND ${CMAKE_COMMAND} -DEXPECTED_EXIT=0 "-DPATTERN=0 regressed"
                 "-DCOMMAND=$<TARGET_FILE:vivv>;run;${CMAKE_CURRENT_SOURCE_DIR}/baseline/pendulum-midpoint-larger-constant.json;--out;${VIVV_BASELINE}/wider;--quiet;--baseline;${VIVV_BASELINE}/before/report.json;--baseline-tolerance;2"
                 -P ${VIVV_EXPECT})
add_test(NAME baseline/not-a-report
         COMMAND ${CMAKE_COMMAND} -DEXPECTED_EXIT=2 "-DPATTERN=--baseline [^\n]*pendulum-midpoint\\.json: "
                 -DNO_FILE=${VIVV_BASELINE}/bad/report.json
                 "-DCOMMAND=$<TARGET_FILE:vivv>;run;${CMAKE_CURRENT_SOURCE_DIR}/baseline/pendulum-midpoint.json;--out;${VIVV_BASELINE}/bad;--quiet;--baseline;${CMAKE_CURRENT_SOURCE_DIR}/baseline/pendulum-midpoint.json"
                 -P ${VIVV_EXPECT})
set_tests_properties(baseline/unchanged baseline/regressed baseline/within-a-wider-tolerance PROPERTIES
                     LABELS "baseline" FIXTURES_REQUIRED vivv_baseline)
# A baseline goes through every check `vivv report` makes before any case runs: tests/baseline/edited
# holds the pendulum midpoint's report with a fit_points index past its errors, an error zeroed and
# an error made negative, each refused (exit 2, naming --baseline and the file, no report).
file(GLOB VIVV_EDITED_BASELINES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/baseline/edited/*.json)
foreach(baseline_file ${VIVV_EDITED_BASELINES})
  get_filename_component(baseline_name ${baseline_file} NAME_WE)
  file(STRINGS ${CMAKE_CURRENT_SOURCE_DIR}/baseline/edited/${baseline_name}.expect pattern LIMIT_COUNT 1)
  add_test(NAME baseline/edited/${baseline_name}
           COMMAND ${CMAKE_COMMAND} -DEXPECTED_EXIT=2
                   "-DPATTERN=--baseline [^\n]*${baseline_name}\\.json: [^\n]*${pattern}"
                   -DNO_FILE=${VIVV_BASELINE}/edited/${baseline_name}/report.json
                   "-DCOMMAND=$<TARGET_FILE:vivv>;run;${CMAKE_CURRENT_SOURCE_DIR}/baseline/pendulum-midpoint.json;--out;${VIVV_BASELINE}/edited/${baseline_name};--quiet;--baseline;${baseline_file}"
                   -P ${VIVV_EXPECT})
  set_tests_properties(baseline/edited/${baseline_name} PROPERTIES LABELS "baseline;hostile")
endforeach()
# A baseline that is one of the files the run replaces — the same path, a hard link to it, a
# symbolic link — is refused before anything computes, naming --baseline and --out, and is left
# as it was (once, the same command passed on its second run, judged against itself).
foreach(spelling same-path hard-link symbolic-link)
  add_test(NAME baseline/replaces-itself-${spelling}
           COMMAND sh -c "set -e; d=\"$1/replaces-$3\"; rm -rf \"$d\"; mkdir -p \"$d/out\" \"$d/elsewhere\";
                          cp \"$1/before/report.json\" \"$d/out/report.json\";
                          case $3 in same-path) b=\"$d/out/report.json\";;
                            hard-link) ln \"$d/out/report.json\" \"$d/elsewhere/base.json\"; b=\"$d/elsewhere/base.json\";;
                            symbolic-link) ln -s ../out/report.json \"$d/elsewhere/base.json\"; b=\"$d/elsewhere/base.json\";; esac;
                          code=0; \"$0\" run \"$2\" --baseline \"$b\" --out \"$d/out\" --quiet 2>\"$d/err\" || code=$?;
                          test $code -eq 2; grep -q -- '--baseline .* is .*report.json, which this run replaces (--out ' \"$d/err\";
                          cmp \"$1/before/report.json\" \"$d/out/report.json\"; test ! -e \"$d/out/report.html\""
                   $<TARGET_FILE:vivv> ${VIVV_BASELINE} ${CMAKE_CURRENT_SOURCE_DIR}/baseline/pendulum-midpoint.json ${spelling})
  set_tests_properties(baseline/replaces-itself-${spelling} PROPERTIES LABELS "baseline;hostile"
                       FIXTURES_REQUIRED vivv_baseline)
endforeach()
set_tests_properties(baseline/not-a-report PROPERTIES LABELS "baseline")
# Two cases from two runs merge into one report; the same case twice is bad input (exit 2, no files).
set(VIVV_MERGE_A ${CMAKE_BINARY_DIR}/verification/paper-midpoint/report.json)
set(VIVV_MERGE_B ${CMAKE_BINARY_DIR}/verification/paper-left-rectangle-a1/report.json)
add_test(NAME reports/merge
         COMMAND ${CMAKE_COMMAND} -DEXPECTED_EXIT=0 "-DPATTERN=claims: [0-9]+ pass, 0 fail"
                 "-DCOMMAND=$<TARGET_FILE:vivv>;report;${VIVV_MERGE_A};${VIVV_MERGE_B};--out;${CMAKE_BINARY_DIR}/reports-merged"
                 -P ${VIVV_EXPECT})
add_test(NAME reports/merge_duplicate
         COMMAND ${CMAKE_COMMAND} -DEXPECTED_EXIT=2 "-DPATTERN=paper-midpoint' is also in"
                 -DNO_FILE=${CMAKE_BINARY_DIR}/reports-duplicate/report.json
                 "-DCOMMAND=$<TARGET_FILE:vivv>;report;${VIVV_MERGE_A};${VIVV_MERGE_A};--out;${CMAKE_BINARY_DIR}/reports-duplicate"
                 -P ${VIVV_EXPECT})
set_tests_properties(reports/merge PROPERTIES LABELS "schema" FIXTURES_REQUIRED vivv_reports
                     FIXTURES_SETUP vivv_merged_report)
set_tests_properties(reports/merge_duplicate PROPERTIES LABELS "schema" FIXTURES_REQUIRED vivv_reports)
