#include "tirpol/report/provenance.h"

namespace tirpol::report {

// Set per file by report/CMakeLists.txt at configure time, so a new commit recompiles only this.
std::string build_commit() { return TIRPOL_BUILD_COMMIT; }

}  // namespace tirpol::report
