// `vivv bench process`: what protocol vivv-map/1 costs per step (harness/process/process_map.hpp).
#pragma once

#include <ostream>
#include <string>

namespace vivv {

// One step of a process map whose program only echoes (q, p) back — vivv itself as
// `vivv map-echo`, so the figure is the protocol's: the momenta, the decimal strings and JSON on
// vivv's side, two trips through the pipes, the program's parse and reply, the inverse Legendre
// transform — against one midpoint DEL step of vivv's own at the same precision, both timed in
// this run, for the pendulum in double (17 digits) and MPFR at 40 digits. The target is at most
// 50 µs per step. Writes a table and, last, one JSON object (rows: scalar, digits,
// process_step_us, del_step_us, ratio, within_target). Returns 0.
int run_process_benchmark(std::ostream& out, const std::string& vivv_path);

// `vivv map-echo [--jacobian]`: the echo program of the benchmark (answers each request with its
// own q and p, padded with zeros to the digits its greeting asked for; with --jacobian it takes
// up the extension "jacobian" and sends the identity with each answer).
int run_map_echo(bool send_jacobian = false);

// Besides: one Jacobian for symplecticity from the echo sending its own, against one by central
// differences of its steps (a second instance at 2D + 10 digits, or the same instance for a
// double program), pendulum and Kepler in double and MPFR at 40 digits: rows "jacobians" with
// own_jacobian_us, differences_us and speedup.

}  // namespace vivv
