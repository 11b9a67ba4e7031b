// A Lagrangian system that counts its Lagrangian's evaluations, in any scalar or jet: what
// the benchmarks divide a step's time by (bench/galerkin_benchmark.cpp, `vivv bench del`).
#pragma once

#include "core/lagrangian/lagrangian.hpp"

namespace vivv {

template <class System>
struct Counted : System {
  static inline long evaluations = 0;
  template <class P>
  auto lagrangian(const P& q, const P& w) const {
    ++evaluations;
    return System::lagrangian(q, w);
  }
};

}  // namespace vivv
