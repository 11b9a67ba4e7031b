#include "harness/version.hpp"

#include <gmp.h>
#include <mpfr.h>

#include <Eigen/Core>
#include <boost/version.hpp>

namespace vivv {

std::string library_versions() {
  return std::string("vivv ") + VIVV_VERSION + "; Boost " + BOOST_LIB_VERSION + "; Eigen " +
         std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
         std::to_string(EIGEN_MINOR_VERSION) + "; MPFR " + mpfr_get_version() + "; GMP " +
         gmp_version;
}

}  // namespace vivv
