// CSV fields as RFC 4180 writes them: quoted only when needed, quotes doubled, and read back
// exactly, including line breaks inside a field; an unclosed quote is an error with its line.
#include "lsdem/core/CsvText.h"

#include "lsdem/core/Error.h"

#include <gtest/gtest.h>

using namespace lsdem;

TEST(CsvText, FieldsAreQuotedOnlyWhenNeeded)
{
    EXPECT_EQ(csvField("grain_1"), "grain_1");
    EXPECT_EQ(csvField(""), "");
    EXPECT_EQ(csvField("a,b"), "\"a,b\"");
    EXPECT_EQ(csvField("say \"hi\""), "\"say \"\"hi\"\"\"");
    EXPECT_EQ(csvField("two\nlines"), "\"two\nlines\"");
}

TEST(CsvText, WrittenFieldsReadBackExactly)
{
    const std::vector<std::string> fields = {"plain", "", "a,b", "\"quoted\"", "x\ny", " space "};
    std::string text;
    for (int row = 0; row < 2; ++row) {
        for (size_t i = 0; i < fields.size(); ++i) text += (i ? "," : "") + csvField(fields[i]);
        text += row == 0 ? "\r\n" : "\n";
    }
    const auto records = readCsvRecords(text, "test.csv");
    ASSERT_EQ(records.size(), 2u);
    EXPECT_EQ(records[0], fields);
    EXPECT_EQ(records[1], fields);
}

TEST(CsvText, AnUnclosedQuoteNamesItsLine)
{
    try {
        readCsvRecords("a,b\n\"open,c\nd\n", "grains.csv");
        FAIL() << "an unclosed quote was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("grains.csv:2"), std::string::npos) << e.what();
    }
}
