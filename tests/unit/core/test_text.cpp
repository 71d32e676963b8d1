// Text helpers (core/text.h) and JSON strings (core/json_writer.h): what is not UTF-8
// (a .dbf in Latin-1 without its .cpg) becomes UTF-8, read as Windows-1252.
#include "core/text.h"

#include <gtest/gtest.h>

#include "core/json_writer.h"

namespace isoquad {
namespace {

TEST(Text, ValidUtf8IsKeptAndOtherBytesAreReadAsWindows1252) {
  // UTF-8 as it is, whatever its length (é, 日, an emoji).
  const std::string utf8 = "Île-de-France \xe6\x97\xa5 \xf0\x9f\x8c\x8a";
  EXPECT_TRUE(is_utf8(utf8));
  EXPECT_EQ(utf8_or_cp1252(utf8), utf8);
  // Latin-1's Î (0xCE) and ç (0xE7); Windows-1252's euro sign (0x80) and œ (0x9C); an
  // unassigned byte (0x81) as U+FFFD; a truncated sequence and a surrogate byte by byte.
  EXPECT_FALSE(
      is_utf8("\xce"
              "le"));
  EXPECT_EQ(utf8_or_cp1252("\xce"
                           "le Cura\xe7"
                           "ao"),
            "Île Curaçao");
  EXPECT_EQ(utf8_or_cp1252("\x80 \x9c \x81"), "€ œ \xef\xbf\xbd");
  EXPECT_EQ(utf8_or_cp1252("a\xc3"), "aÃ");
  EXPECT_EQ(utf8_or_cp1252("\xed\xa0\x80"), "í\xc2\xa0\xe2\x82\xac");
  // Valid and invalid in one string: the valid sequences untouched.
  EXPECT_EQ(utf8_or_cp1252("\xc3\xa9\xe9"), "éé");
  for (const std::string s : {"\xce", "\x80\x81\x9f", "\xed\xa0\x80", "a\xf4\x90\x80\x80"})
    EXPECT_TRUE(is_utf8(utf8_or_cp1252(s))) << s;
}

TEST(Text, JsonStringsAreUtf8) {
  JsonWriter json;
  json.begin_object();
  json.value("name", std::string("\xce"
                                 "le \"x\""));
  json.end_object();
  EXPECT_NE(json.str().find("\"name\": \"Île \\\"x\\\"\""), std::string::npos) << json.str();
  EXPECT_TRUE(is_utf8(json.str()));
}

}  // namespace
}  // namespace isoquad
