// The Table type (io/table.hpp): Markdown, aligned text and CSV renderings.
#include <gtest/gtest.h>

#include <stdexcept>

#include "io/table.hpp"

namespace contact2d {
namespace {

Table sample() {
  Table t{{"scene", "max pos (m)", "note"}, {}};
  add_row(t, {"box", "0.0123", ""});
  add_row(t, {"μ-disc", "1e-05", "a, \"b\" | c"});
  return t;
}

TEST(Table, Markdown) {
  EXPECT_EQ(to_markdown(sample()),
            "| scene | max pos (m) | note |\n"
            "|---|---|---|\n"
            "| box | 0.0123 |  |\n"
            "| μ-disc | 1e-05 | a, \"b\" \\| c |\n");
}

TEST(Table, MarkdownKeepsAnEscapedPipeAndJoinsLines) {
  Table t{{"a"}, {}};
  add_row(t, {"x \\| y\nz"});
  EXPECT_EQ(to_markdown(t), "| a |\n|---|\n| x \\| y z |\n");
}

TEST(Table, AlignedTextCountsCharactersNotBytes) {
  EXPECT_EQ(to_text(sample()),
            "scene   max pos (m)  note\n"
            "box     0.0123\n"
            "μ-disc  1e-05        a, \"b\" | c\n");
}

TEST(Table, CsvQuotesOnlyWhatNeedsIt) {
  EXPECT_EQ(to_csv(sample()),
            "scene,max pos (m),note\n"
            "box,0.0123,\n"
            "μ-disc,1e-05,\"a, \"\"b\"\" | c\"\n");
}

TEST(Table, RowOfTheWrongWidthIsRefused) {
  Table t{{"a", "b"}, {}};
  EXPECT_THROW(add_row(t, {"1"}), std::invalid_argument);
  EXPECT_THROW(add_row(t, {"1", "2", "3"}), std::invalid_argument);
  EXPECT_TRUE(t.rows.empty());
}

TEST(Table, EmptyTableIsItsHeader) {
  const Table t{{"a", "b"}, {}};
  EXPECT_EQ(to_markdown(t), "| a | b |\n|---|---|\n");
  EXPECT_EQ(to_csv(t), "a,b\n");
  EXPECT_EQ(to_text(t), "a  b\n");
}

// An empty last cell leaves no trailing blanks on its line.
TEST(Table, TextLinesEndWithoutBlanks) {
  Table t{{"a", "note"}, {}};
  add_row(t, {"long value", ""});
  EXPECT_EQ(to_text(t), "a           note\nlong value\n");
}

}  // namespace
}  // namespace contact2d
