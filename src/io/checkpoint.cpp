// Restart checkpoints. Layout (all little-endian):
//   "MLSHCKPT" | u32 version=1 | i32 step | f64 time | u64 fingerprint | u64 n |
//   f64 displacement[n] | f64 velocity[n] | u64 FNV-1a-64 of every preceding byte
// The reader checks each part and names the file and the problem, because a restart from a
// wrong or damaged file would otherwise silently continue a different simulation.
#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <stdexcept>
#include <system_error>

#include "io_util.hpp"

namespace mlshell {
namespace {

constexpr char kMagic[8] = {'M', 'L', 'S', 'H', 'C', 'K', 'P', 'T'};
constexpr std::uint32_t kVersion = 1;
// magic + version + step + time + fingerprint + n
constexpr std::uint64_t kHeaderBytes = 8 + 4 + 4 + 8 + 8 + 8;
constexpr std::uint64_t kChecksumBytes = 8;

std::uint64_t fnv1a64(const char* data, std::size_t n) {
  std::uint64_t h = 14695981039346656037ull;
  for (std::size_t i = 0; i < n; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 1099511628211ull;
  }
  return h;
}

// Explicit byte order (rather than memcpy of the native representation) keeps files portable;
// on the little-endian machines we run on the bytes are the same.
void put_u64(std::string& out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}
void put_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}
std::uint64_t get_u64(const char* p) {
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= std::uint64_t{static_cast<unsigned char>(p[i])} << (8 * i);
  return v;
}
std::uint32_t get_u32(const char* p) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= std::uint32_t{static_cast<unsigned char>(p[i])} << (8 * i);
  return v;
}

[[noreturn]] void bad(const std::filesystem::path& path, const std::string& problem) {
  throw OutputError("cannot read checkpoint '" + path.string() + "': " + problem);
}

}  // namespace

void write_checkpoint(const std::filesystem::path& path, const Checkpoint& c) {
  if (c.displacement.size() != c.velocity.size())
    throw std::invalid_argument("write_checkpoint: displacement has " +
                                std::to_string(c.displacement.size()) + " values, velocity " +
                                std::to_string(c.velocity.size()));
  const std::uint64_t n = c.displacement.size();
  std::string out;
  out.reserve(kHeaderBytes + 16 * n + kChecksumBytes);
  out.append(kMagic, sizeof kMagic);
  put_u32(out, kVersion);
  put_u32(out, static_cast<std::uint32_t>(static_cast<std::int32_t>(c.step)));
  put_u64(out, std::bit_cast<std::uint64_t>(c.time));
  put_u64(out, c.scene_fingerprint);
  put_u64(out, n);
  for (double x : c.displacement) put_u64(out, std::bit_cast<std::uint64_t>(x));
  for (double x : c.velocity) put_u64(out, std::bit_cast<std::uint64_t>(x));
  put_u64(out, fnv1a64(out.data(), out.size()));
  write_file_atomic(path, out);
}

Checkpoint read_checkpoint(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) bad(path, "no such file");
  if (!std::filesystem::is_regular_file(status)) bad(path, "not a regular file");
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) bad(path, "cannot get its size: " + ec.message());

  std::ifstream in(path, std::ios::binary);
  if (!in) bad(path, std::string("cannot open: ") + std::strerror(errno));
  // Read the header first: its n decides how much to read, and a foreign or huge file should
  // be rejected before allocating for it.
  std::string head(static_cast<std::size_t>(std::min<std::uint64_t>(size, kHeaderBytes)), '\0');
  if (!in.read(head.data(), static_cast<std::streamsize>(head.size())))
    bad(path, "read error in the header");
  if (head.size() < sizeof kMagic || std::memcmp(head.data(), kMagic, sizeof kMagic) != 0)
    bad(path, "not an mlshell checkpoint (bad magic)");
  if (head.size() < kHeaderBytes)
    bad(path, "truncated header (" + std::to_string(size) + " bytes)");
  const std::uint32_t version = get_u32(head.data() + 8);
  if (version != kVersion)
    bad(path, "unsupported format version " + std::to_string(version) + " (expected " +
                  std::to_string(kVersion) + ")");
  const std::uint64_t n = get_u64(head.data() + 32);
  // Compare without computing 16*n, which a corrupt n could overflow.
  const std::uint64_t body = size - kHeaderBytes;
  if (body < kChecksumBytes || (body - kChecksumBytes) / 16 < n)
    bad(path, "truncated: the header announces " + std::to_string(n) +
                  " values per array, more than the file's " + std::to_string(size) +
                  " bytes can hold");
  if (body - kChecksumBytes != 16 * n)
    bad(path, "size mismatch: " + std::to_string(size) + " bytes but the header announces " +
                  std::to_string(n) + " values per array (" +
                  std::to_string(kHeaderBytes + 16 * n + kChecksumBytes) + " bytes)");

  std::string data = head;
  data.resize(static_cast<std::size_t>(size));
  if (!in.read(data.data() + kHeaderBytes, static_cast<std::streamsize>(size - kHeaderBytes)))
    bad(path, "read error (file shrank while reading?)");
  const std::uint64_t stored = get_u64(data.data() + size - kChecksumBytes);
  if (stored != fnv1a64(data.data(), static_cast<std::size_t>(size - kChecksumBytes)))
    bad(path, "checksum mismatch (the file is corrupt)");

  Checkpoint c;
  c.step = static_cast<std::int32_t>(get_u32(data.data() + 12));
  c.time = std::bit_cast<double>(get_u64(data.data() + 16));
  c.scene_fingerprint = get_u64(data.data() + 24);
  c.displacement.resize(static_cast<std::size_t>(n));
  c.velocity.resize(static_cast<std::size_t>(n));
  const char* p = data.data() + kHeaderBytes;
  for (auto* array : {&c.displacement, &c.velocity}) {
    for (double& x : *array) {
      x = std::bit_cast<double>(get_u64(p));
      p += 8;
    }
  }
  return c;
}

}  // namespace mlshell
