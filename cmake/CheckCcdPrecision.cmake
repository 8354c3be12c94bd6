# af::Real is double; libccd must have been built with the same precision, or every
# support point handed to it would be silently truncated.
include(CheckCXXSourceCompiles)
get_target_property(_af_ccd_includes ccd INTERFACE_INCLUDE_DIRECTORIES)
set(CMAKE_REQUIRED_INCLUDES ${_af_ccd_includes})
check_cxx_source_compiles("
#include <ccd/config.h>
#ifndef CCD_DOUBLE
#error libccd is not double precision
#endif
int main() { return 0; }" AF_CCD_IS_DOUBLE)
unset(CMAKE_REQUIRED_INCLUDES)
if(NOT AF_CCD_IS_DOUBLE)
    message(FATAL_ERROR "libccd was built without CCD_DOUBLE, but af::Real is double. "
                        "Install a double-precision libccd (Debian's libccd-dev is one).")
endif()
