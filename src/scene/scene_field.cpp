#include "scene_field.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "mlshell/scene.hpp"

namespace mlshell::scene_reading {
namespace {

constexpr std::size_t kMaxShownChars = 72;

std::string lowercase(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

std::string join(std::initializer_list<std::string_view> words, std::string_view separator) {
  std::string out;
  for (std::string_view w : words) {
    if (!out.empty()) out += separator;
    out += w;
  }
  return out;
}

/// Edit distance, to suggest `thickness` for `thicknes`.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitute = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitute});
    }
  }
  return row[b.size()];
}

std::optional<std::string_view> nearest_key(std::string_view key,
                                            std::initializer_list<std::string_view> allowed) {
  std::optional<std::string_view> best;
  std::size_t best_distance = 3;  // more than two edits is not a typo
  for (std::string_view candidate : allowed) {
    const std::size_t d = edit_distance(lowercase(key), candidate);
    if (d < best_distance) {
      best = candidate;
      best_distance = d;
    }
  }
  return best;
}

/// yaml-cpp tags quoted scalars "!" and plain ones "?": `"1.0"` is a string to YAML, and a scene
/// that quotes a number most likely meant something else, so numbers and booleans must be plain.
bool is_quoted(const YAML::Node& node) { return node.Tag() == "!"; }

}  // namespace

std::optional<double> parse_real(std::string_view text) {
  std::string_view body = text;
  bool negative = false;
  if (!body.empty() && (body.front() == '+' || body.front() == '-')) {
    negative = body.front() == '-';
    body.remove_prefix(1);
  }
  // YAML spells the special values .inf/.nan; accept C's spellings too, so that they are
  // recognised (and then rejected as non-finite) instead of reported as "not a number".
  const std::string special = lowercase(body);
  if (special == ".inf" || special == "inf" || special == "infinity") {
    return negative ? -std::numeric_limits<double>::infinity()
                    : std::numeric_limits<double>::infinity();
  }
  if (special == ".nan" || special == "nan") return std::numeric_limits<double>::quiet_NaN();
  if (body.empty() ||
      !(std::isdigit(static_cast<unsigned char>(body.front())) || body.front() == '.'))
    return std::nullopt;

  double value = 0.0;
  const auto [end, error] = std::from_chars(body.data(), body.data() + body.size(), value);
  if (end != body.data() + body.size()) return std::nullopt;
  if (error == std::errc::result_out_of_range) {
    // 1e999 overflows to inf (rejected later as non-finite); 1e-999 underflows towards 0.
    value = std::strtod(std::string(body).c_str(), nullptr);
  } else if (error != std::errc{}) {
    return std::nullopt;
  }
  return negative ? -value : value;
}

std::string yaml_text(const YAML::Node& node) {
  std::string text;
  if (!node.IsDefined() || node.IsNull()) return text;
  if (node.IsScalar()) {
    text = node.Scalar();
  } else {
    YAML::Emitter emitter;
    emitter.SetMapFormat(YAML::Flow);
    emitter.SetSeqFormat(YAML::Flow);
    emitter << node;
    text = emitter.c_str();
  }
  std::replace(text.begin(), text.end(), '\n', ' ');
  if (text.size() > kMaxShownChars) text = text.substr(0, kMaxShownChars - 3) + "...";
  return text;
}

Field Field::document(YAML::Node node, std::string file) {
  return Field(std::move(node), std::move(file), "", 1);
}

Field::Field(YAML::Node node, std::string file, std::string path, int line)
    : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)), line_(line) {}

Field Field::child(const YAML::Node& node, std::string path, int line) const {
  return Field(node, file_, std::move(path), line);
}

std::string Field::context() const {
  std::string out = file_ + ":" + std::to_string(line_);
  if (!path_.empty()) out += ": " + path_;
  return out;
}

void Field::fail(std::string_view problem, std::string_view expected) const {
  std::string message = context() + ": " + std::string(problem) + "; got '" + text() + "'";
  if (!expected.empty()) message += " (expected " + std::string(expected) + ")";
  throw SceneError(message);
}

// --- maps -------------------------------------------------------------------------------------

std::string Field::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void Field::expect_map(std::string_view expected) const {
  if (!is_map())
    fail(is_null() ? "has no value" : "must be a map of `key: value` entries", expected);
}

void Field::expect_keys(std::initializer_list<std::string_view> allowed) const {
  expect_map("a map with keys " + join(allowed, ", "));
  for (const auto& [key, value] : entries()) {
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;

    std::string message =
        value.context() + ": unknown key; got '" + key + "' (allowed keys: " + join(allowed, ", ");
    if (const auto suggestion = nearest_key(key, allowed)) {
      message += "; did you mean '" + std::string(*suggestion) + "'?";
    }
    message += ")";
    if (key.find(')') != std::string::npos && key.find('(') == std::string::npos) {
      // `{where: point(0.5, 0.5)}`: in a flow map the comma ends the value and `0.5)` becomes a
      // key.
      message +=
          "; a comma inside (...) splits a value in a {...} map: quote the value, e.g. "
          "\"point(0.5, 0.5)\"";
    }
    throw SceneError(message);
  }
}

std::optional<Field> Field::find(std::string_view key) const {
  expect_map();
  for (const auto& entry : node_) {
    if (entry.first.IsScalar() && entry.first.Scalar() == key) {
      return child(entry.second, key_path(key), entry.first.Mark().line + 1);
    }
  }
  return std::nullopt;
}

Field Field::require(std::string_view key, std::string_view expected) const {
  if (std::optional<Field> value = find(key)) return *value;
  // Reported at the map that lacks the key, showing what the map does hold.
  child(node_, key_path(key), line_).fail("required key is missing", expected);
}

Field Field::without_value(std::string_view key) const {
  return child(YAML::Node(YAML::NodeType::Null), key_path(key), line_);
}

std::vector<std::pair<std::string, Field>> Field::entries() const {
  expect_map();
  std::vector<std::pair<std::string, Field>> out;
  for (const auto& entry : node_) {
    const int key_line = entry.first.Mark().line + 1;
    if (!entry.first.IsScalar()) {
      child(entry.first, path_, key_line).fail("map keys must be plain names");
    }
    const std::string& key = entry.first.Scalar();
    Field value = child(entry.second, key_path(key), key_line);
    // yaml-cpp keeps repeated keys; a lookup would silently take the first, so refuse them.
    const auto previous =
        std::find_if(out.begin(), out.end(), [&](const auto& seen) { return seen.first == key; });
    if (previous != out.end()) {
      value.fail("key given twice (first at line " + std::to_string(previous->second.line()) + ")");
    }
    out.emplace_back(key, std::move(value));
  }
  return out;
}

// --- sequences --------------------------------------------------------------------------------

std::vector<Field> Field::items() const {
  if (!is_sequence()) fail(is_null() ? "has no value" : "must be a list", "a list such as [a, b]");
  std::vector<Field> out;
  out.reserve(node_.size());
  for (std::size_t i = 0; i < node_.size(); ++i) {
    const YAML::Node item = node_[i];
    // A null item (`- ` with nothing after it) has no usable mark: keep the list's line.
    const int item_line = item.Mark().line >= 0 && !item.IsNull() ? item.Mark().line + 1 : line_;
    out.push_back(child(item, path_ + "[" + std::to_string(i) + "]", item_line));
  }
  return out;
}

std::vector<Field> Field::items(std::size_t n, std::string_view expected) const {
  if (!is_sequence()) {
    fail(is_null() ? "has no value" : "must be a list of " + std::to_string(n) + " entries",
         expected);
  }
  if (node_.size() != n) {
    fail("must have exactly " + std::to_string(n) + " entries, has " + std::to_string(node_.size()),
         expected);
  }
  return items();
}

// --- scalars ----------------------------------------------------------------------------------

double Field::number() const { return number("a number such as 0.5 or 1e-3"); }

double Field::number(std::string_view expected) const {
  if (!is_scalar()) fail(is_null() ? "has no value" : "must be a number", expected);
  if (is_quoted(node_)) fail("must be a number, not a quoted string", expected);
  const std::optional<double> value = parse_real(node_.Scalar());
  if (!value) fail("must be a number", expected);
  if (!std::isfinite(*value)) fail("must be a finite number (NaN and Inf are not accepted)");
  return *value;
}

double Field::positive_number() const {
  const double value = number();
  check(value > 0.0, "must be > 0");
  return value;
}

int Field::integer_in(int lo, int hi) const {
  const std::string range = hi == INT_MAX ? ">= " + std::to_string(lo)
                                          : "in " + std::to_string(lo) + ".." + std::to_string(hi);
  const double value = number("an integer " + range);
  check(value >= lo && value <= hi,
        value > hi && hi == INT_MAX ? "is too large" : "must be " + range);
  check(value == std::floor(value), "must be a whole number", "an integer " + range);
  return static_cast<int>(value);
}

bool Field::boolean() const {
  if (is_scalar() && !is_quoted(node_)) {
    const std::string word = lowercase(node_.Scalar());
    if (word == "true") return true;
    if (word == "false") return false;
  }
  fail(is_null() ? "has no value" : "must be a boolean", "true or false");
}

std::string Field::string() const {
  if (!is_scalar()) fail(is_null() ? "has no value" : "must be a string", "a string");
  if (node_.Scalar().empty()) fail("must not be empty", "a string");
  return node_.Scalar();
}

}  // namespace mlshell::scene_reading
