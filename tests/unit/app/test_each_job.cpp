// --each's regions (app/each_job.h): file names, the runs' order on several threads, the
// table.
#include "app/each_job.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "app/quality_report.h"
#include "core/error.h"
#include "support/test_support.h"

using namespace isoquad;
using namespace isoquad::test;

TEST(EachJob, ValuesBecomeFileNamesAndTwoThatMeetAreRefused) {
  EXPECT_EQ(
      each_file_names("name", {"Côte d'Ivoire", "a/b c", "", "x.y-z_1", "..", ".", "..."}),
      (std::vector<std::string>{"Côte_d_Ivoire", "a_b_c", "_", "x.y-z_1", "_..", "_.", "..."}));
  // Bytes that are not UTF-8 (Latin-1's ç, a truncated sequence, a surrogate) as '_',
  // UTF-8 kept; a leading '-' as '_'.
  EXPECT_EQ(each_file_names("name", {"Cura\xe7"
                                     "ao",
                                     "\xc3", "a\xed\xa0\x80", "-o", "\xe6\x97\xa5"}),
            (std::vector<std::string>{"Cura_ao", "_", "a___", "_o", "\xe6\x97\xa5"}));
  try {
    each_file_names("name", {"a b", "a/b"});
    FAIL() << "two values with one file name";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::usage);
    EXPECT_NE(std::string(e.what()).find("'a b' and 'a/b' give the same file name 'a_b'"),
              std::string::npos)
        << e.what();
  }
  // An empty value and the features without one: both '_', the latter named NULL.
  try {
    each_file_names("name", {"", ""}, {false, true}, "--each-clip");
    FAIL() << "an empty value and a null one";
  } catch (const Error& e) {
    EXPECT_NE(
        std::string(e.what()).find(
            "--each-clip name: the values '' and NULL (no value) give the same file name '_'"),
        std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(has_each_mark("out/{}.gpkg"));
  EXPECT_FALSE(has_each_mark("out/x.gpkg"));
  EXPECT_EQ(fill_each_mark("out/{}/m_{}.gpkg", "fr"), "out/fr/m_fr.gpkg");
}

// With two threads the regions end out of order (the first sleeps); what they print
// comes out in their order all the same, header, out, err, and each outcome is its own.
TEST(EachJob, RegionsRunAtOncePrintInTheirOrder) {
  for (const std::size_t jobs : {1, 2, 3}) {
    std::ostringstream stream;
    const auto outcomes = run_regions(
        4, jobs, [](std::size_t k) { return "== " + std::to_string(k) + "\n"; },
        [](std::size_t k, const Console& c) {
          if (k == 0) std::this_thread::sleep_for(std::chrono::milliseconds(200));
          c.out << "out " << k << "\n";
          c.err << "err " << k << "\n";
          RegionOutcome o;
          if (k == 2) {
            o.exit = 5;
          } else {
            o.quality = QualitySummary{};
            o.quality->num_quads = 10 * k;
          }
          return o;
        },
        stream);
    EXPECT_EQ(stream.str(),
              "== 0\nout 0\nerr 0\n== 1\nout 1\nerr 1\n== 2\nout 2\nerr 2\n== 3\nout 3\nerr 3\n")
        << jobs << " jobs";
    ASSERT_EQ(outcomes.size(), 4u);
    EXPECT_EQ(outcomes[1].quality->num_quads, 10u);
    EXPECT_EQ(outcomes[3].quality->num_quads, 30u);
    EXPECT_FALSE(outcomes[2].quality);
    EXPECT_EQ(each_exit_code(outcomes), 5);
  }
}

// `finished` sees each region end, one call at a time: every call one region more ended
// than the one before, the others still `not_run`, and the last call every outcome.
TEST(EachJob, EveryRegionsEndIsReportedWithTheOutcomesSoFar) {
  for (const std::size_t jobs : {1, 2, 3}) {
    std::ostringstream stream;
    std::vector<std::vector<RegionOutcome>> calls;
    const auto outcomes = run_regions(
        5, jobs, [](std::size_t) { return std::string(); },
        [](std::size_t k, const Console&) {
          if (k == 1) std::this_thread::sleep_for(std::chrono::milliseconds(200));
          RegionOutcome o;
          o.exit = static_cast<int>(k) + 1;
          return o;
        },
        stream, [&](const std::vector<RegionOutcome>& so_far) { calls.push_back(so_far); });
    ASSERT_EQ(calls.size(), 5u) << jobs << " jobs";
    for (std::size_t c = 0; c < calls.size(); ++c) {
      ASSERT_EQ(calls[c].size(), 5u);
      const auto ended = std::count_if(calls[c].begin(), calls[c].end(),
                                       [](const RegionOutcome& o) { return !o.not_run; });
      EXPECT_EQ(ended, static_cast<long>(c) + 1) << jobs << " jobs, call " << c;
      for (std::size_t k = 0; k < 5; ++k) {
        if (!calls[c][k].not_run) {
          EXPECT_EQ(calls[c][k].exit, static_cast<int>(k) + 1);
        }
      }
    }
    for (std::size_t k = 0; k < 5; ++k) EXPECT_EQ(calls.back()[k].exit, outcomes[k].exit);
    // With more than one thread, region 1 (asleep) ends after those after it.
    if (jobs > 1) {
      EXPECT_TRUE(calls[1][1].not_run) << jobs << " jobs";
    }
  }
}

// Something other than a region's failure (a bug) reaches the caller, once every region
// has run.
TEST(EachJob, AnExceptionFromARegionIsRethrownAfterTheOthers) {
  for (const std::size_t jobs : {1, 2}) {
    std::ostringstream stream;
    std::vector<int> ran(3, 0);
    EXPECT_THROW(run_regions(
                     3, jobs, [](std::size_t) { return std::string(); },
                     [&](std::size_t k, const Console&) {
                       ran[k] = 1;
                       if (k == 0 && jobs > 1) throw std::runtime_error("bug");
                       if (k == 2 && jobs == 1) throw std::runtime_error("bug");
                       return RegionOutcome{};
                     },
                     stream),
                 std::runtime_error);
    EXPECT_EQ(ran, (std::vector<int>{1, 1, 1})) << jobs << " jobs";
  }
}

TEST(EachJob, TheTableHasALinePerRegionPaddedInCharacters) {
  std::vector<RegionOutcome> outcomes(3);
  outcomes[0].quality = QualitySummary{};
  outcomes[0].quality->num_quads = 1234;
  outcomes[0].quality->share_angles_75_105 = 0.9;
  outcomes[0].quality->orientation_mean_deg = 7.3;
  outcomes[0].seconds = 1.5;
  outcomes[1].skipped = true;
  outcomes[2].exit = 3;
  const std::vector<std::string> values = {"Réunion", "b", "cc"};
  const std::string table = format_each_table("name", values, outcomes);
  std::istringstream lines(table);
  std::string line;
  std::vector<std::string> rows;
  while (std::getline(lines, line))
    if (!line.empty()) rows.push_back(line);
  ASSERT_EQ(rows.size(), 4u) << table;
  // "Réunion" is 7 characters (8 bytes): every value padded to 7.
  EXPECT_EQ(rows[0].substr(0, 8), "name    ");
  EXPECT_EQ(rows[1].substr(0, 9), "Réunion ");
  EXPECT_NE(rows[1].find("1234"), std::string::npos);
  EXPECT_NE(rows[1].find("90.0%"), std::string::npos);
  EXPECT_NE(rows[1].find("7.3"), std::string::npos);
  EXPECT_NE(rows[1].find("1.50"), std::string::npos);
  EXPECT_EQ(rows[2], "b        skipped");
  EXPECT_EQ(rows[3], "cc        failed");
  EXPECT_EQ(format_each_total("name", values, outcomes),
            "--each name: 1 of 3 meshed, 1 skipped (every output exists); failed: cc\n");
  EXPECT_EQ(each_exit_code(outcomes), 3);
}

// A usage error that two regions share is the command's: the regions not yet started are
// not run. Usage errors that differ (they name a place) and other failures go on.
TEST(EachJob, TheSameUsageErrorTwiceStopsTheBatch) {
  const std::vector<std::string> values = {"a", "b", "c", "d", "e", "f", "g", "h"};
  std::ostringstream stream;
  auto batch = [&](std::size_t jobs, const std::function<RegionOutcome(std::size_t)>& fail,
                   std::vector<int>& ran) {
    ran.assign(values.size(), 0);
    stream.str("");
    std::mutex mutex;
    return run_regions(
        values.size(), jobs, [](std::size_t k) { return "== " + std::to_string(k) + "\n"; },
        [&](std::size_t k, const Console&) {
          {
            const std::lock_guard<std::mutex> lock(mutex);
            ran[k] = 1;
          }
          return fail(k);
        },
        stream);
  };
  auto usage = [](const std::string& message) {
    RegionOutcome o;
    o.exit = 2;
    o.usage_error = message;
    return o;
  };
  for (const std::size_t jobs : {1, 2, 3}) {
    std::vector<int> ran;
    auto outcomes = batch(
        jobs, [&](std::size_t) { return usage("read: no attribute 'x'"); }, ran);
    const int num_ran = static_cast<int>(std::count(ran.begin(), ran.end(), 1));
    EXPECT_GE(num_ran, 2) << jobs << " jobs";
    EXPECT_LE(num_ran, jobs == 1 ? 2 : 2 + static_cast<int>(jobs)) << jobs << " jobs";
    // One thread's outcomes on any number: a and b failed, the rest not run (those
    // started at once with a and b, failed the same way, counted not run).
    for (std::size_t k = 0; k < values.size(); ++k) EXPECT_EQ(outcomes[k].not_run, k >= 2) << k;
    EXPECT_EQ(each_exit_code(outcomes), 2);
    const std::string total = format_each_total("name", values, outcomes);
    EXPECT_NE(total.find("; failed: a, b"), std::string::npos) << total;
    EXPECT_NE(total.find("6 not run: a and b failed with the same usage error"), std::string::npos)
        << total;
    EXPECT_EQ(stream.str(), "== 0\n== 1\n") << jobs << " jobs";
    // Regions skipped (--skip-existing) after those two: not run either.
    outcomes = batch(
        jobs,
        [&](std::size_t k) {
          if (k < 2) return usage("read: no attribute 'x'");
          RegionOutcome o;
          o.skipped = true;
          return o;
        },
        ran);
    for (std::size_t k = 0; k < values.size(); ++k) EXPECT_EQ(outcomes[k].not_run, k >= 2) << k;
    EXPECT_EQ(stream.str(), "== 0\n== 1\n") << jobs << " jobs";
    EXPECT_NE(format_each_table("name", values, outcomes).find("h     not run\n"),
              std::string::npos);

    // Usage errors that name a place, and the same input error everywhere: all run.
    outcomes = batch(
        jobs, [&](std::size_t k) { return usage("sizing: no size at " + std::to_string(k)); }, ran);
    EXPECT_EQ(std::count(ran.begin(), ran.end(), 1), 8) << jobs << " jobs";
    EXPECT_EQ(format_each_total("name", values, outcomes).find("not run"), std::string::npos);
    outcomes = batch(
        jobs,
        [&](std::size_t) {
          RegionOutcome o;
          o.exit = 3;
          return o;
        },
        ran);
    EXPECT_EQ(std::count(ran.begin(), ran.end(), 1), 8) << jobs << " jobs";
    EXPECT_EQ(each_exit_code(outcomes), 3);
  }
}

// The table as CSV: a row per region, every row as many fields as the header, values and
// errors with commas or quotes quoted (RFC 4180), no seconds.
TEST(EachJob, TheTableAsCsvQuotesWhatNeedsIt) {
  std::vector<RegionOutcome> outcomes(4);
  outcomes[0].quality = QualitySummary{};
  outcomes[0].quality->num_quads = 1234;
  outcomes[0].quality->share_angles_75_105 = 0.9;
  outcomes[0].seconds = 1.5;
  outcomes[1].skipped = true;
  outcomes[2].exit = 3;
  outcomes[2].error = "read: 'a.shp': \"x\", y";
  outcomes[3].not_run = true;
  const std::vector<EachCsvRegion> values = {
      {"Bonaire, Saint Eustatius and Saba", "Bonaire__Saint_Eustatius_and_Saba", false},
      {"b", "b", false},
      {"c\"d", "c_d", false},
      {"NULL", "_", true}};
  const std::string csv = format_each_csv("name", values, outcomes);
  std::vector<std::string> rows;
  for (std::size_t at = 0, next; (next = csv.find("\r\n", at)) != std::string::npos; at = next + 2)
    rows.push_back(csv.substr(at, next - at));
  ASSERT_EQ(rows.size(), 5u) << csv;
  // Fields outside quotes: commas not between an odd number of quotes.
  auto num_fields = [](const std::string& row) {
    std::size_t n = 1;
    bool quoted = false;
    for (char c : row) {
      if (c == '"') quoted = !quoted;
      if (c == ',' && !quoted) ++n;
    }
    return n;
  };
  for (const std::string& row : rows) EXPECT_EQ(num_fields(row), 18u) << row;
  EXPECT_EQ(rows[0].substr(0, 23), "name,file,status,exit,q");
  EXPECT_EQ(rows[1].substr(0, 91),
            "\"Bonaire, Saint Eustatius and Saba\",Bonaire__Saint_Eustatius_and_Saba,meshed,0,1234,"
            "0,90.00");
  EXPECT_EQ(rows[2], "b,b,skipped,0,,,,,,,,,,,,,,");
  EXPECT_EQ(rows[3], "\"c\"\"d\",c_d,failed,3,,,,,,,,,,,,,,\"read: 'a.shp': \"\"x\"\", y\"");
  // The features without a value: an empty value (not the text NULL); not run: no exit.
  EXPECT_EQ(rows[4], ",_,not run,,,,,,,,,,,,,,,");
  EXPECT_EQ(csv.find("1.5"), std::string::npos);  // no seconds
  EXPECT_EQ(format_each_csv("name", values, outcomes, "measured").find("meshed"),
            std::string::npos);
  // A mesh of triangles measured (quality --each on a .slf): its vertices, and no quads'
  // figures rather than zeros, in the CSV and in the table.
  std::vector<RegionOutcome> triangles(1);
  triangles[0].quality = QualitySummary{};
  triangles[0].quality->num_vertices = 321;
  triangles[0].seconds = 0.25;
  const std::string tri_csv = format_each_csv("name", {{"b", "b", false}}, triangles, "measured");
  const std::string row = tri_csv.substr(tri_csv.find("\r\n") + 2);
  EXPECT_EQ(row, "b,b,measured,0,0,321,,,,,,,,,,,,\r\n");
  EXPECT_EQ(num_fields(row.substr(0, row.size() - 2)), 18u);
  const std::string table = format_each_table("name", {"b"}, triangles);
  EXPECT_NE(table.find("b           0        -        -        -        -     0.25"),
            std::string::npos)
      << table;
}

// A resumed batch's figures read back from a region's report: all of them, or none when
// a key is missing or not a number, or the file is not JSON.
TEST(EachJob, ReportFiguresAreReadBackWholeOrNotAtAll) {
  TempDir dir;
  const std::string keys[] = {"num_vertices",
                              "share_angles_75_105",
                              "min_angle_deg",
                              "max_angle_deg",
                              "share_regular_interior",
                              "size_ratio_median",
                              "share_size_ratio_08_125",
                              "orientation_mean_deg",
                              "orientation_p90_deg",
                              "schism_angle_ratio_violations",
                              "schism_aspect_ratio_violations",
                              "dflowfm_orthogonality_violations"};
  std::string quality = "\"num_quads\": 1234";
  for (const std::string& k : keys) quality += ", \"" + k + "\": 0.5";
  write_file(dir.file("whole.json"), "{\"quality\": {" + quality + "}}");
  const std::optional<QualitySummary> q = read_report_quality(dir.file("whole.json"));
  ASSERT_TRUE(q.has_value());
  EXPECT_EQ(q->num_quads, 1234u);
  EXPECT_DOUBLE_EQ(q->orientation_p90_deg, 0.5);
  std::string text = quality;
  text.replace(0, 17, "\"num_quads\": \"many\"");
  write_file(dir.file("text.json"), "{\"quality\": {" + text + "}}");
  EXPECT_FALSE(read_report_quality(dir.file("text.json")).has_value());
  write_file(dir.file("short.json"), "{\"quality\": {\"num_quads\": 1234}}");
  EXPECT_FALSE(read_report_quality(dir.file("short.json")).has_value());
  write_file(dir.file("broken.json"), "not json");
  EXPECT_FALSE(read_report_quality(dir.file("broken.json")).has_value());
}
