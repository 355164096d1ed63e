#pragma once
// cpp-httplib for files that also see Eigen (the live view reaches it through calibration's
// analyzer): httplib includes <resolv.h>, whose `_res` macro renames a parameter in Eigen's
// matrix products, so Eigen has to come first. clang-format would sort <httplib.h> first.
// clang-format off
#include <Eigen/Core>
#include <httplib.h>
// clang-format on
