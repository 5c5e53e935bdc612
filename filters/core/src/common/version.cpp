// SPDX-License-Identifier: BSD-3-Clause
#include "tc/common/version.h"

#include <CGAL/version.h>
#include <Eigen/Core>
#include <boost/version.hpp>
#include <tbb/version.h>

#define TC_STR2(x) #x
#define TC_STR(x) TC_STR2(x)

namespace tc
{
const char* version()
{
  return TRICHART_VERSION;
}

const char* buildInfo()
{
  return "Eigen " TC_STR(EIGEN_WORLD_VERSION) "." TC_STR(EIGEN_MAJOR_VERSION) "." TC_STR(
    EIGEN_MINOR_VERSION) "\nCGAL " TC_STR(CGAL_VERSION) "\nBoost " BOOST_LIB_VERSION
                                                        "\nTBB " TBB_VERSION_STRING "\n";
}
} // namespace tc
