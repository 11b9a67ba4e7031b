// `vivv run --plan`: what each case of the run will compute and hold, from its file alone, before
// (and instead of) any work: the system's size, the reference flow's orders, the sweep, what each
// claim walks on top of it and the memory estimate part by part (cases/memory_estimate.hpp).
#include <algorithm>
#include <ostream>
#include <string>
#include <vector>

#include "cases/case_reader.hpp"
#include "cases/memory_estimate.hpp"
#include "core/numerics/scalar.hpp"
#include "harness/claims/map_local_order.hpp"
#include "harness/command_line/command_line.hpp"

namespace vivv::command_line {

namespace {

bool is_program(const CaseSpec& spec) {
  return spec.discretization.formalism == "map" && spec.discretization.kind == "process";
}

// What claim `id` computes beyond the reference and the shared sweep (docs/claims.md says how
// each is judged). A claim with no line of its own here walks the sweep or the initial state's
// steps as docs/claims.md describes.
std::string claim_work(const CaseSpec& spec, const std::string& id, double sweep_steps) {
  const std::string sweep = "the sweep (" + std::to_string(static_cast<long>(sweep_steps)) + " steps, shared)";
  const bool dense = dense_symplecticity(spec);
  if (id == "global-order")
    return sweep + ": its end states against the reference at T" +
           (spec.discretization.formalism == "qxq" ? "; one step at 2^-10 of the finest h" : "");
  if (id == "local-order")
    return "one step of the map at each h of the sweep, then halvings below the finest to the floor, from " +
           std::to_string(MapLocalOrderClaim::states) + " states along the reference orbit, each against the reference";
  if (id == "symplecticity") {
    if (dense)
      return sweep + ": a dense 2n x 2n Jacobian of every step (" + std::to_string(4 * spec.dimension * spec.dimension) +
             " numbers each, all kept) and J^T Omega J";
    if (is_program(spec))
      return sweep + ": 2 fresh and 2 carried probe pairs a step, 8 products J v" +
             (spec.discretization.process_precision == "double"
                  ? " by extrapolated central differences (32 program requests a step)"
                  : " by central differences of a second instance at 2D + 10 digits (16 requests a step, more at "
                    "every eighth)") +
             " (sent up to 8 ahead of their answers where it takes \"pipeline\"), or from the program's own Jacobian "
             "where it sends one";
    return sweep + ": the generating form over the blocks' nonzeros and 4 probe pairs a step (about one DEL step a step)";
  }
  if (id == "energy-behaviour") return sweep + ": the energy at every state";
  if (id == "energy-balance") return sweep + ": the energy at its first and last states";
  if (id == "discrete-noether") return sweep + ": the momentum map of the symmetry at every state";
  if (id == "modified-energy") return sweep + ": the modified energy at every state";
  return "as docs/claims.md describes for " + id;
}

}  // namespace

int print_plan(std::ostream& out, const std::vector<CaseSpec>& specs, const RunOptions& options) {
  out << "plan: " << specs.size() << " case" << (specs.size() == 1 ? "" : "s")
      << ", nothing computed (the work is counted from the case files; the memory is an estimate, "
         "docs/performance.md says how close it comes)\n";
  double largest = 0;
  for (std::size_t k = 0; k < specs.size(); ++k) {
    CaseSpec spec = specs[k];
    if (options.scalar) spec.scalar = *options.scalar;
    if (options.digits) spec.digits = *options.digits;
    const bool program_in_double = double_program(spec, spec.scalar);
    const std::string working = working_scalar(spec, spec.scalar);
    out << "case " << k + 1 << " of " << specs.size() << ": " << spec.name << " (" << spec.file << ")\n";
    out << "  system: " << spec.dimension << " coordinate" << (spec.dimension == 1 ? "" : "s");
    if (spec.formula && spec.formula->operations)
      out << ", L of " << spec.formula->operations << " operations"
          << (spec.formula->acceleration_operations
                  ? ", its acceleration " + std::to_string(spec.formula->acceleration_operations)
                  : std::string());
    out << "; vivv computes in " << working
        << (working == "mpfr" ? " at " + std::to_string(spec.digits) + " digits" : std::string())
        << (program_in_double ? " (the program in double)" : "") << "\n";
    if (spec.formula) {
      const ReferenceOrders orders = reference_orders(working, spec.digits, program_in_double);
      out << "  reference flow: Taylor series to T = " << three_digits(std::stod(spec.final_time)) << ", order " << orders.flow
          << ", and its cross-check, order " << orders.check << " (kept for the run's later cases on this system)\n";
    } else {
      out << "  reference flow: to T = " << three_digits(std::stod(spec.final_time)) << " (the catalogue's closed form where it has one)\n";
    }
    double sweep_steps = 0;
    std::string counts;
    for (int N : spec.steps) sweep_steps += N, counts += (counts.empty() ? "" : ", ") + std::to_string(N);
    out << "  sweep: N = " << counts << " over T (" << static_cast<long>(sweep_steps) << " steps"
        << (is_program(spec) ? ", each a step of the program: a batch a request where it takes \"steps\" (and "
                               "\"trajectory\", where a claim reads every state), else a request a step"
                             : "")
        << ")\n";
    for (const auto& id : spec.claims) out << "  " << id << ": " << claim_work(spec, id, sweep_steps) << "\n";
    const MemoryEstimate estimate = estimate_memory(spec, spec.scalar, spec.digits);
    largest = std::max(largest, estimate.total());
    out << "  memory: about " << in_bytes(estimate.total()) << "\n";
    for (const auto& part : estimate.parts)
      out << "    " << part.name << ": " << in_bytes(part.bytes) << " (" << part.what << ")\n";
  }
  out << "the largest case needs about " << in_bytes(largest)
      << (options.jobs > 1 ? "; with --jobs " + std::to_string(options.jobs) + " up to that many such cases at once"
                           : std::string())
      << "\n";
  return exit_pass;
}

}  // namespace vivv::command_line
