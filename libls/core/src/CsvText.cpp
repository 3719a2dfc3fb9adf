#include "lsdem/core/CsvText.h"

#include "lsdem/core/Error.h"

namespace lsdem {

std::string csvField(const std::string& text)
{
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) {
        if (c == '"') quoted += '"';
        quoted += c;
    }
    return quoted + "\"";
}

bool splitCsvRecord(const std::string& line, std::vector<std::string>& fields)
{
    fields.clear();
    std::string field;
    bool quoted = false;
    for (size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c != '"') {
                field += c;
            } else if (i + 1 < line.size() && line[i + 1] == '"') {
                field += '"';
                ++i;
            } else {
                quoted = false;
            }
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            fields.push_back(field);
            field.clear();
        } else {
            field += c;
        }
    }
    fields.push_back(field);
    return !quoted;
}

std::vector<std::vector<std::string>> readCsvRecords(const std::string& text,
                                                      const std::string& where)
{
    std::vector<std::vector<std::string>> records;
    std::string record;
    int line = 0, firstLine = 1;
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::string piece = text.substr(start, end - start);
        if (!piece.empty() && piece.back() == '\r') piece.pop_back();
        ++line;
        if (record.empty()) firstLine = line;
        record += record.empty() && firstLine == line ? piece : "\n" + piece;
        start = end + 1;
        std::vector<std::string> fields;
        if (splitCsvRecord(record, fields)) {
            records.push_back(std::move(fields));
            record.clear();
        }
    }
    if (!record.empty())
        throw Error(where + ":" + std::to_string(firstLine), "a quoted field is never closed",
                    "close it with a double quote (write a quote inside a field as \"\")");
    return records;
}

} // namespace lsdem
