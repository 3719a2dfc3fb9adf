/// @file VtuReader.h
/// @brief A small reader of the ParaView files VtkSeries writes, independent of its code, for
///        the run tests: a `.vtu` (header, DataArray tags, raw appended block of UInt64 byte
///        counts and values; its structure checked as it is read) and a `.pvd`'s DataSets.
#pragma once

#include "lsdem/core/Vec3.h"

#include "support/TestSupport.h"  // readFile

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

namespace lsdem::test {

/// The attributes of one XML tag's text, e.g. `type="Int32" Name="grain"`.
inline std::map<std::string, std::string> attributesOf(const std::string& tag)
{
    static const std::regex attribute(R"__((\w+)="([^"]*)")__");
    std::map<std::string, std::string> out;
    for (auto it = std::sregex_iterator(tag.begin(), tag.end(), attribute);
         it != std::sregex_iterator(); ++it)
        out[(*it)[1]] = (*it)[2];
    return out;
}

/// Little-endian unsigned integer of @a size bytes at @a at in @a bytes.
inline std::uint64_t readLittleEndian(const std::string& bytes, size_t at, size_t size)
{
    if (at + size > bytes.size()) throw std::runtime_error("appended data ends early");
    std::uint64_t v = 0;
    for (size_t i = 0; i < size; ++i)
        v |= std::uint64_t(static_cast<unsigned char>(bytes[at + i])) << (8 * i);
    return v;
}

struct ParsedArray
{
    std::string type;
    int components = 1;
    std::vector<double> reals;       ///< Float64 arrays
    std::vector<std::int64_t> ints;  ///< Int32, Int64, UInt8 arrays
};

struct ParsedGrid
{
    size_t points = 0, cells = 0;
    /// Keyed "Section/Name", e.g. "PointData/velocity", "Points/Points", "Cells/types".
    std::map<std::string, ParsedArray> arrays;

    const ParsedArray& at(const std::string& key) const
    {
        const auto it = arrays.find(key);
        if (it == arrays.end()) throw std::runtime_error("no array " + key);
        return it->second;
    }
    Vec3 vec3(const std::string& key, size_t i) const
    {
        const ParsedArray& a = at(key);
        return {a.reals.at(3 * i), a.reals.at(3 * i + 1), a.reals.at(3 * i + 2)};
    }
};

/// Read a .vtu written with raw appended data and UInt64 headers, checking its structure.
inline ParsedGrid parseVtu(const std::string& path)
{
    const std::string text = readFile(path);
    if (text.find("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
                  "header_type=\"UInt64\">") == std::string::npos)
        throw std::runtime_error("not a little-endian UInt64 UnstructuredGrid file");
    const size_t appended = text.find("<AppendedData encoding=\"raw\">");
    if (appended == std::string::npos) throw std::runtime_error("no raw AppendedData");
    const size_t underscore = text.find('_', appended);
    if (underscore == std::string::npos) throw std::runtime_error("no '_' opening the data");
    const size_t dataStart = underscore + 1;
    const std::string xml = text.substr(0, appended);

    ParsedGrid grid;
    static const std::regex piece(R"(<Piece ([^>]*)>)");
    std::smatch match;
    if (!std::regex_search(xml, match, piece)) throw std::runtime_error("no Piece");
    const auto pieceAttributes = attributesOf(match[1]);
    grid.points = std::stoul(pieceAttributes.at("NumberOfPoints"));
    grid.cells = std::stoul(pieceAttributes.at("NumberOfCells"));

    size_t dataEnd = dataStart;
    static const std::regex dataArray(R"(<DataArray ([^>]*)/>)");
    for (auto it = std::sregex_iterator(xml.begin(), xml.end(), dataArray);
         it != std::sregex_iterator(); ++it) {
        // The section is the nearest opening tag before this array.
        const std::string before = xml.substr(0, static_cast<size_t>(it->position()));
        std::string section;
        size_t sectionAt = 0;
        for (const char* name : {"PointData", "CellData", "Points", "Cells"}) {
            const size_t p = before.rfind(std::string("<") + name + " ");
            const size_t q = before.rfind(std::string("<") + name + ">");
            const size_t found = p == std::string::npos ? q : (q == std::string::npos ? p : std::max(p, q));
            if (found != std::string::npos && (section.empty() || found > sectionAt))
                section = name, sectionAt = found;
        }
        const auto attributes = attributesOf((*it)[1]);
        if (attributes.at("format") != "appended") throw std::runtime_error("not appended");
        ParsedArray array;
        array.type = attributes.at("type");
        array.components = std::stoi(attributes.at("NumberOfComponents"));
        const size_t at = dataStart + std::stoull(attributes.at("offset"));
        const size_t bytes = readLittleEndian(text, at, 8);
        const size_t width = array.type == "Float64" || array.type == "Int64" ? 8
                             : array.type == "Int32"                         ? 4
                             : array.type == "UInt8"                         ? 1
                                                                             : 0;
        if (width == 0 || bytes % width != 0) throw std::runtime_error("bad array " + array.type);
        for (size_t i = 0; i < bytes / width; ++i) {
            const std::uint64_t raw = readLittleEndian(text, at + 8 + i * width, width);
            if (array.type == "Float64") {
                double d;
                std::memcpy(&d, &raw, sizeof d);
                array.reals.push_back(d);
            } else if (array.type == "Int32") {
                array.ints.push_back(static_cast<std::int32_t>(static_cast<std::uint32_t>(raw)));
            } else {
                array.ints.push_back(static_cast<std::int64_t>(raw));
            }
        }
        dataEnd = std::max(dataEnd, at + 8 + bytes);
        grid.arrays[section + "/" + attributes.at("Name")] = array;
    }
    // The block holds exactly the arrays, then closes.
    const size_t close = text.find_first_not_of(" \n", dataEnd);
    if (close == std::string::npos || text.compare(close, 16, "</AppendedData>\n") != 0)
        throw std::runtime_error("appended data does not end where the arrays do");
    return grid;
}

/// One `<DataSet>` of a .pvd: a frame's time, its part and its file.
struct DataSetEntry
{
    double time = 0.0;
    int part = -1;
    std::string file;
};

inline std::vector<DataSetEntry> parsePvd(const std::string& path)
{
    const std::string text = readFile(path);
    if (text.find("<VTKFile type=\"Collection\"") == std::string::npos)
        throw std::runtime_error(path + " is not a VTK collection");
    static const std::regex dataSet(R"(<DataSet ([^>]*)/>)");
    std::vector<DataSetEntry> out;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), dataSet);
         it != std::sregex_iterator(); ++it) {
        const auto a = attributesOf((*it)[1]);
        out.push_back({std::strtod(a.at("timestep").c_str(), nullptr), std::stoi(a.at("part")),
                       a.at("file")});
    }
    return out;
}

} // namespace lsdem::test
