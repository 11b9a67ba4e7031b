// run_on_system: a case run on one system type (harness/run/run_system_impl.hpp holds the
// definition; CMake generates its one instantiation per scalar, for formula systems sized at run
// time, which every system runs as: harness/run/run_case.cpp).
#pragma once

#include <functional>
#include <string>

#include "cases/case_file.hpp"
#include "cases/systems.hpp"
#include "core/formulas/formula_system.hpp"
#include "harness/run/run_case.hpp"

namespace vivv {

// Runs every claim of `spec` on `system` into `result`; with `refine`, extends spec.steps.
template <LagrangianSystem System>
void run_on_system(const System& system, CaseSpec& spec, CaseResult& result, bool refine,
                   const std::function<void(const std::string&)>& progress);

// Scalar names CMake can write into a generated file.
using long_double = long double;

// Formula systems, sized at run time, for the generated instantiations.
template <class T>
using FormulaSystemAny = FormulaSystem<T, any_size>;

}  // namespace vivv
