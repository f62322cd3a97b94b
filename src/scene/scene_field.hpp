// A value of a scene file together with where it came from — file, line and key path — and typed
// reads that validate what they read. Every failure is a SceneError in the one format scene.hpp
// promises:  `<file>:<line>: <key.path>: <problem>; got '<value>' (expected ...)`.
// Internal to src/scene; the rest of mlshell sees only the validated Scene.
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mlshell::scene_reading {

/// The number a YAML plain scalar spells (`1e7`, `-0.3`, `+2`, `.nan`, `inf`), or nullopt if it
/// spells none. NaN and Inf are returned as such; callers reject them with a precise message.
std::optional<double> parse_real(std::string_view text);

/// The value as the user wrote it, on one line and shortened for messages (`[0.5, 0.5, 0]`).
std::string yaml_text(const YAML::Node& node);

class Field {
 public:
  /// The whole document of `file` (the file name as the user gave it, used in messages).
  static Field document(YAML::Node node, std::string file);

  const std::string& path() const { return path_; }
  int line() const { return line_; }
  /// `<file>:<line>: <key.path>` — every message about this value starts with it and ": ".
  std::string context() const;
  /// The value as written, for messages and Where::text.
  std::string text() const { return yaml_text(node_); }

  bool is_null() const { return node_.IsNull(); }
  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  bool is_scalar() const { return node_.IsScalar(); }

  /// Throws `<context>: <problem>; got '<value>'` plus ` (expected <expected>)` if one is given.
  [[noreturn]] void fail(std::string_view problem, std::string_view expected = {}) const;
  void check(bool ok, std::string_view problem, std::string_view expected = {}) const {
    if (!ok) fail(problem, expected);
  }

  // --- maps -----------------------------------------------------------------------------------
  /// Requires a map whose keys are all in `allowed` and appear once each; the message for an
  /// unknown key lists the allowed ones (and suggests the nearest if it looks like a typo).
  void expect_keys(std::initializer_list<std::string_view> allowed) const;
  /// The value of `key`, or nullopt if the map has no such key. Fails unless this is a map.
  std::optional<Field> find(std::string_view key) const;
  /// The value of `key`; a missing key fails, saying what the key should hold (`expected`).
  Field require(std::string_view key, std::string_view expected) const;
  /// `key` as if written with no value (`key:`), e.g. the parameters of a bare `- inertia`.
  Field without_value(std::string_view key) const;
  /// Key/value pairs in file order; a key given twice fails (keys must be plain scalars).
  std::vector<std::pair<std::string, Field>> entries() const;

  // --- sequences ------------------------------------------------------------------------------
  /// The items of a sequence; fails unless this is one.
  std::vector<Field> items() const;
  /// The items of a sequence of exactly `n` entries; `expected` describes it (`[x, y, z]`).
  std::vector<Field> items(std::size_t n, std::string_view expected) const;

  // --- scalars --------------------------------------------------------------------------------
  double number() const;           ///< a finite number (a quoted "1.0" is a string, not a number)
  double positive_number() const;  ///< a finite number > 0
  int integer_in(int lo, int hi) const;
  bool boolean() const;
  std::string string() const;  ///< a non-empty scalar
  /// A sequence of exactly N finite numbers; `expected` describes it, e.g. `[x, y, z]`.
  template <std::size_t N>
  std::array<double, N> numbers(std::string_view expected) const {
    const std::vector<Field> entries = items(N, expected);
    std::array<double, N> values{};
    for (std::size_t i = 0; i < N; ++i) values[i] = entries[i].number();
    return values;
  }

 private:
  Field(YAML::Node node, std::string file, std::string path, int line);
  Field child(const YAML::Node& node, std::string path, int line) const;
  std::string key_path(std::string_view key) const;
  void expect_map(std::string_view expected = "a map such as {key: value, ...}") const;
  double number(std::string_view expected) const;

  YAML::Node node_;
  std::string file_;
  std::string path_;
  int line_;
};

}  // namespace mlshell::scene_reading
