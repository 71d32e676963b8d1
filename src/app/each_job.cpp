#include "app/each_job.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <exception>
#include <filesystem>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "core/error.h"
#include "core/text.h"

namespace isoquad {

bool has_each_mark(const std::string& path) {
  return path.find(kEachMark) != std::string::npos;
}

std::string fill_each_mark(std::string path, const std::string& name) {
  const std::string mark = kEachMark;
  for (std::size_t at = path.find(mark); at != std::string::npos;
       at = path.find(mark, at + name.size()))
    path.replace(at, mark.size(), name);
  return path;
}

std::vector<std::string> each_file_names(const std::string& field,
                                         const std::vector<std::string>& values,
                                         const std::vector<bool>& null, const std::string& option) {
  std::map<std::string, std::size_t> value_of;  // file name -> the value's index
  std::vector<std::string> names;
  auto shown = [&](std::size_t k) {
    return k < null.size() && null[k] ? std::string("NULL (no value)") : "'" + values[k] + "'";
  };
  for (std::size_t k = 0; k < values.size(); ++k) {
    const std::string& value = values[k];
    std::string name = value.empty() ? "_" : value;
    for (char& c : name)
      if (static_cast<unsigned char>(c) < 0x80 && !std::isalnum(static_cast<unsigned char>(c)) &&
          c != '.' && c != '-' && c != '_')
        c = '_';
    // Bytes that are not UTF-8 (a Latin-1 .dbf without its .cpg) would give a name no
    // file browser shows: each as '_'.
    for (std::size_t i = 0; i < name.size();) {
      const std::size_t n = utf8_sequence_length(name, i);
      if (n == 0)
        name[i++] = '_';
      else
        i += n;
    }
    // A name starting with '-' reads as an option on a command line.
    if (name[0] == '-') name[0] = '_';
    // "." and ".." would name the folder, or the one above, in a path such as out/{}/m.gpkg.
    if (name == "." || name == "..") name = "_" + name;
    const auto [at, added] = value_of.emplace(name, k);
    if (!added)
      throw Error(ErrorClass::usage, "options",
                  option + " " + field + ": the values " + shown(at->second) + " and " + shown(k) +
                      " give the same file name '" + name + "'");
    names.push_back(name);
  }
  return names;
}

std::vector<RegionOutcome> run_regions(
    std::size_t n, std::size_t jobs, const std::function<std::string(std::size_t)>& header,
    const std::function<RegionOutcome(std::size_t, const Console&)>& run, std::ostream& stream,
    const std::function<void(const std::vector<RegionOutcome>&)>& finished) {
  std::vector<RegionOutcome> outcomes(n);
  for (RegionOutcome& o : outcomes) o.not_run = true;
  jobs = std::min(jobs, n);
  // Whether outcome k repeats the usage error of a region that ended before it.
  std::vector<std::string> usage_errors;
  auto repeats_usage_error = [&](std::size_t k) {
    const std::string& e = outcomes[k].usage_error;
    if (e.empty() || outcomes[k].quality) return false;
    if (std::find(usage_errors.begin(), usage_errors.end(), e) != usage_errors.end()) return true;
    usage_errors.push_back(e);
    return false;
  };
  if (jobs <= 1) {
    for (std::size_t k = 0; k < n; ++k) {
      stream << header(k) << std::flush;
      outcomes[k] = run(k, Console{stream, stream, true});
      if (finished) finished(outcomes);
      if (repeats_usage_error(k)) break;
    }
    return outcomes;
  }
  struct Buffers {
    std::ostringstream out, err;
    bool done = false;
    std::exception_ptr crash;
  };
  std::vector<Buffers> buffers(n);
  std::mutex mutex;
  std::size_t printed = 0;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  // The regions done, printed in order (the mutex held). Where one thread would have
  // stopped (the second region, in order, with a usage error an earlier one had), the
  // later regions that failed with such an error, or were skipped, were only started
  // because several ran at once: they are `not run`, unprinted, as one thread leaves them, so that
  // the table and the total are the same on any number of threads (what a later region meshed
  // meanwhile is kept: its files are written).
  std::vector<std::string> errors_in_order;
  bool stopped = false;
  auto print_done = [&](bool skip_not_done) {
    for (; printed < n && (buffers[printed].done || skip_not_done); ++printed) {
      if (!buffers[printed].done) continue;
      RegionOutcome& o = outcomes[printed];
      const bool usage_failure = !o.usage_error.empty() && !o.quality;
      const bool seen = usage_failure && std::find(errors_in_order.begin(), errors_in_order.end(),
                                                   o.usage_error) != errors_in_order.end();
      if (stopped && (seen || o.skipped)) {
        o = RegionOutcome();
        o.not_run = true;
        continue;
      }
      stream << header(printed) << buffers[printed].out.str() << buffers[printed].err.str()
             << std::flush;
      if (seen) stopped = true;
      if (usage_failure && !seen) errors_in_order.push_back(o.usage_error);
    }
  };
  auto worker = [&] {
    for (std::size_t k = next++; k < n && !stop; k = next++) {
      RegionOutcome outcome;
      try {
        outcome = run(k, Console{buffers[k].out, buffers[k].err, false});
      } catch (...) {
        buffers[k].crash = std::current_exception();
      }
      const std::lock_guard<std::mutex> lock(mutex);
      outcomes[k] = std::move(outcome);
      if (finished && !buffers[k].crash) finished(outcomes);
      if (repeats_usage_error(k)) stop = true;
      buffers[k].done = true;
      print_done(false);
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t j = 1; j < jobs; ++j) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  // Regions after one that did not start are printed by nobody above: those that ran
  // print now, in order.
  print_done(true);
  for (const Buffers& b : buffers)
    if (b.crash) std::rethrow_exception(b.crash);
  return outcomes;
}

namespace {

// Characters in UTF-8 text: the bytes that start one.
std::size_t num_chars(const std::string& text) {
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  }));
}

}  // namespace

std::string format_each_table(const std::string& field, const std::vector<std::string>& values,
                              const std::vector<RegionOutcome>& outcomes) {
  std::size_t width = num_chars(field);
  for (const std::string& v : values) width = std::max(width, num_chars(v));
  auto padded = [&](const std::string& t) { return t + std::string(width - num_chars(t), ' '); };
  std::string table = "\n" + padded(field) +
                      printf_string(" %8s %8s %8s %8s %8s %8s\n", "quads", "angles", "regular",
                                    "sizes", "orient.", "seconds");
  for (std::size_t k = 0; k < values.size(); ++k) {
    table += padded(values[k]);
    const RegionOutcome& o = outcomes[k];
    if (!o.quality || o.skipped) {
      table += printf_string(" %8s\n", o.skipped ? "skipped" : o.not_run ? "not run" : "failed");
      continue;
    }
    const QualitySummary& q = *o.quality;
    if (q.num_quads == 0) {  // a mesh of triangles measured: no quads' figures
      table += printf_string(" %8d %8s %8s %8s %8s %8.2f\n", 0, "-", "-", "-", "-", o.seconds);
      continue;
    }
    table += printf_string(" %8zu %7.1f%% %7.1f%% %7.1f%% %8.1f %8.2f\n", q.num_quads,
                           100 * q.share_angles_75_105, 100 * q.share_regular_interior,
                           100 * q.share_size_08_125, q.orientation_mean_deg, o.seconds);
  }
  return table;
}

std::string format_each_total(const std::string& field, const std::vector<std::string>& values,
                              const std::vector<RegionOutcome>& outcomes, const std::string& done,
                              const std::string& option) {
  std::vector<std::string> failed;
  std::size_t skipped = 0, not_run = 0;
  for (std::size_t k = 0; k < values.size(); ++k)
    if (outcomes[k].skipped)
      ++skipped;
    else if (outcomes[k].not_run)
      ++not_run;
    else if (!outcomes[k].quality)
      failed.push_back(values[k]);
  std::string line = option + " " + field + ": " +
                     std::to_string(values.size() - failed.size() - skipped - not_run) + " of " +
                     std::to_string(values.size()) + " " + done;
  if (skipped) line += ", " + std::to_string(skipped) + " skipped (every output exists)";
  for (std::size_t i = 0; i < failed.size(); ++i) line += (i ? ", " : "; failed: ") + failed[i];
  if (not_run) {
    // The two regions whose usage error was the same.
    std::vector<std::string> same;
    for (std::size_t k = 0; k < values.size() && same.size() < 2; ++k) {
      if (outcomes[k].usage_error.empty()) continue;
      for (std::size_t j = k + 1; j < values.size(); ++j)
        if (outcomes[j].usage_error == outcomes[k].usage_error) {
          same = {values[k], values[j]};
          break;
        }
    }
    line += "; " + std::to_string(not_run) + " not run";
    if (same.size() == 2)
      line += ": " + same[0] + " and " + same[1] +
              " failed with the same usage error, which the other regions would repeat; "
              "correct the command and run it again (--skip-existing keeps what is meshed)";
  }
  return line + "\n";
}

namespace {

// A CSV field (RFC 4180): quoted, its quotes doubled, when it holds a comma, a quote or a
// line break.
// A CSV field: valid UTF-8 (utf8_or_cp1252), quoted when it needs it (RFC 4180).
std::string csv_field(const std::string& raw) {
  const std::string text = utf8_or_cp1252(raw);
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace

std::string format_each_csv(const std::string& field, const std::vector<EachCsvRegion>& regions,
                            const std::vector<RegionOutcome>& outcomes, const std::string& done) {
  std::string csv =
      csv_field(field) +
      ",file,status,exit,quads,vertices,angles_75_105_pct,min_angle_deg,max_angle_deg,"
      "regular_interior_pct,size_ratio_median,sizes_08_125_pct,"
      "orientation_mean_deg,orientation_p90_deg,schism_angle_ratio_fails,"
      "schism_aspect_fails,dflowfm_links_over_05,error\r\n";
  for (std::size_t k = 0; k < regions.size(); ++k) {
    const RegionOutcome& o = outcomes[k];
    // A skipped region's figures, when there, are its earlier report's.
    const char* status = o.skipped   ? "skipped"
                         : o.quality ? done.c_str()
                         : o.not_run ? "not run"
                                     : "failed";
    csv += (regions[k].null ? std::string() : csv_field(regions[k].value)) + "," +
           csv_field(regions[k].file) + "," + status + "," +
           (o.not_run ? std::string() : std::to_string(o.exit));
    if (o.quality && o.quality->num_quads == 0) {
      // A mesh of triangles measured: its vertices, and no quads' figures.
      csv += printf_string(",0,%zu", o.quality->num_vertices) + std::string(12, ',');
    } else if (o.quality) {
      const QualitySummary& q = *o.quality;
      csv += printf_string(",%zu,%zu,%.2f,%.2f,%.2f,%.2f,%.4f,%.2f,%.2f,%.2f,%zu,%zu,%zu,",
                           q.num_quads, q.num_vertices, 100 * q.share_angles_75_105,
                           q.min_angle_deg, q.max_angle_deg, 100 * q.share_regular_interior,
                           q.size_ratio_median, 100 * q.share_size_08_125, q.orientation_mean_deg,
                           q.orientation_p90_deg, q.schism_angle_ratio_violations,
                           q.schism_aspect_violations, q.dflowfm_orthogonality_violations);
    } else {
      csv += ",,,,,,,,,,,,,,";
    }
    csv += csv_field(o.error) + "\r\n";
  }
  return csv;
}

std::string format_each_csv_types() {
  // As format_each_csv's columns: the value, file, status, exit, quads, vertices, eight
  // figures, three counts, the error.
  std::string types = "\"String\",\"String\",\"String\",\"Integer\",\"Integer\",\"Integer\"";
  for (int k = 0; k < 8; ++k) types += ",\"Real\"";
  for (int k = 0; k < 3; ++k) types += ",\"Integer\"";
  return types + ",\"String\"\r\n";
}

std::string each_csv_types_path(const std::string& table_path) {
  std::filesystem::path p(table_path);
  if (lower_case(p.extension().string()) != ".csv") return "";
  return p.replace_extension(".csvt").string();
}

int each_exit_code(const std::vector<RegionOutcome>& outcomes) {
  for (const RegionOutcome& o : outcomes)
    if (!o.quality && !o.skipped && !o.not_run) return o.exit;
  return 0;
}

}  // namespace isoquad
