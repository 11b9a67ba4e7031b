// Versions of vivv and of the libraries it computes with, for reports.
#pragma once

#include <string>

namespace vivv {

// "vivv X.Y.Z; Boost a.b; Eigen c.d.e; MPFR f.g.h; GMP i.j.k".
std::string library_versions();

}  // namespace vivv
