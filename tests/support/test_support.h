// Helpers shared by the tests: temporary directories, fixture files, running the CLI.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

namespace isoquad::test {

inline std::string source_dir() { return ISOQUAD_SOURCE_DIR; }
inline std::string sample(const std::string& name) {
  return source_dir() + "/shapefiles/" + name;
}

// A fresh directory removed (with its contents) when the object dies.
class TempDir {
 public:
  TempDir() {
    std::string tmpl =
        (std::filesystem::temp_directory_path() / "isoquad-test-XXXXXX").string();
    path_ = mkdtemp(tmpl.data()) ? tmpl : "";
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  std::vector<std::string> entries() const {
    std::vector<std::string> out;
    for (const auto& e : std::filesystem::directory_iterator(path_))
      out.push_back(e.path().filename().string());
    return out;
  }

 private:
  std::string path_;
};

inline void write_file(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}

inline std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// The GeoJSON member naming UTM zone 31N as the coordinates' CRS, for geojson_polygons.
inline const char* const kUtm31nCrsMember =
    R"("crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32631"}},)";

// A GeoJSON FeatureCollection with one Polygon feature per ring list given as raw JSON
// coordinate text, e.g. "[[[0,0],[1,0],[1,1],[0,0]]]".
inline std::string geojson_polygons(const std::vector<std::string>& coordinates,
                                    const std::string& crs_member = "") {
  std::string s = "{\"type\":\"FeatureCollection\"," + crs_member + "\"features\":[";
  for (std::size_t i = 0; i < coordinates.size(); ++i) {
    if (i) s += ",";
    s += "{\"type\":\"Feature\",\"properties\":{\"id\":" + std::to_string(i) +
         ",\"name\":\"f" + std::to_string(i) + "\"},\"geometry\":{\"type\":\"Polygon\","
         "\"coordinates\":" + coordinates[i] + "}}";
  }
  return s + "]}";
}

struct CliResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Runs `program` with `args` (each quoted), capturing both streams.
inline CliResult run_cli_program(const std::string& program, const std::vector<std::string>& args,
                                 const TempDir& dir) {
  std::string cmd = shell_quote(program);
  for (const std::string& a : args) cmd += " " + shell_quote(a);
  const std::string out = dir.path() + "/.stdout", err = dir.path() + "/.stderr";
  cmd += " >" + shell_quote(out) + " 2>" + shell_quote(err) + " </dev/null";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

// Writes `script` to the directory and runs it with Debian's Python (/usr/bin/python3,
// where meshio, netCDF4, GDAL and QGIS load), capturing both streams.
inline CliResult run_python(const TempDir& dir, const std::string& script,
                            const std::vector<std::string>& args) {
  const std::string path = dir.path() + "/check.py";
  {
    std::ofstream f(path);
    f << script;
  }
  std::vector<std::string> all = {path};
  all.insert(all.end(), args.begin(), args.end());
  return run_cli_program("/usr/bin/python3", all, dir);
}

// run_python for a check that must succeed (exit 0); returns its standard output.
inline std::string python_check(const TempDir& dir, const std::string& script,
                                const std::vector<std::string>& args) {
  const CliResult r = run_python(dir, script, args);
  EXPECT_EQ(r.exit_code, 0) << r.err << r.out;
  return r.out;
}

// The first number under `key` in a JSON report ("key": value); NaN (and a failure)
// when it has none.
inline double report_number(const std::string& report, const std::string& key) {
  const std::size_t at = report.find("\"" + key + "\": ");
  EXPECT_NE(at, std::string::npos) << key;
  return at == std::string::npos ? std::nan("") : std::stod(report.substr(at + key.size() + 4));
}

// Starts `args` (the program first) in a child process, its standard error to the file
// `err_path`, and returns its pid without waiting, for a test to stop it part-way.
inline pid_t start_program(const std::vector<std::string>& args, const std::string& err_path) {
  const pid_t child = fork();
  if (child == 0) {
    const int err = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(err, 2);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  return child;
}

// Waits for the child `child` (start_program) to end, checking `ready()` every
// `poll_us` microseconds: once it holds, calls `stop()` (which signals the child) and waits
// for the end. Returns the wait status, or -1 when the child has not ended within two
// minutes.
inline int wait_or_stop(pid_t child, const std::function<bool()>& ready,
                        const std::function<void()>& stop, int poll_us) {
  int status = 0;
  const auto start = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - start < std::chrono::seconds(120)) {
    if (ready()) {
      stop();
      return waitpid(child, &status, 0) == child ? status : -1;
    }
    if (waitpid(child, &status, WNOHANG) == child) return status;
    usleep(poll_us);
  }
  return -1;
}

// Runs the built isoquad binary.
inline CliResult run_cli(const std::vector<std::string>& args, const TempDir& dir) {
  return run_cli_program(ISOQUAD_CLI, args, dir);
}

}  // namespace isoquad::test
