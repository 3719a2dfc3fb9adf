// A membrane's vertices as CSV (MembraneStateCsv.h).
#include "lsdem/scene/MembraneStateCsv.h"

#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/CsvText.h"
#include "lsdem/core/Error.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace lsdem {

namespace {

const char* const kColumns[] = {"x", "y", "z", "vx", "vy", "vz"};

} // namespace

std::string membraneStateCsvText(const Membrane& m)
{
    std::string text = "x,y,z,vx,vy,vz\n";
    char line[256];
    for (size_t i = 0; i < m.positions.size(); ++i) {
        const Vec3 &x = m.positions[i], &v = m.velocities[i];
        std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", x.x(), x.y(),
                      x.z(), v.x(), v.y(), v.z());
        text += line;
    }
    return text;
}

void writeMembraneStateCsv(const Membrane& m, const std::string& path)
{
    writeTextFileAtomically(path, membraneStateCsvText(m));
}

void readMembraneStateCsv(const std::string& path, Membrane& m)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw Error(path, "cannot read the membrane's state file",
                    "check the path (relative to the scene's folder) and its permissions");
    std::stringstream buffer;
    buffer << in.rdbuf();
    std::vector<std::vector<std::string>> records = readCsvRecords(buffer.str(), path);
    // (blank lines, e.g. a trailing one, hold no vertex)
    std::vector<size_t> lineOf;  // each record's line in the file (records are one line each)
    {
        std::vector<std::vector<std::string>> kept;
        for (size_t r = 0; r < records.size(); ++r) {
            if (records[r].size() == 1 && records[r][0].find_first_not_of(" \t\r") == std::string::npos)
                continue;
            kept.push_back(std::move(records[r]));
            lineOf.push_back(r);
        }
        records = std::move(kept);
    }
    const auto at = [&](size_t record) {
        return path + ":" + std::to_string((record < lineOf.size() ? lineOf[record] : 0) + 1);
    };
    if (records.empty() || records[0] != std::vector<std::string>(std::begin(kColumns), std::end(kColumns)))
        throw Error(at(0), "the header is not x,y,z,vx,vy,vz",
                    "write a header x,y,z,vx,vy,vz and a row per vertex of the membrane");
    const size_t vertices = m.positions.size();
    if (records.size() - 1 != vertices)
        throw Error(records.size() - 1 > vertices ? at(vertices + 1) : at(records.size() - 1),
                    "has " + std::to_string(records.size() - 1) + " rows for a membrane of " +
                              std::to_string(vertices) + " vertices",
                    "write a row per vertex, in the order its shape makes them (a tube: ring "
                    "by ring from its base), or change segments and rings to the file's");
    std::vector<Vec3> positions(vertices), velocities(vertices);
    for (size_t r = 1; r < records.size(); ++r) {
        const std::vector<std::string>& fields = records[r];
        if (fields.size() != 6)
            throw Error(at(r), "has " + std::to_string(fields.size()) + " fields, not 6",
                        "write x, y, z, vx, vy, vz");
        double value[6];
        for (int k = 0; k < 6; ++k) {
            const std::string& s = fields[size_t(k)];
            const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value[k]);
            if (s.empty() || ec != std::errc() || ptr != s.data() + s.size() ||
                !std::isfinite(value[k]))
                throw Error(at(r), std::string("column '") + kColumns[k] + "': '" + s +
                                       "' is not a finite number",
                            "write a decimal number, e.g. 1.5e-3");
        }
        positions[r - 1] = Vec3(value[0], value[1], value[2]);
        velocities[r - 1] = Vec3(value[3], value[4], value[5]);
    }
    m.positions = std::move(positions);
    m.velocities = std::move(velocities);
}

} // namespace lsdem
