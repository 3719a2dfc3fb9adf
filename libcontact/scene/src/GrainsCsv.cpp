#include "lsdem/scene/GrainsCsv.h"

#include "lsdem/scene/EntryRules.h"

#include "SceneSections.h"

#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/CsvText.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"

#include <charconv>
#include <cmath>
#include <map>
#include <sstream>

namespace lsdem {

namespace {

const char* const kRequired[] = {"asset", "x", "y", "z", "qw", "qx", "qy", "qz"};
const char* const kOptional[] = {"name", "material", "vx", "vy", "vz", "wx", "wy", "wz"};

std::string listOf(const std::vector<std::string>& names)
{
    std::string s;
    for (const std::string& n : names) s += (s.empty() ? "'" : ", '") + n + "'";
    return s;
}

template <typename Spec>
int findByName(const std::vector<Spec>& specs, const std::string& name)
{
    for (size_t i = 0; i < specs.size(); ++i)
        if (specs[i].name == name) return static_cast<int>(i);
    return -1;
}

template <typename Spec>
std::vector<std::string> namesOf(const std::vector<Spec>& specs)
{
    std::vector<std::string> names;
    for (const Spec& s : specs) names.push_back(s.name);
    return names;
}

/// One data row being read: its fields by column name, with messages naming the line.
class Row
{
public:
    Row(const std::vector<std::string>& fields, const std::map<std::string, size_t>& columns,
        std::string where)
        : mFields(fields), mColumns(columns), mWhere(std::move(where))
    {
    }
    bool has(const std::string& column) const { return mColumns.count(column) > 0; }
    const std::string& text(const std::string& column) const
    {
        return mFields[mColumns.at(column)];
    }
    double number(const std::string& column) const
    {
        std::string s = text(column);
        const size_t begin = s.find_first_not_of(" \t"), end = s.find_last_not_of(" \t");
        s = begin == std::string::npos ? "" : s.substr(begin, end - begin + 1);
        double v = 0.0;
        const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        if (s.empty() || ec != std::errc() || ptr != s.data() + s.size())
            fail(column, "'" + s + "' is not a number", "write a decimal number, e.g. 1.5e-3");
        if (!std::isfinite(v))
            fail(column, "is not finite (" + s + ")", "give a finite number");
        return v;
    }
    Vec3 vec3(const std::string& a, const std::string& b, const std::string& c) const
    {
        return Vec3(has(a) ? number(a) : 0.0, has(b) ? number(b) : 0.0, has(c) ? number(c) : 0.0);
    }
    [[noreturn]] void fail(const std::string& column, const std::string& problem,
                           const std::string& fix) const
    {
        throw Error(mWhere, "column '" + column + "': " + problem, fix);
    }
    const std::string& where() const { return mWhere; }

private:
    const std::vector<std::string>& mFields;
    const std::map<std::string, size_t>& mColumns;
    std::string mWhere;
};

} // namespace

void readGrainsCsv(const std::string& text, const std::string& path, int material, Scene& scene)
{
    std::istringstream in(text);
    std::string line;
    int lineNumber = 0;
    std::map<std::string, size_t> columns;
    std::vector<std::string> fields;
    auto where = [&] { return path + ":" + std::to_string(lineNumber); };
    // The header: the first line that is not empty.
    while (columns.empty() && std::getline(in, line)) {
        ++lineNumber;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.find_first_not_of(" \t") == std::string::npos) continue;
        if (!splitCsvRecord(line, fields))
            throw Error(where(), "a quoted column name is not closed", "close the quote");
        for (size_t k = 0; k < fields.size(); ++k) {
            const std::string& name = fields[k];
            bool known = false;
            for (const char* c : kRequired) known = known || name == c;
            for (const char* c : kOptional) known = known || name == c;
            if (!known)
                throw Error(where(), "unknown column '" + name + "'",
                            "the columns are asset, x, y, z, qw, qx, qy, qz and optionally "
                            "name, material, vx, vy, vz, wx, wy, wz");
            if (!columns.emplace(name, k).second)
                throw Error(where(), "column '" + name + "' appears twice", "keep one");
        }
        for (const char* c : kRequired)
            if (!columns.count(c))
                throw Error(where(), std::string("missing column '") + c + "'",
                            "the header needs asset, x, y, z, qw, qx, qy, qz");
    }
    if (columns.empty())
        throw Error(path + ":1", "no header row (the file is empty)",
                    "write a header asset,x,y,z,qw,qx,qy,qz and a row per grain");
    while (std::getline(in, line)) {
        ++lineNumber;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.find_first_not_of(" \t") == std::string::npos) continue;
        if (!splitCsvRecord(line, fields))
            throw Error(where(), "a quoted field is not closed", "close the quote");
        if (fields.size() != columns.size())
            throw Error(where(),
                        "has " + std::to_string(fields.size()) + " fields, the header " +
                            std::to_string(columns.size()),
                        "give every row one value per column");
        if (static_cast<long long>(scene.grains.size()) >= scenefile::kMaxSceneGrains)
            throw Error(where(), "is one grain more than the limit of " +
                                     std::to_string(scenefile::kMaxSceneGrains), "split the scene");
        const Row row(fields, columns, where());
        GrainSpec g;
        g.where = where();
        if (row.has("name")) g.name = row.text("name");
        g.asset = findByName(scene.assets, row.text("asset"));
        if (g.asset < 0)
            row.fail("asset", "no asset named '" + row.text("asset") + "'",
                     "use one of " + listOf(namesOf(scene.assets)) +
                         ", or define it in an [assets.NAME] table");
        g.material = material;
        if (row.has("material")) {
            g.material = findByName(scene.materials, row.text("material"));
            if (g.material < 0)
                row.fail("material", "no material named '" + row.text("material") + "'",
                         "use one of " + listOf(namesOf(scene.materials)));
        }
        g.pose.position = row.vec3("x", "y", "z");
        const Quat q(row.number("qw"), row.number("qx"), row.number("qy"), row.number("qz"));
        if (std::optional<std::string> p = orientationProblem(q, kTableOrientationTolerance))
            row.fail("qw", "the quaternion (qw, qx, qy, qz) " + *p, kOrientationFix);
        g.pose.orientation = unitQuaternion(q);
        g.velocity = row.vec3("vx", "vy", "vz");
        g.angularVelocity = row.vec3("wx", "wy", "wz");
        scene.grains.push_back(g);
    }
}

std::string grainsCsvText(const Scene& scene, size_t first, size_t count)
{
    bool named = false, moving = false, spinning = false, ownMaterial = false;
    for (size_t i = first; i < first + count; ++i) {
        const GrainSpec& g = scene.grains[i];
        named = named || !g.name.empty();
        moving = moving || !g.velocity.isZero(0.0);
        spinning = spinning || !g.angularVelocity.isZero(0.0);
        ownMaterial = ownMaterial || g.material != scene.grains[first].material;
    }
    std::string text = named ? "name," : "";
    text += ownMaterial ? "material," : "";
    text += "asset,x,y,z,qw,qx,qy,qz";
    text += moving ? ",vx,vy,vz" : "";
    text += spinning ? ",wx,wy,wz" : "";
    text += "\n";
    for (size_t i = first; i < first + count; ++i) {
        const GrainSpec& g = scene.grains[i];
        std::string line = named ? csvField(g.name) + "," : "";
        if (ownMaterial) line += csvField(scene.materials[size_t(g.material)].name) + ",";
        line += csvField(scene.assets[size_t(g.asset)].name);
        const Quat& q = g.pose.orientation;
        std::vector<double> values = {g.pose.position.x(), g.pose.position.y(),
                                      g.pose.position.z(), q.w(), q.x(), q.y(), q.z()};
        if (moving) values.insert(values.end(), {g.velocity.x(), g.velocity.y(), g.velocity.z()});
        if (spinning)
            values.insert(values.end(), {g.angularVelocity.x(), g.angularVelocity.y(),
                                         g.angularVelocity.z()});
        for (double v : values) {
            if (!std::isfinite(v))
                throw Error(g.where, "cannot write a grain with a non-finite value",
                            "every number of a grain must be finite");
            line += "," + numberText(v);
        }
        text += line + "\n";
    }
    return text;
}

void writeGrainsCsv(const Scene& scene, size_t first, size_t count, const std::string& path)
{
    writeTextFileAtomically(path, grainsCsvText(scene, first, count));
}

} // namespace lsdem
