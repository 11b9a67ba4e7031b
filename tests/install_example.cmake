# ctest install/user-integrator: installs the built vivv into a fresh prefix, configures and
# builds examples/user-integrator against that installed package alone (find_package(vivv)),
# and runs the example's own GoogleTest suite.
#   cmake -DBUILD=<vivv build dir> -DEXAMPLE=<example source> -DWORK=<scratch dir> -P install_example.cmake
file(REMOVE_RECURSE ${WORK})
set(prefix ${WORK}/prefix)
function(step name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "${name} failed (${code}):\n${out}\n${err}")
  endif()
  message(STATUS "${name}: ok")
  set(last_output "${out}" PARENT_SCOPE)
endfunction()
step("install vivv into ${prefix}" ${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix})
if(NOT EXISTS ${prefix}/lib/cmake/vivv/vivvConfig.cmake OR NOT EXISTS ${prefix}/include/vivv/vivv.hpp)
  message(FATAL_ERROR "the install has no vivvConfig.cmake or vivv/vivv.hpp")
endif()
# CMAKE_FIND_USE_PACKAGE_REGISTRY off and the prefix alone: the example sees only the install.
# The user's own warning flags (-Wall -Wextra): the example must compile without a warning, and
# vivv must add none of its own flags (-Wpedantic, say) to the user's compile lines.
step("configure the example" ${CMAKE_COMMAND} -S ${EXAMPLE} -B ${WORK}/build -G Ninja -DCMAKE_BUILD_TYPE=Release
     -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF "-DCMAKE_CXX_FLAGS=-O1 -Wall -Wextra"
     -DCMAKE_EXPORT_COMPILE_COMMANDS=ON)
step("build the example" ${CMAKE_COMMAND} --build ${WORK}/build)
if(last_output MATCHES "warning:")
  message(FATAL_ERROR "the example compiles with warnings:\n${last_output}")
endif()
file(READ ${WORK}/build/compile_commands.json commands)
if(commands MATCHES "-Wpedantic")
  message(FATAL_ERROR "vivv::vivv pushes its own warning flags onto the user's code:\n${commands}")
endif()
if(NOT commands MATCHES "-std=gnu\\+\\+2")
  message(FATAL_ERROR "vivv::vivv does not carry its language level (gnu++20) to the user's target:\n${commands}")
endif()
execute_process(COMMAND ${WORK}/build/user_integrator_test WORKING_DIRECTORY ${WORK} RESULT_VARIABLE code
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT code EQUAL 0)
  message(FATAL_ERROR "the example's tests failed (${code})")
endif()
