// The sections of a case file that take more than a few fields (docs/case-files.md), each read
// by a function of its own: the discretization (cases/discretization_section.cpp) and the system
// given as a formula, its parameters and its initial state (cases/system_section.cpp).
// cases/case_file.cpp reads the rest and calls these.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "cases/case_file.hpp"
#include "cases/case_reader.hpp"

namespace vivv::case_reading {

// "discretization": a built-in or formula Q×Q rule, a TQ discretization, or a one-step map (odeint,
// registered, another program's); allow_tq false where only a Q×Q rule may stand (a TQ pullback's qxq).
DiscretizationSpec read_discretization(Reader reader, int dimension,
                                       const std::vector<std::pair<std::string, std::string>>& parameters,
                                       bool allow_tq = true, const std::string& time_name = "");
// "system": {"name", "lagrangian", "coordinates", "velocities", "params"}: a system as a formula.
void read_formula_system(Reader& system, CaseSpec& spec);
// "system.params": a decimal for each declared parameter (name, default), the default where the
// case gives none; a parameter that is not declared is an error (params.finish).
std::vector<std::pair<std::string, std::string>> read_parameters(
    Reader& system, const std::vector<std::pair<std::string, std::string>>& declared);
// The system registered under the name "system.name" gives, if one is.
const RegisteredSystem* registered_system(Reader& system);
// The initial state in the formula's domain (sqrt, log, powers, quotients) and the Lagrangian
// regular there, checked in long double before any work.
void check_initial_state(const CaseSpec& spec, const std::string& file);

// A formula system whose run would not fit in the memory this process may take, in `scalar` at
// `digits`: bad input naming the estimate (cases/memory_estimate.hpp, part by part), the part that
// needs the most and what the case could drop (field system.coordinates).
void check_memory(const CaseSpec& spec, const std::string& file, const std::string& scalar, int digits);

}  // namespace vivv::case_reading
