#include "core/json_writer.h"

#include <cmath>
#include <cstdio>

#include "core/text.h"

namespace isoquad {

std::string JsonWriter::quote(const std::string& raw) {
  // JSON is UTF-8 (RFC 8259): text that is not (a .dbf's Latin-1 in a command line) is
  // read as Windows-1252.
  const std::string s = utf8_or_cp1252(raw);
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string JsonWriter::number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

void JsonWriter::prefix(const std::string& key) {
  if (!first_.empty()) {
    if (!first_.back()) out_ += ",";
    first_.back() = false;
    out_ += "\n" + std::string(2 * first_.size(), ' ');
  }
  if (!key.empty()) out_ += quote(key) + ": ";
}

JsonWriter& JsonWriter::begin_object(const std::string& key) {
  prefix(key);
  out_ += "{";
  first_.push_back(true);
  return *this;
}

JsonWriter& JsonWriter::end_object() {
  const bool empty = first_.back();
  first_.pop_back();
  if (!empty) out_ += "\n" + std::string(2 * first_.size(), ' ');
  out_ += "}";
  return *this;
}

JsonWriter& JsonWriter::begin_array(const std::string& key) {
  prefix(key);
  out_ += "[";
  first_.push_back(true);
  return *this;
}

JsonWriter& JsonWriter::end_array() {
  const bool empty = first_.back();
  first_.pop_back();
  if (!empty) out_ += "\n" + std::string(2 * first_.size(), ' ');
  out_ += "]";
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, double v) {
  prefix(key);
  out_ += number(v);
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, long long v) {
  prefix(key);
  out_ += std::to_string(v);
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, bool v) {
  prefix(key);
  out_ += v ? "true" : "false";
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, const std::string& v) {
  prefix(key);
  out_ += quote(v);
  return *this;
}

JsonWriter& JsonWriter::array(const std::string& key, const std::vector<int>& v) {
  prefix(key);
  out_ += "[";
  for (std::size_t i = 0; i < v.size(); ++i) out_ += (i ? ", " : "") + std::to_string(v[i]);
  out_ += "]";
  return *this;
}

JsonWriter& JsonWriter::array(const std::string& key, const std::vector<double>& v) {
  prefix(key);
  out_ += "[";
  for (std::size_t i = 0; i < v.size(); ++i) out_ += (i ? ", " : "") + number(v[i]);
  out_ += "]";
  return *this;
}

JsonWriter& JsonWriter::array(const std::string& key, const std::vector<std::string>& v) {
  prefix(key);
  out_ += "[";
  for (std::size_t i = 0; i < v.size(); ++i) out_ += (i ? ", " : "") + quote(v[i]);
  out_ += "]";
  return *this;
}

}  // namespace isoquad
