// `vivv bench size`: how the cost of a DEL step, a reference step and a symplecticity check grows
// with the number of coordinates (a chain, all-pairs gravity).
#pragma once

#include <ostream>
#include <string>

namespace vivv {

// Times, per size, one midpoint DEL step, one Taylor reference step and one symplecticity check
// (bench/commands/size.cpp says on which systems and sizes), and fits log-log slopes. Writes a
// table per system and, last, one JSON object (rows and slopes per system). Returns 0. `only`: one
// of its tables (chain_double, chain_mpfr, gravity_double); empty: all.
int run_size_benchmark(std::ostream& out, const std::string& only = "");

}  // namespace vivv
