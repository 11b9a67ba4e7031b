# The verdict pin's negative control (tests/expect_exit.cmake, VERDICTS): with one claim of a real
# case's NAME.verdicts flipped, with one line missing and with one claim too many, the check must
# fail naming that claim; with the file as it is, it must pass.
#   cmake -DVIVV=path -DCASE=NAME.json -DWORK=dir -DEXPECT=expect_exit.cmake -P check_verdicts_self_test.cmake
cmake_minimum_required(VERSION 3.20)
get_filename_component(directory ${CASE} DIRECTORY)
get_filename_component(case_name ${CASE} NAME_WE)
file(STRINGS ${directory}/${case_name}.verdicts pinned REGEX "^[^#]")
list(GET pinned 0 first)
string(REGEX REPLACE " [^ ]+$" "" first_claim "${first}")
string(REGEX REPLACE "^.* " "" first_verdict "${first}")
set(flipped_verdict inconclusive)
if(first_verdict STREQUAL "inconclusive")
  set(flipped_verdict fail)
endif()
list(SUBLIST pinned 1 -1 rest)
string(JOIN "\n" rest_text ${rest})
file(MAKE_DIRECTORY ${WORK})
file(WRITE ${WORK}/flipped.verdicts "${first_claim} ${flipped_verdict}\n${rest_text}\n")
file(WRITE ${WORK}/missing.verdicts "${rest_text}\n")
string(JOIN "\n" all_text ${pinned})
file(WRITE ${WORK}/extra.verdicts "${all_text}\n${case_name} symplecticity-of-nothing pass\n")
file(COPY_FILE ${directory}/${case_name}.verdicts ${WORK}/as-is.verdicts)

# VARIANT must fail (or, as-is, pass) with output matching PATTERN.
function(check variant should_fail pattern)
  execute_process(COMMAND ${CMAKE_COMMAND} -DEXPECTED_EXIT=1 -DVERDICTS=${WORK}/${variant}.verdicts
                          -DREPORT=${WORK}/out/report.json
                          "-DCOMMAND=${VIVV};run;${CASE};--out;${WORK}/out;--quiet" -P ${EXPECT}
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(should_fail AND code EQUAL 0)
    message(FATAL_ERROR "${variant}: the verdict check passed a report that ${variant}.verdicts contradicts")
  endif()
  if(NOT should_fail AND NOT code EQUAL 0)
    message(FATAL_ERROR "${variant}: the verdict check failed the verdicts as pinned:\n${out}${err}")
  endif()
  if(NOT "${out}${err}" MATCHES "${pattern}")
    message(FATAL_ERROR "${variant}: the check's output does not match '${pattern}':\n${out}${err}")
  endif()
  message("${variant}: as expected")
endfunction()

check(flipped TRUE "${first_claim}: [^ ]*flipped.verdicts pins ${flipped_verdict}, the report says ${first_verdict}")
check(missing TRUE "${first}: a claim [^ ]*missing.verdicts does not pin")
check(extra TRUE "symplecticity-of-nothing: [^ ]*extra.verdicts pins pass, the report says none")
check(as-is FALSE "claims: ")
