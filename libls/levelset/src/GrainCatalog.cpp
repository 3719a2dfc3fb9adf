#include "lsdem/ls/GrainCatalog.h"

#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Constants.h"
#include "lsdem/core/CsvText.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

namespace lsdem {

namespace {

/// How each column is written and read: text columns and numeric ones.
struct Column
{
    std::string name;
    std::function<std::string(const CatalogEntry&)> write;
    std::function<void(CatalogEntry&, double)> setNumber;           // numeric columns
    std::function<void(CatalogEntry&, const std::string&)> setText;  // text columns
};

const std::vector<Column>& columns()
{
    using E = CatalogEntry;
    auto text = [](const char* name, std::string E::*field) {
        return Column{name, [field](const E& e) { return csvField(e.*field); }, nullptr,
                      [field](E& e, const std::string& v) { e.*field = v; }};
    };
    auto measure = [](const char* name, double GrainMeasures::*field) {
        return Column{name, [field](const E& e) { return numberText(e.measures.*field); },
                      [field](E& e, double v) { e.measures.*field = v; }, nullptr};
    };
    auto number = [](const char* name, double E::*field) {
        return Column{name, [field](const E& e) { return numberText(e.*field); },
                      [field](E& e, double v) { e.*field = v; }, nullptr};
    };
    static const std::vector<Column> all = {
        text("name", &E::name),
        text("asset", &E::asset),
        text("source", &E::source),
        text("source_sha256", &E::sourceSha256),
        text("bake_options", &E::bakeOptions),
        measure("volume", &GrainMeasures::volume),
        measure("surface_area", &GrainMeasures::surfaceArea),
        measure("equivalent_diameter", &GrainMeasures::equivalentDiameter),
        measure("length_long", &GrainMeasures::lengthLong),
        measure("length_intermediate", &GrainMeasures::lengthIntermediate),
        measure("length_short", &GrainMeasures::lengthShort),
        measure("elongation", &GrainMeasures::elongation),
        measure("flatness", &GrainMeasures::flatness),
        measure("sphericity", &GrainMeasures::sphericity),
        Column{"nodes", [](const E& e) { return std::to_string(e.nodes); },
               [](E& e, double v) { e.nodes = static_cast<long long>(v); }, nullptr},
        number("vdp", &E::vdp),
        number("sdp", &E::sdp),
        number("bake_seconds", &E::bakeSeconds),
    };
    return all;
}

/// @a text as a finite number (the whole text), or Error at @a where.
double parseFinite(const std::string& text, const std::string& where, const std::string& column)
{
    double v = 0.0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, v);
    if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(v))
        throw Error(where, "column '" + column + "': '" + text + "' is not a finite number",
                    "fix the value, or bake the set again with lsdem-bake --out-dir");
    return v;
}

} // namespace

GrainMeasures measureGrain(const GrainAsset& asset)
{
    GrainMeasures m;
    m.volume = asset.mass.volume;
    m.surfaceArea = asset.nodes.totalArea();
    m.equivalentDiameter = std::cbrt(6.0 * m.volume / kPi);
    Vec3 lo = Vec3::Constant(HUGE_VAL), hi = Vec3::Constant(-HUGE_VAL);
    for (const Vec3& p : asset.nodes.positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    Vec3 extent = asset.nodes.size() ? Vec3(hi - lo) : Vec3::Zero();
    std::sort(extent.data(), extent.data() + 3, std::greater<double>());
    m.lengthLong = extent[0];
    m.lengthIntermediate = extent[1];
    m.lengthShort = extent[2];
    m.elongation = extent[0] > 0.0 ? extent[1] / extent[0] : 0.0;
    m.flatness = extent[1] > 0.0 ? extent[2] / extent[1] : 0.0;
    m.sphericity = m.surfaceArea > 0.0
                       ? kPi * m.equivalentDiameter * m.equivalentDiameter / m.surfaceArea
                       : 0.0;
    return m;
}

CatalogEntry catalogEntry(const GrainAsset& asset, const std::string& name,
                          const std::string& assetFile, const std::string& bakeOptions,
                          double bakeSeconds)
{
    CatalogEntry e;
    e.name = name;
    e.asset = assetFile;
    e.source = asset.provenance.source;
    e.sourceSha256 = asset.provenance.sourceSha256;
    e.bakeOptions = bakeOptions;
    e.measures = measureGrain(asset);
    e.nodes = static_cast<long long>(asset.nodes.size());
    e.vdp = asset.voxelSize;
    e.sdp = asset.spacing.mean;
    e.bakeSeconds = bakeSeconds;
    return e;
}

const std::vector<std::string>& catalogColumns()
{
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n;
        for (const Column& c : columns()) n.push_back(c.name);
        return n;
    }();
    return names;
}

void writeCatalog(const std::string& path, const std::vector<CatalogEntry>& entries)
{
    std::ostringstream out;
    const char* separator = "";
    for (const Column& c : columns()) out << separator << c.name, separator = ",";
    out << "\n";
    for (const CatalogEntry& e : entries) {
        separator = "";
        for (const Column& c : columns()) out << separator << c.write(e), separator = ",";
        out << "\n";
    }
    writeTextFileAtomically(path, out.str());
}

std::vector<CatalogEntry> readCatalog(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw Error(path, "cannot read the catalogue",
                    "check the path; lsdem-bake --out-dir DIR writes DIR/catalog.csv");
    std::ostringstream text;
    text << in.rdbuf();
    std::string content = text.str();
    const std::string byteOrderMark = "\xEF\xBB\xBF";  // Excel starts UTF-8 CSV with it
    if (content.compare(0, byteOrderMark.size(), byteOrderMark) == 0)
        content.erase(0, byteOrderMark.size());
    const auto records = readCsvRecords(content, path);
    if (records.empty())
        throw Error(path, "the catalogue is empty (no header)",
                    "bake the set with lsdem-bake --out-dir, or write a header 'name,asset'");
    const std::vector<std::string>& header = records[0];
    std::map<std::string, size_t> position;  // column name -> field index
    for (size_t k = 0; k < header.size(); ++k) {
        if (!position.emplace(header[k], k).second)
            throw Error(path + ":1", "column '" + header[k] + "' appears twice",
                        "keep one of them");
    }
    for (const char* required : {"name", "asset"})
        if (!position.count(required))
            throw Error(path + ":1", "the catalogue has no column '" + std::string(required) + "'",
                        "the header must name at least 'name' and 'asset' (the .vdb file, "
                        "relative to the catalogue's folder)");

    std::vector<CatalogEntry> entries;
    std::map<std::string, size_t> rowOfName;
    for (size_t r = 1; r < records.size(); ++r) {
        const auto& fields = records[r];
        // The record number is the line number unless a quoted field spans lines.
        const std::string where = path + ":" + std::to_string(r + 1);
        if (fields.size() == 1 && fields[0].empty()) continue;  // a blank line
        if (fields.size() != header.size())
            throw Error(where,
                        "has " + std::to_string(fields.size()) + " fields, the header " +
                            std::to_string(header.size()),
                        "give every row one value per column (quote values holding commas)");
        CatalogEntry e;
        for (const Column& c : columns()) {
            const auto found = position.find(c.name);
            if (found == position.end()) continue;
            const std::string& value = fields[found->second];
            if (c.setText) {
                c.setText(e, value);
                continue;
            }
            const double number = parseFinite(value, where, c.name);
            if (c.name == "nodes" && !(number >= 0.0 && number == std::floor(number)))
                throw Error(where, "column 'nodes': '" + value + "' is not a whole count",
                            "fix the value, or bake the set again with lsdem-bake --out-dir");
            c.setNumber(e, number);
        }
        if (e.name.empty())
            throw Error(where, "column 'name' is empty", "give every asset a name");
        if (e.asset.empty())
            throw Error(where, "column 'asset' is empty for '" + e.name + "'",
                        "give the .vdb file of every asset");
        if (!rowOfName.emplace(e.name, r + 1).second)
            throw Error(where, "a second asset named '" + e.name + "'",
                        "the first is on line " + std::to_string(rowOfName[e.name]) +
                            "; give assets distinct names");
        entries.push_back(std::move(e));
    }
    return entries;
}

} // namespace lsdem
