// `vivv bench del`: what one DEL step costs beyond the Lagrangian evaluations it needs.
#pragma once

#include <ostream>

namespace vivv {

// One midpoint DEL step (q_{k+1} from q_{k−1}, q_k by Newton) of the pendulum (1 DOF) and the
// double pendulum (2 DOF), in double, float128 and MPFR at 256 bits, against one evaluation of
// L with its first and second derivatives (the jet every DEL evaluation of L is): the step's
// time over (its number of L evaluations × the time of one), all timed in this run. The
// target is a ratio of at most 3. Writes a table and, last, one JSON object (a list of rows:
// system, scalar, bits, evaluations, step_ns, evaluation_ns, ratio, within_target). Returns 0.
int run_del_benchmark(std::ostream& out);

}  // namespace vivv
