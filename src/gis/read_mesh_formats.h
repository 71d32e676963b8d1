// The readers behind read_mesh (read_mesh.h), one translation unit per family of
// formats: the text ones (read_mesh_text.cpp: SCHISM's .gr3/.ll, ADCIRC's .14, SMS's .2dm,
// Gmsh's .msh, MIKE's .mesh), the binary ones (read_mesh_binary.cpp: UGRID netCDF and
// D-Flow FM's net files, TELEMAC's Selafin and the .cli beside it; read_mesh_vtk.cpp:
// VTK's .vtu and .vtk), and what they share:
// a text file's lines and fields with their numbers for the messages, and the open
// boundaries from the nodes' codes (read_mesh.cpp). Not for use outside these files.
#pragma once

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"
#include "gis/read_mesh.h"

namespace isoquad::mesh_readers {

// The file's lines, one at a time, with their numbers for the messages.
class LineReader {
 public:
  explicit LineReader(const std::string& path) : path_(path), in_(path) {
    if (!in_) throw Error(ErrorClass::input, "read", "'" + path + "': cannot open the mesh file");
  }
  // The next line (without a trailing carriage return); false at the end of the file.
  bool next(std::string& line) {
    if (!std::getline(in_, line)) return false;
    ++number_;
    unterminated_ = in_.eof();  // the file ended before the line's break
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  }
  // The next line that holds something; Error(input) at the end of the file.
  std::string need(const std::string& what) {
    std::string line;
    while (next(line))
      if (line.find_first_not_of(" \t") != std::string::npos) return line;
    throw Error(ErrorClass::input, "read",
                "'" + path_ + "': the file ends at line " + std::to_string(number_) + " where " +
                    what + " should follow");
  }
  [[noreturn]] void fail(const std::string& what) const { fail_at(number_, what); }
  [[noreturn]] void fail_at(int line, const std::string& what) const {
    // The last line without its line break: a file cut short, most likely.
    const bool cut = line == number_ && unterminated_;
    throw Error(ErrorClass::input, "read",
                "'" + path_ + "' line " + std::to_string(line) + ": " + what +
                    (cut ? " (the file ends there, in the middle of a line: was it written or "
                           "copied whole?)"
                         : ""));
  }
  int number() const { return number_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ifstream in_;
  int number_ = 0;
  bool unterminated_ = false;
};

// A word of the file as a message shows it: at most 32 characters, each byte outside
// printable ASCII as '?'.
inline std::string shown(const std::string& word) {
  std::string out;
  for (char c : word.substr(0, 32)) out += c >= 32 && c < 127 ? c : '?';
  return word.size() > 32 ? out + "..." : out;
}

// Whitespace-separated fields of a line, read as numbers.
class Fields {
 public:
  Fields(const std::string& line, const LineReader& reader) : line_(line), reader_(reader) {}
  bool at_end() {
    skip();
    return pos_ >= line_.size();
  }
  std::string word(const char* what) {
    skip();
    if (pos_ >= line_.size()) reader_.fail(std::string("expected ") + what);
    const std::size_t start = pos_;
    while (pos_ < line_.size() && !std::isspace(static_cast<unsigned char>(line_[pos_]))) ++pos_;
    return line_.substr(start, pos_ - start);
  }
  long long integer(const char* what) {
    const std::string w = word(what);
    long long value = 0;
    const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), value);
    if (ec != std::errc() || end != w.data() + w.size())
      reader_.fail(std::string("expected ") + what + ", an integer, found '" + shown(w) + "'");
    return value;
  }
  double number(const char* what) {
    const std::string w = word(what);
    double value = 0;
    // Fortran writes exponents as D.
    std::string text = w;
    std::replace(text.begin(), text.end(), 'D', 'E');
    std::replace(text.begin(), text.end(), 'd', 'e');
    const char* first = text.data();
    if (!text.empty() && text[0] == '+') ++first;
    const auto [end, ec] = std::from_chars(first, text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
      reader_.fail(std::string("expected ") + what + ", a number, found '" + shown(w) + "'");
    return value;
  }
  std::string rest() {
    skip();
    return line_.substr(std::min(pos_, line_.size()));
  }

 private:
  void skip() {
    while (pos_ < line_.size() && std::isspace(static_cast<unsigned char>(line_[pos_]))) ++pos_;
  }
  std::string line_;
  const LineReader& reader_;
  std::size_t pos_ = 0;
};

// The text formats: each reads the file from `r` into `mesh` (read_mesh_text.cpp).
void read_gr3(LineReader& r, ReadMesh& mesh);   // .gr3, .ll, .14
void read_2dm(LineReader& r, ReadMesh& mesh);   // .2dm
void read_msh(LineReader& r, ReadMesh& mesh);   // .msh, ASCII 2.2 and 4.1
void read_mike(LineReader& r, ReadMesh& mesh);  // .mesh

// The binary formats (read_mesh_binary.cpp).
// Whether a netCDF file holds a mesh (UGRID, a D-Flow FM net file) rather than a grid;
// true for one netCDF cannot open, for read_netcdf's message.
bool netcdf_holds_mesh(const std::string& path);
void read_netcdf(const std::string& path, ReadMesh& mesh);
void read_selafin(const std::string& path, ReadMesh& mesh);
void read_telemac_cli(const std::string& slf_path, ReadMesh& mesh);

// VTK's XML unstructured grid (.vtu) and legacy ASCII file (.vtk), by mesh.format
// (read_mesh_vtk.cpp).
void read_vtk(const std::string& path, ReadMesh& mesh);

// read_mesh.cpp: the open boundaries as runs of the outline's faces of one kind, and
// from the nodes' codes by MIKE's rule.
bool open_runs(ReadMesh& mesh, const std::string& path,
               const std::function<long long(int, int)>& face_kind);
void open_boundaries_from_codes(const std::vector<long long>& codes, const std::string& path,
                                ReadMesh& mesh);

}  // namespace isoquad::mesh_readers
