// The memory a case will hold, part by part (cases/memory_estimate.hpp). The model and its
// constants were measured (bench/memory_table.py, docs/performance.md): the process itself; while
// the system is recorded, L's tape and the edge-pushing record of its sparse second derivatives;
// while it computes, the Taylor reference's coefficients, the sweep's trajectories and what the
// claims keep. The peak is the process plus the larger of the recording and the computing: what
// the recording frees the computing takes again.
#include "cases/memory_estimate.hpp"

#include <algorithm>
#include <cmath>

#include "cases/lexical_forms.hpp"
#include "core/numerics/scalar.hpp"
#include "core/structure/dense_limit.hpp"

namespace vivv {

namespace {

// The process before any case: the executable, its libraries and the case files read (measured:
// 9.5–11 MiB resident for a case of one or two coordinates).
constexpr double process_bytes = 10.0 * 1024 * 1024;
// A Taylor expansion holds three arrays (coefficients, weighted operands, weighted self) of
// (order + 1) numbers for every node of the acceleration's tape (core/autodiff/taylor_expansion.hpp).
constexpr double expansion_arrays = 3;
// The tapes the run keeps, per node of the acceleration's tape and of L's: the nodes, their
// constants and the derivative tape's values (measured, rounded up).
constexpr double tape_bytes_per_node = 160;
// The sweep: numbers of n kept a step of every run (the DEL's positions and momenta, the map's
// states), and those the symplecticity probes' walk adds (measured on the chain at n = 1024).
constexpr double sweep_vectors_per_step = 2;
constexpr double probe_vectors_per_step = 6;

std::string gib(double bytes) { return three_digits(bytes / (1024.0 * 1024 * 1024)) + " GiB"; }

// Whether a discretization still differentiates L in dense jets at run-time sizes: Galerkin's
// extremal and the TQ formalism. The other Q × Q rules read L's sparse derivatives
// (core/qxq/sparse_legendre.hpp), and a map's Legendre transform reads L's sparse derivatives too.
bool dense_second_derivatives(const DiscretizationSpec& d) { return d.formalism == "tq" || d.kind == "galerkin"; }

bool lists(const CaseSpec& spec, const std::string& claim) {
  return std::find(spec.claims.begin(), spec.claims.end(), claim) != spec.claims.end();
}

int taylor_order_for_log(double minus_log_tolerance) {
  return std::max(2, static_cast<int>(std::ceil(minus_log_tolerance / 2 + 1)));
}

}  // namespace

bool double_program(const CaseSpec& spec, const std::string& scalar) {
  return scalar == "double" && spec.discretization.formalism == "map" && spec.discretization.kind == "process" &&
         spec.discretization.process_precision == "double";
}

std::string working_scalar(const CaseSpec& spec, const std::string& scalar) {
  return double_program(spec, scalar) ? "float128" : scalar;
}

bool dense_symplecticity(const CaseSpec& spec) {
  return (spec.discretization.formalism != "qxq" && spec.discretization.formalism != "map") ||
         spec.dimension <= symplecticity_dense_limit;
}

double MemoryEstimate::total() const {
  double sum = 0;
  for (const auto& part : parts) sum += part.bytes;
  return sum;
}

const MemoryPart* MemoryEstimate::part(const std::string& name) const {
  for (const auto& part : parts)
    if (part.name == name) return &part;
  return nullptr;
}

std::string in_bytes(double bytes) {
  if (bytes < 1024.0 * 1024) return three_digits(bytes / 1024) + " KiB";
  if (bytes < 1024.0 * 1024 * 1024) return three_digits(bytes / (1024.0 * 1024)) + " MiB";
  return gib(bytes);
}

double bytes_per_number(const std::string& scalar, int digits) {
  if (scalar == "double") return sizeof(double);
  if (scalar == "long double") return sizeof(long double);
  if (scalar == "float128") return sizeof(quad);
  const double limbs = std::ceil(digits * 3.3219280948873623 / 64) + 1;
  return static_cast<double>(sizeof(mpfr_real)) + 8 * limbs;
}

// references/taylor_reference.hpp: the tolerance (harness/context/case_context.hpp,
// reference_tolerance_for) raised to the floor 10⁴ ε; the step tolerance a thousandth of it; the
// check's step tolerance 10⁻⁴ of that but at least 10 ε, else the flow's order + 6.
ReferenceOrders reference_orders(const std::string& scalar, int digits, bool double_program) {
  const double ln10 = std::log(10.0), ln2 = std::log(2.0);
  // −ln ε of the scalar: 2^(1 − bits).
  const double bits = scalar == "double"        ? 53
                      : scalar == "long double" ? 64
                      : scalar == "float128"    ? 113
                                                : std::ceil(digits * 3.3219280948873623);
  const double minus_ln_epsilon = (bits - 1) * ln2;
  double minus_ln_tolerance = minus_ln_epsilon - 3 * ln10;  // 1000 ε
  if (double_program) minus_ln_tolerance = std::min(52 * ln2 + 6 * ln10, minus_ln_epsilon - 3 * ln10);
  else if (scalar == "mpfr") minus_ln_tolerance = (digits - 10) * ln10;
  minus_ln_tolerance = std::min(minus_ln_tolerance, minus_ln_epsilon - 4 * ln10);  // the floor 10⁴ ε
  const double minus_ln_step = minus_ln_tolerance + 3 * ln10;
  ReferenceOrders orders;
  orders.flow = taylor_order_for_log(minus_ln_step);
  const double minus_ln_check = std::min(minus_ln_step + 4 * ln10, minus_ln_epsilon - ln10);
  orders.check = minus_ln_check > minus_ln_step ? taylor_order_for_log(minus_ln_check) : orders.flow + 6;
  return orders;
}

MemoryEstimate estimate_memory(const CaseSpec& spec, const std::string& scalar, int digits) {
  MemoryEstimate estimate;
  estimate.parts.push_back({"the process", process_bytes, "the executable, its libraries and the case files"});
  if (!spec.formula || spec.dimension <= 2) return estimate;
  const double n = spec.dimension;
  const double operations = static_cast<double>(spec.formula->operations);
  const double acceleration = static_cast<double>(spec.formula->acceleration_operations);
  const bool program_in_double = double_program(spec, scalar);
  const std::string working = working_scalar(spec, scalar);
  const double number = bytes_per_number(working, digits);
  const std::string per_number = " x " + three_digits(number) + " bytes";

  // While L is recorded (once when the case is read, again when it runs); freed before the work.
  const double recording = operations * recording_bytes_per_operation;
  // While the case computes.
  std::vector<MemoryPart> held;
  held.push_back({"L's tapes", (operations + acceleration) * tape_bytes_per_node,
                  std::to_string(static_cast<long>(operations)) + " operations of L and " +
                      std::to_string(static_cast<long>(acceleration)) + " of its acceleration, " +
                      three_digits(tape_bytes_per_node) + " bytes each"});
  const ReferenceOrders orders = reference_orders(working, digits, program_in_double);
  held.push_back({"reference flow",
                  expansion_arrays * acceleration * (orders.flow + orders.check + 2) * number,
                  "3 arrays x " + std::to_string(static_cast<long>(acceleration)) +
                      " acceleration nodes x (" + std::to_string(orders.flow + 1) + " + " +
                      std::to_string(orders.check + 1) + " coefficients: the flow's order " +
                      std::to_string(orders.flow) + ", its cross-check's " + std::to_string(orders.check) + ")" +
                      per_number});
  double sweep_steps = 0;
  for (int N : spec.steps) sweep_steps += N + 1;
  const bool symplecticity = lists(spec, "symplecticity");
  const bool dense_jacobians = dense_symplecticity(spec);
  const double vectors = sweep_vectors_per_step + (symplecticity && !dense_jacobians ? probe_vectors_per_step : 0);
  held.push_back({"sweep", sweep_steps * vectors * n * number,
                  std::to_string(static_cast<long>(sweep_steps)) + " states of the sweep x " + three_digits(vectors) + " vectors of " +
                      std::to_string(spec.dimension) + per_number});
  const bool dense = dense_second_derivatives(spec.discretization) ||
                     (spec.past_discretization && dense_second_derivatives(*spec.past_discretization)) ||
                     (spec.compare_discretization && dense_second_derivatives(*spec.compare_discretization));
  if (dense)
    held.push_back({"dense second derivatives", operations * (1 + 2 * n + 4 * n * n) * number,
                    "each of L's " + std::to_string(static_cast<long>(operations)) +
                        " operations a jet of 1 + 2n + (2n)^2 numbers (Galerkin and TQ discretizations)"});
  if (symplecticity && dense_jacobians && !spec.steps.empty())
    held.push_back({"symplecticity's Jacobians", static_cast<double>(spec.steps.back()) * 4 * n * n * number,
                    "a dense 2n x 2n matrix for each of the " + std::to_string(spec.steps.back()) +
                        " steps of the longest run"});
  double computing = 0;
  for (const auto& part : held) computing += part.bytes;
  if (recording > computing) {
    estimate.parts.push_back({"recording L", recording,
                              std::to_string(static_cast<long>(operations)) + " operations x " +
                                  three_digits(recording_bytes_per_operation) +
                                  " bytes (its tape and the record of its sparse second derivatives); the "
                                  "computing after it takes less: " + in_bytes(computing)});
  } else {
    estimate.parts.insert(estimate.parts.end(), held.begin(), held.end());
  }
  std::stable_sort(estimate.parts.begin() + 1, estimate.parts.end(),
                   [](const MemoryPart& a, const MemoryPart& b) { return a.bytes > b.bytes; });
  return estimate;
}

}  // namespace vivv
