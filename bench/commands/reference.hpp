// `vivv bench reference`: the reference-flow benchmark of issue 3.
#pragma once

#include <ostream>

namespace vivv {

// Pendulum q'' = −sin q, q(0) = 1, w(0) = 0 on [0, 10]: the Taylor flow at 256 bits to 1e-70 and
// in quad to 1e-32, and Boost.Odeint's bulirsch_stoer on the same MPFR scalar at 1e-40 against
// the Taylor flow at 1e-40, all timed in this run; and heyoka's two published pendulum problems,
// x'' = −9.8 sin x from (1, 0), to t = 0.1 at 257 bits with tolerance 1e-77 and to t = 1 in quad
// with tolerance 1e-34. Writes a few readable lines and, last, one JSON object (seconds_256,
// steps_256, order_256, fma_per_step_256, seconds_quad, odeint_seconds, odeint_ratio,
// heyoka_pendulum_256, heyoka_pendulum_quad, ...). Returns 0.
int run_reference_benchmark(std::ostream& out);

}  // namespace vivv
