#include "app/command_record.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/test_support.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

const std::map<std::string, OptionShape> kValues = {{"--hmax", {"--hmax", 1}},
                                                    {"--where", {"--where", 1}},
                                                    {"-o", {"-o", 1}},
                                                    {"--output", {"-o", 1}},
                                                    {"--report", {"--report", 1}},
                                                    {"--repair", {"--repair", 0}},
                                                    {"--layer", {"--layer", 1}},
                                                    {"--open-groups", {"--open-groups", 1 << 29}}};

}  // namespace

// Arguments quoted for a shell where they need it, and split back as they were.
TEST(CommandRecord, ShellWordsReadBackTheQuotedArguments) {
  const std::vector<std::string> args = {"isoquad", "a b.shp",     "name = 'x'",
                                         "",        "--hmax=5000", "it's"};
  std::string line;
  for (const std::string& a : args) line += (line.empty() ? "" : " ") + shell_quoted(a);
  EXPECT_EQ(line, "isoquad 'a b.shp' 'name = '\\''x'\\''' '' --hmax=5000 'it'\\''s'");
  EXPECT_EQ(shell_words(line), args);
}

// The options compared as a set: order, --opt=value and a number's spelling do not
// count; a value changed, an option left out or added are each said once.
TEST(CommandRecord, DifferencesAreTheOptionsNotTheirOrder) {
  const std::string base = "isoquad mesh in.shp --hmax 5000 --repair -o a.gpkg -o b.gr3";
  EXPECT_EQ(command_difference(base, base, kValues), "");
  EXPECT_EQ(command_difference(base, "isoquad mesh --repair in.shp -o b.gr3 --hmax=5e3 -o a.gpkg",
                               kValues),
            "");
  EXPECT_EQ(command_difference(base, "isoquad mesh in.shp --hmax 4000 --repair -o a.gpkg -o b.gr3",
                               kValues),
            "it had --hmax 5000 where this command has --hmax 4000");
  EXPECT_EQ(command_difference(base, "isoquad mesh in.shp --hmax 5000 -o a.gpkg -o b.gr3 --layer x",
                               kValues),
            "it had --repair, which this command leaves out; this command adds --layer x");
  // An option's other names, -ovalue, and INPUT after "--": the same command.
  EXPECT_EQ(
      command_difference(
          base, "isoquad mesh --hmax 5000 --repair --output a.gpkg -ob.gr3 -- in.shp", kValues),
      "");
  // A value given with '=' is its option's, a flag's too.
  EXPECT_EQ(command_difference(base, base + " --repair=false", kValues),
            "this command adds --repair=false");
  // A flag before INPUT takes no value: INPUT is compared as itself.
  EXPECT_EQ(
      command_difference("isoquad mesh --repair in.shp", "isoquad mesh --repair out.shp", kValues),
      "it had in.shp where this command has out.shp");
  // Values of an option taken several times, as a set too.
  EXPECT_EQ(command_difference("isoquad quality --open-groups a b",
                               "isoquad quality --open-groups b a", kValues),
            "it had --open-groups a b where this command has --open-groups b a");
  // Ignored options, and a region's selection compared whole.
  EXPECT_EQ(
      command_difference(base + " --where 'name IN ('\\''A'\\'')' [--each: name = 'A']",
                         base + " --where 'name IN ('\\''A'\\'','\\''B'\\'')' [--each: name = 'A']",
                         kValues, {"--where"}),
      "");
  EXPECT_EQ(
      command_difference(base + " [--each: name = 'A']", base + " [--each: name = 'B']", kValues),
      "its region was [--each: name = 'A'], this command's [--each: name = 'B']");
  // More than three differences: the first three, and a count.
  EXPECT_EQ(command_difference("isoquad mesh a --hmax 1 --layer l --report r.json --repair",
                               "isoquad mesh b --hmax 2 --layer m", kValues),
            "it had a where this command has b; it had --hmax 1 where this command has --hmax 2; "
            "it had --layer l where this command has --layer m; and 2 more");
}
