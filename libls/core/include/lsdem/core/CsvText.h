/// @file CsvText.h
/// @brief Comma-separated text as RFC 4180 has it: a field that holds a comma, a quote or a line
///        break is quoted, its quotes doubled; the reader undoes exactly that. Used for every
///        CSV file lsdem writes or reads, so a name like `left,top` keeps its column.
#pragma once

#include <string>
#include <vector>

namespace lsdem {

/// @a text as one CSV field (quoted only when it has to be).
std::string csvField(const std::string& text);

/// The fields of one CSV record. @a line must hold the whole record (a quoted field may
/// contain line breaks, so a record can span lines: see readCsvRecords).
/// @return false if a quoted field is not closed.
bool splitCsvRecord(const std::string& line, std::vector<std::string>& fields);

/// Every record of @a text (trailing line breaks and '\r' before them ignored).
/// @throw Error naming @a where and the line if a quoted field is not closed.
std::vector<std::vector<std::string>> readCsvRecords(const std::string& text,
                                                      const std::string& where);

} // namespace lsdem
