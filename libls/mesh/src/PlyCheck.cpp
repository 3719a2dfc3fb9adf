// The PLY check before assimp reads a file (PlyCheck.h): the header's words, then the body
// element by element.
#include "PlyCheck.h"

#include "lsdem/core/Error.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace lsdem {

namespace {

namespace fs = std::filesystem;

/// One property of an element: a scalar, or a list (its count, then its items).
struct PlyProperty
{
    size_t size = 0;           ///< bytes of the scalar, or of a list's count
    size_t itemSize = 0;       ///< bytes of a list's items; 0 for a scalar
    bool signedCount = false;  ///< a list's count type is signed
};

struct PlyElement
{
    long long count = 0;
    std::vector<PlyProperty> properties;
};

/// Throws the Error for a damaged file, with the line it has reached where that helps.
class PlyFailure
{
public:
    explicit PlyFailure(std::string path) : mPath(std::move(path)) {}
    void nextLine() { ++mLine; }
    [[noreturn]] void fail(const std::string& problem) const
    {
        throw Error(mPath, "the PLY file " + problem + " (it is damaged or not PLY)",
                    "export the mesh again");
    }
    [[noreturn]] void atLine(const std::string& problem) const
    {
        fail("at line " + std::to_string(mLine) + ": " + problem);
    }

private:
    std::string mPath;
    int mLine = 1;
};

/// Bytes of a PLY scalar type, or 0 if @a type is none.
size_t typeSize(const std::string& type)
{
    static const std::map<std::string, size_t> sizes = {
        {"char", 1},  {"uchar", 1},  {"int8", 1},  {"uint8", 1},   {"short", 2},   {"ushort", 2},
        {"int16", 2}, {"uint16", 2}, {"int", 4},   {"uint", 4},    {"int32", 4},   {"uint32", 4},
        {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
    const auto it = sizes.find(type);
    return it == sizes.end() ? 0 : it->second;
}

/// Whether @a word is a whole number in C syntax (what an ASCII PLY value is).
bool isNumber(const std::string& word, double& value)
{
    char* end = nullptr;
    value = std::strtod(word.c_str(), &end);
    return !word.empty() && end == word.c_str() + word.size();
}

/// Each element item of an ASCII PLY body on its own line, with the values its properties
/// announce (a list: its count, then that many values), and nothing but blank lines after.
void checkAsciiBody(std::istream& in, const std::vector<PlyElement>& elements,
                    PlyFailure& failure)
{
    std::string line, word;
    double value = 0.0;
    for (const auto& [count, properties] : elements)
        for (long long i = 0; i < count; ++i) {
            if (!std::getline(in, line)) failure.fail("announces more elements than the file holds");
            failure.nextLine();
            for (const char c : line)
                if ((c < ' ' && c != '\t' && c != '\r') || c > '~')
                    failure.atLine("holds a byte that is not text");
            std::istringstream words(line);
            for (const PlyProperty& p : properties) {
                if (!(words >> word) || !isNumber(word, value))
                    failure.atLine("has fewer values than the header announces");
                if (p.itemSize == 0) continue;
                if (!(value >= 0.0 && value <= 1e6 && value == std::floor(value)))
                    failure.atLine("has a list of a bad length");
                const long long length = static_cast<long long>(value);
                for (long long k = 0; k < length; ++k)
                    if (!(words >> word) || !isNumber(word, value))
                        failure.atLine("has a list shorter than its length");
            }
            if (words >> word) failure.atLine("has more values than the header announces");
        }
    while (std::getline(in, line)) {
        failure.nextLine();
        if (line.find_first_not_of(" \t\r") != std::string::npos)
            failure.atLine("follows the last element the header announces");
    }
}

/// The items of a binary PLY body fit the file: scalars at their sizes, lists at the length
/// they state.
void checkBinaryBody(std::istream& in, const std::vector<PlyElement>& elements, bool bigEndian,
                     const PlyFailure& failure)
{
    const std::streamoff start = in.tellg();
    in.seekg(0, std::ios::end);
    const double size = double(in.tellg() - start);
    in.seekg(start);
    double at = 0.0;
    for (const auto& [count, properties] : elements)
        for (long long i = 0; i < count; ++i)
            for (const PlyProperty& p : properties) {
                if (at + double(p.size) > size) failure.fail("announces more data than it holds");
                if (p.itemSize == 0) {
                    at += double(p.size);
                    continue;
                }
                unsigned char bytes[4] = {};
                in.seekg(start + static_cast<std::streamoff>(at));
                in.read(reinterpret_cast<char*>(bytes), static_cast<std::streamsize>(p.size));
                double length = 0.0;
                for (size_t b = 0; b < p.size; ++b)
                    length = 256.0 * length + bytes[bigEndian ? b : p.size - 1 - b];
                if (p.signedCount && (bytes[bigEndian ? 0 : p.size - 1] & 0x80))
                    failure.fail("has a list of negative length");
                at += double(p.size) + length * double(p.itemSize);
            }
    if (at > size) failure.fail("announces more data than it holds");
}

std::string lowerCase(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

/// A PLY header read line by line: its format, its elements and their properties, and the
/// bytes its body must hold at least (one per ASCII value, the fixed sizes in binary).
class PlyHeader
{
public:
    explicit PlyHeader(PlyFailure& failure) : mFailure(failure) {}

    void format(std::istringstream& words)
    {
        std::string format;
        words >> format;
        if (format == "binary_little_endian" || format == "binary_big_endian") {
            mBinary = true;
            mBigEndian = format == "binary_big_endian";
        } else if (format != "ascii") {
            mFailure.atLine("unknown format '" + format + "'");
        }
    }
    void element(std::istringstream& words)
    {
        std::string name, items, extra;
        if (!(words >> name >> items) || (words >> extra) || items.size() > 18 ||
            items.find_first_not_of("0123456789") != std::string::npos)
            mFailure.atLine("an element needs a name and a count, and nothing more");
        // Two elements of one name made assimp free memory twice (found by fuzzing).
        if (std::find(mNames.begin(), mNames.end(), name) != mNames.end())
            mFailure.atLine("a second element named '" + name + "'");
        mNames.push_back(name);
        finishElement();
        mElements.push_back({std::stoll(items), {}});
    }
    void property(std::istringstream& words)
    {
        std::string type, countType, itemType, name, extra;
        words >> type;
        const bool list = type == "list";
        if (list) words >> countType >> itemType;
        words >> name;
        const size_t size = typeSize(list ? countType : type);
        if (mElements.empty() || size == 0 || (list && typeSize(itemType) == 0) || name.empty() ||
            (words >> extra))
            mFailure.atLine("a property needs an element, a known type and a name");
        mBytesPerItem += mBinary ? double(size) : 1.0;
        const bool integer =
            list && countType.find("float") == std::string::npos && countType != "double";
        if (list && !integer) mFailure.atLine("a list's count must be an integer type");
        const bool isSigned = countType == "char" || countType == "short" || countType == "int" ||
                              countType == "int8" || countType == "int16" || countType == "int32";
        mElements.back().properties.push_back({size, list ? typeSize(itemType) : 0, isSigned});
    }
    /// The header has ended at @a in's position: the body must be as long as announced, and
    /// hold the items the elements announce.
    void end(std::ifstream& in)
    {
        finishElement();
        const std::streamoff header = in.tellg();
        in.seekg(0, std::ios::end);
        if (header < 0 || double(in.tellg() - header) < mBodyBytes)
            mFailure.fail("announces more data than it holds");
        in.seekg(header);
        // assimp also trusts the body to match the header: NULs in an ASCII body made it fill
        // all memory, and short lines made it write past its buffers (found by fuzzing). So
        // the body is walked element by element as well.
        if (mBinary)
            checkBinaryBody(in, mElements, mBigEndian, mFailure);
        else
            checkAsciiBody(in, mElements, mFailure);
    }

private:
    void finishElement()
    {
        if (mElements.empty()) return;
        const double count = double(mElements.back().count);
        if (count > 0.0 && mBytesPerItem == 0.0)
            mFailure.atLine("an element before this line has no properties");
        mBodyBytes += count * mBytesPerItem;
        mBytesPerItem = 0.0;
    }

    PlyFailure& mFailure;
    bool mBinary = false, mBigEndian = false;
    std::vector<PlyElement> mElements;
    std::vector<std::string> mNames;
    double mBytesPerItem = 0.0;  ///< of the element being read
    double mBodyBytes = 0.0;     ///< at least this many bytes must follow the header
};

} // namespace

void checkPlyFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::string line;
    std::getline(in, line);
    // assimp reads a .ply file as PLY whatever it starts with, and recognises the magic word
    // in any case elsewhere.
    if (lowerCase(line.substr(0, 3)) != "ply" &&
        lowerCase(fs::path(path).extension().string()) != ".ply")
        return;  // not PLY
    PlyFailure failure(path);
    if (line.compare(0, 3, "ply") != 0) failure.fail("does not start with the word 'ply'");
    PlyHeader header(failure);
    size_t read = line.size() + 1;
    while (read < (size_t(1) << 20) && std::getline(in, line)) {
        read += line.size() + 1;
        failure.nextLine();
        if (!line.empty() && line.back() == '\r') line.pop_back();
        // Plain text only: assimp splits lines and words its own way, and hung on a header
        // with a stray control byte that a stream would take for a space.
        for (const char c : line)
            if ((c < ' ' && c != '\t') || c > '~') failure.atLine("holds a byte that is not plain text");
        std::istringstream words(line);
        std::string keyword;
        words >> keyword;
        if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "end_header") {
            if (line != "end_header") failure.atLine("end_header must be alone on its line");
            header.end(in);
            return;
        }
        if (keyword == "format")
            header.format(words);
        else if (keyword == "element")
            header.element(words);
        else if (keyword == "property")
            header.property(words);
        else
            failure.atLine("unknown keyword '" + keyword + "'");
    }
    failure.fail("has no end_header line");
}

} // namespace lsdem
