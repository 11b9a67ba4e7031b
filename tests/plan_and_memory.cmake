# `vivv run --plan` and the memory estimate it states (cases/memory_estimate.hpp), included from
# tests/CMakeLists.txt.
#
# The estimate against the measured peak: bench/memory_table.py --check runs a chain, all-pairs
# gravity and a Lennard-Jones cluster through a NumPy Verlet at about 64 and 256 coordinates (the cluster at 64 and 129) and
# fails unless each peak is within a factor 2 of the plan's estimate, the plan's reference orders are
# the run's and every verdict passes; the same with the estimate tripled must fail (the check's
# negative control). docs/performance.md holds the table up to 1024 coordinates.
foreach(system_sizes chain:64,256 gravity:64,256 lj:64,129)
  string(REPLACE ":" ";" system_sizes ${system_sizes})
  list(GET system_sizes 0 system)
  list(GET system_sizes 1 sizes)
  add_test(NAME scale/memory-estimate-${system}
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/bench/memory_table.py $<TARGET_FILE:vivv>
                   --systems ${system} --sizes ${sizes} --check)
  set_tests_properties(scale/memory-estimate-${system} PROPERTIES LABELS "scale;memory" TIMEOUT 600)
endforeach()
add_test(NAME scale/memory-estimate-tripled-fails
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/bench/memory_table.py $<TARGET_FILE:vivv>
                 --systems chain --sizes 256 --check --scale-estimate 3)
set_tests_properties(scale/memory-estimate-tripled-fails PROPERTIES LABELS "scale;memory;negative" WILL_FAIL TRUE)

# --plan reads and checks every case, prints each one's work and memory, computes nothing and
# writes no report; a bad case still refuses the run (exit 2) before any plan is printed.
add_test(NAME input/plan
         COMMAND ${CMAKE_COMMAND} -DEXPECTED_EXIT=0
                 "-DPATTERN=case 2 of 2: pleiades-midpoint .*symplecticity: the sweep.*memory: about [0-9.]+ [KM]iB"
                 -DFORBIDDEN=report:
                 -DNO_FILE=${CMAKE_BINARY_DIR}/plan-out/report.json
                 "-DCOMMAND=$<TARGET_FILE:vivv>;run;${CMAKE_SOURCE_DIR}/cases/suite/fpu-midpoint.json;${CMAKE_SOURCE_DIR}/cases/suite/pleiades-midpoint.json;--plan;--out;${CMAKE_BINARY_DIR}/plan-out"
                 -P ${VIVV_EXPECT})
add_test(NAME input/plan-refuses-a-bad-case
         COMMAND ${CMAKE_COMMAND} -DEXPECTED_EXIT=2 "-DPATTERN=no-such-case.json"
                 -DFORBIDDEN=memory:
                 "-DCOMMAND=$<TARGET_FILE:vivv>;run;${CMAKE_SOURCE_DIR}/cases/suite/fpu-midpoint.json;${CMAKE_BINARY_DIR}/no-such-case.json;--plan"
                 -P ${VIVV_EXPECT})
set_tests_properties(input/plan input/plan-refuses-a-bad-case PROPERTIES LABELS "input")
