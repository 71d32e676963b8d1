#include "app/each_job.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <exception>
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
                                         const std::vector<std::string>& values) {
  std::map<std::string, std::string> value_of;  // file name -> value
  std::vector<std::string> names;
  for (const std::string& value : values) {
    std::string name = value.empty() ? "_" : value;
    for (char& c : name)
      if (static_cast<unsigned char>(c) < 0x80 && !std::isalnum(static_cast<unsigned char>(c)) &&
          c != '.' && c != '-' && c != '_')
        c = '_';
    const auto [at, added] = value_of.emplace(name, value);
    if (!added)
      throw Error(ErrorClass::usage, "options",
                  "--each " + field + ": the values '" + at->second + "' and '" + value +
                      "' give the same file name '" + name + "'");
    names.push_back(name);
  }
  return names;
}

std::vector<RegionOutcome> run_regions(
    std::size_t n, std::size_t jobs, const std::function<std::string(std::size_t)>& header,
    const std::function<RegionOutcome(std::size_t, const Console&)>& run, std::ostream& stream) {
  std::vector<RegionOutcome> outcomes(n);
  jobs = std::min(jobs, n);
  if (jobs <= 1) {
    for (std::size_t k = 0; k < n; ++k) {
      stream << header(k) << std::flush;
      outcomes[k] = run(k, Console{stream, stream, true});
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
  auto worker = [&] {
    for (std::size_t k = next++; k < n; k = next++) {
      try {
        outcomes[k] = run(k, Console{buffers[k].out, buffers[k].err, false});
      } catch (...) {
        buffers[k].crash = std::current_exception();
      }
      const std::lock_guard<std::mutex> lock(mutex);
      buffers[k].done = true;
      for (; printed < n && buffers[printed].done; ++printed)
        stream << header(printed) << buffers[printed].out.str() << buffers[printed].err.str()
               << std::flush;
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t j = 1; j < jobs; ++j) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
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
    if (!o.quality) {
      table += printf_string(" %8s\n", o.skipped ? "skipped" : "failed");
      continue;
    }
    const QualitySummary& q = *o.quality;
    table += printf_string(" %8zu %7.1f%% %7.1f%% %7.1f%% %8.1f %8.2f\n", q.num_quads,
                           100 * q.share_angles_75_105, 100 * q.share_regular_interior,
                           100 * q.share_size_08_125, q.orientation_mean_deg, o.seconds);
  }
  return table;
}

std::string format_each_total(const std::string& field, const std::vector<std::string>& values,
                              const std::vector<RegionOutcome>& outcomes, const std::string& done) {
  std::vector<std::string> failed;
  std::size_t skipped = 0;
  for (std::size_t k = 0; k < values.size(); ++k)
    if (outcomes[k].skipped)
      ++skipped;
    else if (!outcomes[k].quality)
      failed.push_back(values[k]);
  std::string line = "--each " + field + ": " +
                     std::to_string(values.size() - failed.size() - skipped) + " of " +
                     std::to_string(values.size()) + " " + done;
  if (skipped) line += ", " + std::to_string(skipped) + " skipped (every output exists)";
  for (std::size_t i = 0; i < failed.size(); ++i) line += (i ? ", " : "; failed: ") + failed[i];
  return line + "\n";
}

int each_exit_code(const std::vector<RegionOutcome>& outcomes) {
  for (const RegionOutcome& o : outcomes)
    if (!o.quality && !o.skipped) return o.exit;
  return 0;
}

}  // namespace isoquad
