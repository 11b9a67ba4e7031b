// `vivv list`: the systems, discretizations, maps, claims and suite cases this tool knows.
#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cases/catalogue.hpp"
#include "core/qxq/discrete_lagrangian.hpp"
#include "harness/claims/registry.hpp"
#include "harness/command_line/command_line.hpp"
#include "harness/run/run_case.hpp"

namespace fs = std::filesystem;

namespace vivv::command_line {

int command_list() {
  std::cout << "systems:\n";
  for (const auto& system : system_catalogue()) {
    std::cout << "  " << system.name << " (n = " << system.dimension << ")";
    for (const auto& p : system.parameters) std::cout << " " << p.name << "=" << p.default_value;
    std::cout << "\n";
  }
  std::cout << "  or your own: {\"name\", \"lagrangian\": a formula, \"coordinates\", \"velocities\", \"params\"}"
               " (any n: names, or families such as {\"x\": [13, 3]} of up to 10^6 members; optional \"symmetry\": "
               "the generator xi(q), a formula per coordinate)\n";
  std::cout << "discretizations (Q×Q rules):\n";
  for (const auto& rule : rule_names()) {
    std::cout << "  " << rule;
    if (rule == "expression") std::cout << " (with \"L_d\": a formula in qb, qe, h, L(x, v), and your \"order\")";
    if (rule == "galerkin")
      std::cout << " (with \"degree\": 1..8, \"quadrature\": gauss | lobatto, \"nodes\": degree..16; "
                   "order min(2 degree, 2 nodes), Lobatto min(2 degree, 2 nodes - 2))";
    std::cout << "\n";
  }
  std::cout << "discretizations of TQ (\"formalism\": \"tq\", \"theta\": a fraction in [0, 1]):\n"
               "  psi: linear | taylor (with \"r\": 1..8) | exact\n"
               "  lagrangian: quadrature (with \"nodes\") | pullback (with a Q×Q \"qxq\") | exact (psi exact only)\n";
  std::cout << "one-step maps of Boost.Odeint (\"kind\": \"odeint\", \"stepper\"; a separable system "
               "1/2 w^T M w - V(q); claims";
  for (const auto& id : map_claim_ids()) std::cout << " " << id;
  std::cout << "):\n";
  for (const auto& stepper : odeint_steppers())
    std::cout << "  " << stepper.name << " (order " << stepper.order << (stepper.symplectic ? ", symplectic" : ", not symplectic")
              << ")\n";
  std::cout << "one-step maps of your own (\"kind\": \"map\", \"name\"): registered by a program that links vivv "
               "(vivv::register_map, docs/library.md); none in this tool\n";
  std::cout << "one-step maps in another program (\"kind\": \"process\", \"command\": [program, "
               "args...], "
               "\"order\"): protocol vivv-map/1 over its standard input and output "
               "(docs/process-protocol.md); "
               "needs vivv run --allow-process\n";
  std::cout << "claims:\n";
  for (const auto& claim : registered_claims())
    std::cout << "  " << claim.id << " [" << claim.source << "]: " << claim.prediction << "\n";
  std::cout << "cases (" << default_suite_directory() << "):\n";
  for (const auto& file : default_suite()) std::cout << "  " << fs::path(file).filename().string() << "\n";
  return exit_pass;
}

}  // namespace vivv::command_line
