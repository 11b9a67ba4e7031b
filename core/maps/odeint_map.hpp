// Boost.Odeint's fixed-step steppers as one-step maps under test (core/maps/one_step_map.hpp), on a
// separable system L = ½ wᵀ M w − V(q):
//   velocity_verlet                    (q, w): Störmer–Verlet, order 2, symplectic;
//   symplectic_rkn_sb3a_mclachlan      (q, p): McLachlan's 6-stage RKN, order 4, symplectic —
//                                      two of its coefficients are double literals;
//   symplectic_rkn_sb3a_m4_mclachlan   (q, p): McLachlan's 5-stage RKN, order 4, symplectic,
//                                      coefficients computed in the value type;
//   runge_kutta4                       (q, w): the classical Runge–Kutta method, order 4, not
//                                      symplectic.
// Each runs in the working precision T and, for the Jacobian, in first-order jets over (q, p).
// The definitions (core/maps/odeint_map_impl.hpp) are compiled once per scalar, for 1 and 2
// coordinates and for a size set at run time (any_size), in units harness/CMakeLists.txt generates.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/maps/one_step_map.hpp"

namespace vivv {

struct OdeintStepperInfo {
  std::string name;
  int order;
  bool symplectic;  // as its authors state it; the symplecticity claim checks it
};

// The steppers a case file may name ("kind": "odeint", "stepper": name).
inline const std::vector<OdeintStepperInfo>& odeint_steppers() {
  static const std::vector<OdeintStepperInfo> steppers = {{"velocity_verlet", 2, true},
                                                          {"symplectic_rkn_sb3a_mclachlan", 4, true},
                                                          {"symplectic_rkn_sb3a_m4_mclachlan", 4, true},
                                                          {"runge_kutta4", 4, false}};
  return steppers;
}

// The odeint stepper `name` (one of odeint_steppers()) stepping `system`.
template <class T, int n>
std::shared_ptr<const OneStepMap<T, n>> make_odeint_map(const std::string& name, const SeparableSystem<T, n>& system);

}  // namespace vivv
