// mlshell's version and commit (generated at build time, cmake/build_info.cmake) and PETSc's.
#include "mlshell/build_info.hpp"

#include <petscversion.h>

#include "mlshell_build_info.hpp"

namespace mlshell {

const BuildInfo& build_info() {
  static const BuildInfo info{MLSHELL_VERSION_STRING, MLSHELL_COMMIT_STRING,
                              std::to_string(PETSC_VERSION_MAJOR) + "." +
                                  std::to_string(PETSC_VERSION_MINOR) + "." +
                                  std::to_string(PETSC_VERSION_SUBMINOR)};
  return info;
}

std::string build_description() {
  const BuildInfo& b = build_info();
  return "mlshell " + b.version + " (commit " + b.commit + "), PETSc " + b.petsc;
}

}  // namespace mlshell
