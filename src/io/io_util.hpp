// Helpers shared by the result-file writers (src/io/*.cpp); not part of the public interface.
#pragma once

#include <filesystem>
#include <string>

#include "mlshell/output_files.hpp"

namespace mlshell::io_detail {

/// `<path>.tmp.<pid>`: a name in the same folder (so the final rename never crosses file
/// systems) that two processes writing the same file cannot share.
std::filesystem::path temporary_path_for(const std::filesystem::path& path);

/// Creates the folder that will hold `path` (if it has one); throws OutputError naming `path`.
void create_parent_folder(const std::filesystem::path& path);

/// Renames the complete temporary `tmp` over `path`; on failure removes `tmp` and throws.
void commit_temporary(const std::filesystem::path& tmp, const std::filesystem::path& path);

/// The shortest text that reads back as the same double, bit-exactly (std::to_chars).
std::string format_double(double x);

/// Checks the shape invariants of a SurfaceSample (3 coordinates per point, 4 in-range indices
/// per quad, displacement empty or one vector per point); throws std::invalid_argument.
void check_surface(const SurfaceSample& surface, const char* who);

}  // namespace mlshell::io_detail
