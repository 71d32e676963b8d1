// A small streaming JSON writer for reports: objects, arrays, numbers, strings.
#pragma once

#include <string>
#include <vector>

namespace isoquad {

class JsonWriter {
 public:
  JsonWriter& begin_object(const std::string& key = "");
  JsonWriter& end_object();
  JsonWriter& begin_array(const std::string& key = "");
  JsonWriter& end_array();
  JsonWriter& value(const std::string& key, double v);
  JsonWriter& value(const std::string& key, long long v);
  JsonWriter& value(const std::string& key, int v) { return value(key, static_cast<long long>(v)); }
  JsonWriter& value(const std::string& key, std::size_t v) {
    return value(key, static_cast<long long>(v));
  }
  JsonWriter& value(const std::string& key, bool v);
  JsonWriter& value(const std::string& key, const std::string& v);
  JsonWriter& value(const std::string& key, const char* v) { return value(key, std::string(v)); }
  JsonWriter& array(const std::string& key, const std::vector<int>& v);
  JsonWriter& array(const std::string& key, const std::vector<double>& v);
  JsonWriter& array(const std::string& key, const std::vector<std::string>& v);
  // The document, with a final newline.
  std::string str() const { return out_ + "\n"; }

  static std::string quote(const std::string& s);
  static std::string number(double v);

 private:
  void prefix(const std::string& key);
  std::string out_;
  std::vector<bool> first_;  // per open container: nothing written yet
};

}  // namespace isoquad
