# cmake -DCOMMAND=a;b;c -DEXPECTED_EXIT=N [-DPATTERN=regex] [-DNO_FILE=path] -P expect_exit.cmake
# Fails unless COMMAND exits with EXPECTED_EXIT, its output matches PATTERN,
# and NO_FILE (a report that must not be written) does not exist.
if(DEFINED NO_FILE)
  file(REMOVE ${NO_FILE})
endif()
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT code EQUAL EXPECTED_EXIT)
  message(FATAL_ERROR "expected exit code ${EXPECTED_EXIT}, got ${code}")
endif()
if(DEFINED PATTERN AND NOT "${out}${err}" MATCHES "${PATTERN}")
  message(FATAL_ERROR "output does not match '${PATTERN}'")
endif()
if(DEFINED NO_FILE AND EXISTS ${NO_FILE})
  message(FATAL_ERROR "${NO_FILE} was written although the input was bad")
endif()
