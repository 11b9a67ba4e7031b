// vivv-bench: the benchmarks `vivv bench NAME` runs, a program of its own beside the vivv tool
// so that building the tool for a run (bootstrap.sh run) does not compile them. Each prints a
// table and, last, one JSON object of ratios measured in one run.
//
//   vivv-bench reference|del|process|size
//   vivv-bench map-echo [--jacobian]   the echo program `process` talks to (protocol vivv-map/1)
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "bench/commands/del.hpp"
#include "bench/commands/process.hpp"
#include "bench/commands/reference.hpp"
#include "bench/commands/size.hpp"

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.size() == 1 && args[0] == "reference") return vivv::run_reference_benchmark(std::cout);
    if (args.size() == 1 && args[0] == "del") return vivv::run_del_benchmark(std::cout);
    if (args.size() == 1 && args[0] == "size") return vivv::run_size_benchmark(std::cout);
    if (args.size() == 2 && args[0] == "size") return vivv::run_size_benchmark(std::cout, args[1]);
    if (args.size() == 1 && args[0] == "process")
      return vivv::run_process_benchmark(std::cout,
                                         std::filesystem::read_symlink("/proc/self/exe").string());
    if (args.size() == 1 && args[0] == "map-echo") return vivv::run_map_echo();
    if (args.size() == 2 && args[0] == "map-echo" && args[1] == "--jacobian")
      return vivv::run_map_echo(true);
  } catch (const std::exception& error) {
    std::cerr << "vivv-bench: " << error.what() << "\n";
    return 2;
  }
  std::cerr << "usage: vivv-bench reference|del|process|size [chain_double|chain_mpfr|gravity_double] (or vivv bench "
               "NAME)\n";
  return 2;
}
