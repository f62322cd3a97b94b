// The error of both OBJ readers (quad cages and triangle meshes): `file:line: what`.
#pragma once

#include <filesystem>
#include <string>

#include "mlshell/mesh_error.hpp"

namespace mlshell {

[[noreturn]] inline void obj_error(const std::filesystem::path& path, int line,
                                   const std::string& what) {
  throw MeshError(path.string() + ":" + std::to_string(line) + ": " + what);
}

}  // namespace mlshell
