// Atomic whole-file writes: the content goes to a temporary in the target folder which is
// renamed over the target only once it is completely written and closed. POSIX rename within a
// folder is atomic, so a reader (ParaView, a plotting script, a restarting run) sees either the
// old complete file or the new complete file, never a torn one.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "io_util.hpp"

namespace mlshell {
namespace io_detail {

std::filesystem::path temporary_path_for(const std::filesystem::path& path) {
  std::filesystem::path tmp = path;
  tmp += ".tmp." + std::to_string(static_cast<long long>(::getpid()));
  return tmp;
}

void create_parent_folder(const std::filesystem::path& path) {
  const std::filesystem::path parent = path.parent_path();
  if (parent.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(parent, ec);
  // Also check the result: older standard libraries report no error when `parent` already
  // exists as a regular file, and the later open would fail with a less helpful message.
  if (ec || !std::filesystem::is_directory(parent)) {
    const std::string why = ec ? ec.message() : std::string("exists and is not a folder");
    throw OutputError("cannot write '" + path.string() + "': cannot create folder '" +
                      parent.string() + "': " + why);
  }
}

void commit_temporary(const std::filesystem::path& tmp, const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw OutputError("cannot write '" + path.string() + "': cannot rename temporary '" +
                      tmp.string() + "' over it: " + ec.message());
  }
}

}  // namespace io_detail

void create_output_folder(MPI_Comm comm, const std::filesystem::path& dir) {
  io_detail::on_rank_zero(comm, [&] {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir)) {
      const std::string why = ec ? ec.message() : std::string("exists and is not a folder");
      throw OutputError("cannot create output folder '" + dir.string() + "': " + why);
    }
    std::filesystem::remove(dir / "summary.json", ec);
    if (ec)
      throw OutputError("cannot remove the earlier run's '" + (dir / "summary.json").string() +
                        "': " + ec.message());
  });
}

void write_file_atomic(const std::filesystem::path& path, const std::string& content) {
  io_detail::create_parent_folder(path);
  const std::filesystem::path tmp = io_detail::temporary_path_for(path);

  // Plain POSIX I/O rather than iostreams: write() and close() report the exact errno (ENOSPC,
  // EDQUOT, EIO), which a stream's failbit does not.
  auto fail = [&](const std::string& what, int err) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw OutputError("cannot write '" + path.string() + "': " + what + ": " + std::strerror(err));
  };
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) {
    const int err = errno;
    // Nothing was created, but a stale temporary of the same name is not ours to delete.
    throw OutputError("cannot write '" + path.string() + "': cannot create temporary '" +
                      tmp.string() + "': " + std::strerror(err));
  }
  const char* data = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      fail("write to temporary '" + tmp.string() + "' failed", err);
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  // No fsync: atomicity against other processes only needs the rename; paying a disk flush for
  // every CSV row or XDMF rewrite would slow long runs down for crash-durability we don't need.
  // close() is checked because network file systems report deferred write errors there.
  if (::close(fd) != 0) fail("closing temporary '" + tmp.string() + "' failed", errno);
  io_detail::commit_temporary(tmp, path);
}

}  // namespace mlshell
