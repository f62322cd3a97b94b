// What was built: mlshell's version, the source commit and the PETSc it was compiled against,
// for `mlshell --version` and summary.json (a result names the code that produced it).
#pragma once

#include <string>

namespace mlshell {

struct BuildInfo {
  std::string version;  ///< mlshell's version (CMake's project version)
  /// `git describe` of the source tree at build time: the commit, with "-modified" when tracked
  /// files differed from it; "unknown" outside a git checkout.
  std::string commit;
  std::string petsc;  ///< the PETSc version compiled against, e.g. "3.18.5"
};

const BuildInfo& build_info();

/// One line: "mlshell 0.1.0 (commit 0123456789ab), PETSc 3.18.5".
std::string build_description();

}  // namespace mlshell
