// Where symplecticity stops forming dense Jacobians: above this many coordinates a DEL map sized
// at run time is judged by random probes (core/structure/symplectic_probes.hpp), O(the step's
// nonzeros) a step, and a one-step map by probes of its products J·v
// (harness/claims/map_symplecticity_probes.hpp: a program's differences along v, a few requests
// each); at or below it, densely, entry by entry (harness/claims/symplecticity.hpp).
// The memory estimate (cases/system_section.cpp) counts dense Jacobians only where they are formed.
// The limit is a cost choice, not a verdict boundary: both checks give every test case the same
// verdict (mutate-rules' 16 -> 32 moves the outer solar system's 18 coordinates to the dense check
// and changes nothing), so no test case can sit near it.
#pragma once

namespace vivv {

inline constexpr int symplecticity_dense_limit = 16;
// The pairs of Gaussian vectors the probes carry through a run (the chance of a miss falls as
// 10^−pairs: core/structure/symplectic_probes.hpp).
inline constexpr int symplecticity_probe_pairs = 4;

}  // namespace vivv
