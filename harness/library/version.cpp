#include "harness/library/version.hpp"

#include <gmp.h>
#include <mpfr.h>

#include <Eigen/Core>
#include <boost/version.hpp>
#include <sstream>

namespace vivv {

std::string library_versions() {
  std::ostringstream out;  // (a chain of string + trips GCC 12's -Warray-bounds at -O2)
  out << "vivv " << VIVV_VERSION << "; Boost " << BOOST_LIB_VERSION << "; Eigen " << EIGEN_WORLD_VERSION << "."
      << EIGEN_MAJOR_VERSION << "." << EIGEN_MINOR_VERSION << "; MPFR " << mpfr_get_version() << "; GMP "
      << gmp_version;
  return out.str();
}

}  // namespace vivv
