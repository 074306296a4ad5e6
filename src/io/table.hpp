// One table type for every table the project writes as text: named columns,
// rows of cells (already formatted text), rendered as
//   - Markdown:   "| a | b |" lines under a "|---|---|" rule; a '|' inside a
//                 cell is escaped as "\|" so a cell never splits;
//   - aligned text: columns padded to their widest cell (a UTF-8 sequence
//                 counts as one character), two spaces apart;
//   - CSV:        a header of the column names, then the rows; a cell with a
//                 comma, quote or newline is quoted (RFC 4180).
// Plain data and free functions; add_row refuses a row of the wrong width.
#pragma once

#include <string>
#include <vector>

namespace contact2d {

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
};

// Appends a row; throws std::invalid_argument when its width is not the
// number of columns.
void add_row(Table& table, std::vector<std::string> cells);

std::string to_markdown(const Table& table);
std::string to_text(const Table& table);
std::string to_csv(const Table& table);

}  // namespace contact2d
