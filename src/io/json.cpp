// Minimal JSON writer for summary.json: insertion-ordered objects, exact integers, doubles with
// 17 significant digits, and RFC 8259 string escaping. Writing only; nothing here parses.
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "io_util.hpp"

namespace mlshell {
namespace {

void append_string(std::string& out, const std::string& s) {
  out += '"';
  for (unsigned char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\f':
        out += "\\f";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (c < 0x20) {  // the remaining control characters must be \u-escaped
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += static_cast<char>(c);  // UTF-8 bytes pass through unchanged
        }
    }
  }
  out += '"';
}

void append_double(std::string& out, double d) {
  // JSON has no NaN or infinity; null keeps the document parseable and marks the gap.
  if (!std::isfinite(d)) {
    out += "null";
    return;
  }
  std::string s = io_detail::format_double(d);
  // The shortest round-trip text of 2.0 is "2"; append ".0" so readers that distinguish
  // integers from floats (Python's json) give back a float.
  if (s.find_first_of(".eE") == std::string::npos) s += ".0";
  out += s;
}

void newline(std::string& out, int indent, int depth) {
  if (indent <= 0) return;
  out += '\n';
  out.append(static_cast<std::size_t>(indent) * static_cast<std::size_t>(depth), ' ');
}

}  // namespace

Json Json::array(const std::vector<double>& xs) {
  Array a;
  a.reserve(xs.size());
  for (double x : xs) a.emplace_back(x);
  return Json(std::move(a));
}

Json& Json::set(const std::string& key, Json value) {
  auto* obj = std::get_if<std::shared_ptr<Object>>(&v_);
  if (!obj) throw std::logic_error("Json::set('" + key + "') on a value that is not an object");
  // Values share their containers on copy (shared_ptr); copy before writing so that other
  // Json values holding the same object are not changed behind their back.
  if (obj->use_count() > 1) *obj = std::make_shared<Object>(**obj);
  for (auto& [k, v] : **obj) {
    if (k == key) {
      v = std::move(value);
      return *this;
    }
  }
  (*obj)->emplace_back(key, std::move(value));
  return *this;
}

std::string Json::dump(int indent) const {
  std::string out;
  dump_to(out, indent, 0);
  if (indent > 0) out += '\n';
  return out;
}

void Json::dump_to(std::string& out, int indent, int depth) const {
  if (std::holds_alternative<std::nullptr_t>(v_)) {
    out += "null";
  } else if (const auto* b = std::get_if<bool>(&v_)) {
    out += *b ? "true" : "false";
  } else if (const auto* i = std::get_if<long long>(&v_)) {
    out += std::to_string(*i);
  } else if (const auto* d = std::get_if<double>(&v_)) {
    append_double(out, *d);
  } else if (const auto* s = std::get_if<std::string>(&v_)) {
    append_string(out, *s);
  } else if (const auto* a = std::get_if<std::shared_ptr<Array>>(&v_)) {
    if ((*a)->empty()) {
      out += "[]";
      return;
    }
    out += '[';
    bool first = true;
    for (const Json& e : **a) {
      if (!first) out += ',';
      first = false;
      newline(out, indent, depth + 1);
      e.dump_to(out, indent, depth + 1);
    }
    newline(out, indent, depth);
    out += ']';
  } else {
    const auto& o = std::get<std::shared_ptr<Object>>(v_);
    if (o->empty()) {
      out += "{}";
      return;
    }
    out += '{';
    bool first = true;
    for (const auto& [k, v] : *o) {
      if (!first) out += ',';
      first = false;
      newline(out, indent, depth + 1);
      append_string(out, k);
      out += indent > 0 ? ": " : ":";
      v.dump_to(out, indent, depth + 1);
    }
    newline(out, indent, depth);
    out += '}';
  }
}

}  // namespace mlshell
