#include "gis/model_lines.h"

#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "core/geometry.h"
#include "core/text.h"
#include "gis/atomic_output.h"

namespace isoquad {

namespace {

std::string extension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.'), slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  return lower_case(path.substr(dot + 1));
}

struct NamedLine {
  std::string name;
  std::vector<Point2> points;
};

class Parser {
 public:
  Parser(const std::string& path, const std::string& stage, const std::string& text)
      : path_(path), stage_(stage), in_(text) {}

  // Tekal: blocks of a name line, a "rows columns" line and rows of x y (...); lines
  // starting with '*' are comments.
  std::vector<NamedLine> tekal(bool close, bool separators) {
    std::vector<NamedLine> out;
    std::string line;
    while (next(line)) {
      std::istringstream name_line(line);
      std::string name;
      name_line >> name;
      long rows = 0, columns = 0;
      std::string size_line;
      if (!next(size_line)) fail("the block " + quote(name) + " ends before its size line");
      std::istringstream size(size_line);
      if (!(size >> rows >> columns) || rows < 0 || columns < 2)
        fail("expected the rows and columns of block " + quote(name) +
             " (two integers, at least 2 columns), found " + quote(size_line));
      NamedLine current{name, {}};
      for (long r = 0; r < rows; ++r) {
        std::string row;
        if (!next(row))
          fail("the block " + quote(name) + " ends after " + std::to_string(r) + " of its " +
               std::to_string(rows) + " rows");
        const Point2 p = point(row);
        if (separators && p.x == 999.999 && p.y == 999.999) {
          if (!current.points.empty()) out.push_back(current);
          current.points.clear();
          continue;
        }
        current.points.push_back(p);
      }
      if (close && current.points.size() >= 3 && current.points.front() != current.points.back())
        current.points.push_back(current.points.front());
      if (!current.points.empty()) out.push_back(std::move(current));
    }
    return out;
  }

  // Blue Kenue .i2s: a header up to ":EndHeader", then lines of "count value" followed
  // by count rows of x y.
  std::vector<NamedLine> i2s() {
    std::vector<NamedLine> out;
    std::string line;
    bool header_ended = false;
    while (!header_ended && next(line)) header_ended = line.rfind(":EndHeader", 0) == 0;
    if (!header_ended) fail("no ':EndHeader' line (a Blue Kenue .i2s file starts with a header)");
    while (next(line)) {
      std::istringstream head(line);
      long count = 0;
      std::string value;
      if (!(head >> count >> value) || count < 0)
        fail("expected a line's point count and value, found " + quote(line));
      NamedLine current{value, {}};
      for (long r = 0; r < count; ++r) {
        std::string row;
        if (!next(row))
          fail("the file ends after " + std::to_string(r) + " of the line's " +
               std::to_string(count) + " points");
        current.points.push_back(point(row));
      }
      out.push_back(std::move(current));
    }
    return out;
  }

 private:
  static std::string quote(const std::string& s) { return "'" + s + "'"; }

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(ErrorClass::input, stage_,
                quote(path_) + ": line " + std::to_string(line_number_) + ": " + what);
  }

  // The next line that is neither empty nor a comment.
  bool next(std::string& line) {
    while (std::getline(in_, line)) {
      ++line_number_;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      const std::size_t first = line.find_first_not_of(" \t");
      if (first == std::string::npos || line[first] == '*') continue;
      return true;
    }
    return false;
  }

  Point2 point(const std::string& row) const {
    std::istringstream is(row);
    Point2 p;
    if (!(is >> p.x >> p.y) || !std::isfinite(p.x) || !std::isfinite(p.y))
      fail("expected two numbers x y, found " + quote(row));
    return p;
  }

  std::string path_, stage_;
  std::istringstream in_;
  long line_number_ = 0;
};

std::string read_text(const std::string& path, const std::string& stage) {
  VSILFILE* f = VSIFOpenL(path.c_str(), "rb");
  if (!f) throw Error(ErrorClass::input, stage, "'" + path + "': cannot be opened");
  std::string text;
  char buffer[65536];
  std::size_t n;
  while ((n = VSIFReadL(buffer, 1, sizeof buffer, f)) > 0) text.append(buffer, n);
  VSIFCloseL(f);
  return text;
}

std::string stem(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  return name.substr(0, name.find_last_of('.'));
}

}  // namespace

bool is_model_lines_file(const std::string& path) {
  const std::string e = extension(path);
  return e == "ldb" || e == "pol" || e == "pli" || e == "i2s";
}

GdalDataset read_model_lines(const std::string& path, const std::string& stage) {
  note_input_file(path);  // no output may replace it
  const std::string e = extension(path);
  Parser parser(path, stage, read_text(path, stage));
  const std::vector<NamedLine> lines =
      e == "i2s" ? parser.i2s() : parser.tekal(e == "pol", e == "ldb");
  if (lines.empty()) throw Error(ErrorClass::input, stage, "'" + path + "': holds no line");
  ensure_gdal_registered();
  GDALDriver* memory = GetGDALDriverManager()->GetDriverByName("Memory");
  GdalDataset ds(memory->Create("", 0, 0, 0, GDT_Unknown, nullptr));
  OGRLayer* layer = ds->CreateLayer(stem(path).c_str(), nullptr, wkbLineString, nullptr);
  OGRFieldDefn field("name", OFTString);
  layer->CreateField(&field);
  for (const NamedLine& l : lines) {
    OGRFeature feature(layer->GetLayerDefn());
    feature.SetField("name", l.name.c_str());
    OGRLineString geometry;
    for (const Point2& p : l.points) geometry.addPoint(p.x, p.y);
    feature.SetGeometry(&geometry);
    if (layer->CreateFeature(&feature) != OGRERR_NONE)
      throw Error(ErrorClass::internal, stage,
                  "'" + path + "': its lines could not be kept in memory");
  }
  return ds;
}

}  // namespace isoquad
