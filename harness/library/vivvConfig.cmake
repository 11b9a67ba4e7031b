# find_package(vivv): the targets of an installed vivv (vivv::vivv) and what they need, all from
# Debian's packages (README, "The two commands").
include(CMakeFindDependencyMacro)
find_dependency(Eigen3 3.3 NO_MODULE)
find_dependency(Boost 1.74)
find_dependency(nlohmann_json 3.10)
include(${CMAKE_CURRENT_LIST_DIR}/vivvTargets.cmake)
