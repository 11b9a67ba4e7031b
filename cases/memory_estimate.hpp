// What a case will hold in memory, estimated from its file before any work: the parts that grow
// with the problem, each named, so that a refusal (check_memory) and `vivv run --plan` say which
// part needs the memory and what the case could drop. docs/performance.md compares the estimate
// with the measured peak on chains, all-pairs gravity and Lennard-Jones clusters of 64 to 1024
// coordinates.
#pragma once

#include <string>
#include <vector>

#include "cases/case_file.hpp"

namespace vivv {

// Recording L: its tape, the edge-pushing record of its sparse second derivatives and the
// interpreter's values, per operation of L (1.4 KiB measured on an all-pairs sum of 200
// particles, rounded up): what reading a case may spend (cases/system_section.cpp) and what the
// recording holds before the work.
inline constexpr double recording_bytes_per_operation = 2048;

struct MemoryPart {
  std::string name;  // "reference flow", "symplecticity's Jacobians", ...
  double bytes = 0;
  std::string what;  // how it is counted: "3 x 41 250 tape nodes x (19 + 25) coefficients x 8 bytes"
};

struct MemoryEstimate {
  std::vector<MemoryPart> parts;  // the largest first
  double total() const;
  // The part named `name`, or nullptr.
  const MemoryPart* part(const std::string& name) const;
};

// The estimate for `spec` computed in `scalar` at `digits` (MPFR) — the scalar vivv's side
// computes in (a program that computes in double is judged in float128). Formula systems of
// three or more coordinates are estimated part by part; catalogue systems and formulas of one
// or two coordinates hold the process and little else.
MemoryEstimate estimate_memory(const CaseSpec& spec, const std::string& scalar, int digits);

// Whether `spec` in `scalar` is a program computing in double, whose case vivv computes in float128
// (harness/run/run_case.cpp), and the scalar vivv's side then computes in.
bool double_program(const CaseSpec& spec, const std::string& scalar);
std::string working_scalar(const CaseSpec& spec, const std::string& scalar);

// Whether symplecticity keeps a dense 2n x 2n Jacobian a step for `spec`: every case but a DEL map
// or a one-step map above symplecticity_dense_limit coordinates, which are judged by probes.
bool dense_symplecticity(const CaseSpec& spec);

// The bytes of one number in `scalar` at `digits` (MPFR: the number and its limbs).
double bytes_per_number(const std::string& scalar, int digits);

// A size in the unit that reads best: KiB, MiB or GiB, three digits.
std::string in_bytes(double bytes);

// The Taylor orders of the reference flow and of its cross-check for a case in `scalar` at
// `digits` (references/taylor_reference.hpp's rules, restated on the tolerance's logarithm).
struct ReferenceOrders {
  int flow = 0, check = 0;
};
ReferenceOrders reference_orders(const std::string& scalar, int digits, bool double_program);

}  // namespace vivv
