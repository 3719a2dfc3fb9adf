#include "lsdem/mesh/MeshIO.h"

#include "lsdem/core/AtomicFile.h"

#include "lsdem/core/Error.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>


#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <map>
#include <ostream>
#include <sstream>

#include <Eigen/Geometry>

namespace fs = std::filesystem;

namespace lsdem {

namespace {

using Position = std::array<double, 3>;

const char* const kNoTriangles = "the file holds no triangles (only points, lines or nothing)";
const char* const kNoTrianglesFix = "export the surface of the solid as triangles or polygons";

/// Whether any mesh of @a scene has a face with three or more corners.
bool hasPolygons(const aiScene& scene)
{
    for (unsigned m = 0; m < scene.mNumMeshes; ++m)
        for (unsigned f = 0; f < scene.mMeshes[m]->mNumFaces; ++f)
            if (scene.mMeshes[m]->mFaces[f].mNumIndices >= 3) return true;
    return false;
}

/// Refuse faces that assimp's own post-processing would trip over (found by fuzzing): a face
/// with no corners makes the mesh count as polygons, and Triangulate then fails an assertion
/// that aborts the process (assimp 5.2); an index past the vertices would be read as it is.
void checkFaces(const aiScene& scene, const std::string& path)
{
    for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
        const aiMesh& mesh = *scene.mMeshes[m];
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const aiFace& face = mesh.mFaces[f];
            if (face.mNumIndices == 0)
                throw Error(path, "the file is corrupt: face " + std::to_string(f) +
                                      " has no corners",
                            "export the mesh again");
            for (unsigned k = 0; k < face.mNumIndices; ++k)
                if (face.mIndices[k] >= mesh.mNumVertices)
                    throw Error(path, "the file is corrupt: face " + std::to_string(f) +
                                          " refers to a missing vertex",
                                "export the mesh again");
        }
    }
}

/// Index of @a p in @a mesh, adding it if no vertex has exactly this position yet (+0 and -0
/// count as equal). Non-finite positions are never merged: they cannot be ordered, and
/// validation reports them by index.
int weldVertex(TriangleMesh& mesh, std::map<Position, int>& index, const Position& p)
{
    const bool finite = std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
    if (finite) {
        const auto found = index.find(p);
        if (found != index.end()) return found->second;
    }
    const int id = static_cast<int>(mesh.vertices.size());
    mesh.vertices.emplace_back(p[0], p[1], p[2]);
    if (finite) index.emplace(p, id);
    return id;
}

/// Append the triangles of @a src to @a mesh; points and lines are skipped. Vertices are added
/// only when a triangle uses them, so the vertices of skipped primitives do not linger.
void appendTriangles(TriangleMesh& mesh, std::map<Position, int>& index, const aiMesh& src,
                     const std::string& path)
{
    std::vector<int> globalId(src.mNumVertices, -1);
    for (unsigned f = 0; f < src.mNumFaces; ++f) {
        const aiFace& face = src.mFaces[f];
        if (face.mNumIndices != 3) continue;
        std::array<int, 3> tri{};
        for (int k = 0; k < 3; ++k) {
            const unsigned local = face.mIndices[k];
            if (local >= src.mNumVertices)
                throw Error(path, "the file is corrupt: a face refers to a missing vertex",
                            "export the mesh again");
            if (globalId[local] < 0) {
                const aiVector3D& v = src.mVertices[local];
                globalId[local] = weldVertex(mesh, index, {double(v.x), double(v.y), double(v.z)});
            }
            tri[k] = globalId[local];
        }
        mesh.triangles.push_back(tri);
    }
}

/// Bytes of a PLY scalar type, or 0 if @a type is none.
size_t plyTypeSize(const std::string& type)
{
    static const std::map<std::string, size_t> sizes = {
        {"char", 1},  {"uchar", 1},  {"int8", 1},  {"uint8", 1},   {"short", 2},   {"ushort", 2},
        {"int16", 2}, {"uint16", 2}, {"int", 4},   {"uint", 4},    {"int32", 4},   {"uint32", 4},
        {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
    const auto it = sizes.find(type);
    return it == sizes.end() ? 0 : it->second;
}

/// Whether @a word is a whole number in C syntax (what an ASCII PLY value is).
bool isPlyNumber(const std::string& word, double& value)
{
    char* end = nullptr;
    value = std::strtod(word.c_str(), &end);
    return !word.empty() && end == word.c_str() + word.size();
}

/// Each element item of an ASCII PLY body on its own line, with the values its properties
/// announce (a list: its count, then that many values), and nothing but blank lines after.
template <typename Property, typename FailAtLine, typename Fail>
void checkPlyAsciiBody(std::istream& in,
                       const std::vector<std::pair<long long, std::vector<Property>>>& elements,
                       int& lineNumber, const FailAtLine& failAtLine, const Fail& fail)
{
    std::string line, word;
    double value = 0.0;
    for (const auto& [count, properties] : elements)
        for (long long i = 0; i < count; ++i) {
            if (!std::getline(in, line)) fail("announces more elements than the file holds");
            ++lineNumber;
            for (const char c : line)
                if ((c < ' ' && c != '\t' && c != '\r') || c > '~')
                    failAtLine("holds a byte that is not text");
            std::istringstream words(line);
            for (const Property& p : properties) {
                if (!(words >> word) || !isPlyNumber(word, value))
                    failAtLine("has fewer values than the header announces");
                if (p.itemSize == 0) continue;
                if (!(value >= 0.0 && value <= 1e6 && value == std::floor(value)))
                    failAtLine("has a list of a bad length");
                const long long length = static_cast<long long>(value);
                for (long long k = 0; k < length; ++k)
                    if (!(words >> word) || !isPlyNumber(word, value))
                        failAtLine("has a list shorter than its length");
            }
            if (words >> word) failAtLine("has more values than the header announces");
        }
    while (std::getline(in, line)) {
        ++lineNumber;
        if (line.find_first_not_of(" \t\r") != std::string::npos)
            failAtLine("follows the last element the header announces");
    }
}

/// The items of a binary PLY body fit the file: scalars at their sizes, lists at the length
/// they state.
template <typename Property, typename Fail>
void checkPlyBinaryBody(std::istream& in,
                        const std::vector<std::pair<long long, std::vector<Property>>>& elements,
                        bool bigEndian, const Fail& fail)
{
    const std::streamoff start = in.tellg();
    in.seekg(0, std::ios::end);
    const double size = double(in.tellg() - start);
    in.seekg(start);
    double at = 0.0;
    for (const auto& [count, properties] : elements)
        for (long long i = 0; i < count; ++i)
            for (const Property& p : properties) {
                if (at + double(p.size) > size) fail("announces more data than it holds");
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
                    fail("has a list of negative length");
                at += double(p.size) + length * double(p.itemSize);
            }
    if (at > size) fail("announces more data than it holds");
}

/// assimp 5.2 trusts a PLY header, and fuzzing found it never returns when end_header is
/// missing and writes past its buffers when a keyword or a type is misspelt. So a file that
/// starts like a PLY file has its header read here first: known keywords and types only,
/// end_header within the first megabyte, and a body at least as long as the elements announced
/// (one byte per ASCII value, the fixed sizes in binary).
void checkPlyHeader(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::string line;
    std::getline(in, line);
    // assimp reads a .ply file as PLY whatever it starts with, and recognises the magic word
    // in any case elsewhere.
    std::string magic = line.substr(0, 3);
    std::transform(magic.begin(), magic.end(), magic.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    std::string extension = fs::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (magic != "ply" && extension != ".ply") return;  // not PLY
    int lineNumber = 1;
    const auto fail = [&](const std::string& problem) {
        throw Error(path, "the PLY file " + problem + " (it is damaged or not PLY)",
                    "export the mesh again");
    };
    const auto failAtLine = [&](const std::string& problem) {
        fail("at line " + std::to_string(lineNumber) + ": " + problem);
    };
    if (line.compare(0, 3, "ply") != 0) fail("does not start with the word 'ply'");
    bool binary = false, bigEndian = false;
    bool inElement = false;
    double bodyBytes = 0.0;  // at least this many bytes must follow the header
    double count = 0.0, bytesPerItem = 0.0;
    struct Property
    {
        size_t size = 0;      ///< bytes of the scalar, or of a list's count
        size_t itemSize = 0;  ///< bytes of a list's items; 0 for a scalar
        bool signedCount = false;  ///< a list's count type is signed
    };
    std::vector<std::pair<long long, std::vector<Property>>> elements;
    std::vector<std::string> names;
    size_t read = line.size() + 1;
    const auto finishElement = [&] {
        if (inElement && count > 0.0 && bytesPerItem == 0.0)
            failAtLine("an element before this line has no properties");
        bodyBytes += count * bytesPerItem;
    };
    while (read < (size_t(1) << 20) && std::getline(in, line)) {
        read += line.size() + 1;
        ++lineNumber;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        // Plain text only: assimp splits lines and words its own way, and hung on a header
        // with a stray control byte that a stream would take for a space.
        for (const char c : line)
            if ((c < ' ' && c != '\t') || c > '~')
                failAtLine("holds a byte that is not plain text");
        std::istringstream words(line);
        std::string keyword, extra;
        words >> keyword;
        if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "end_header") {
            if (line != "end_header") failAtLine("end_header must be alone on its line");
            finishElement();
            const std::streamoff header = in.tellg();
            in.seekg(0, std::ios::end);
            if (header < 0 || double(in.tellg() - header) < bodyBytes)
                fail("announces more data than it holds");
            in.seekg(header);
            // assimp also trusts the body to match the header: NULs in an ASCII body made it
            // fill all memory, and short lines made it write past its buffers (found by
            // fuzzing). So the body is walked element by element as well.
            if (binary)
                checkPlyBinaryBody(in, elements, bigEndian, fail);
            else
                checkPlyAsciiBody(in, elements, lineNumber, failAtLine, fail);
            return;
        }
        if (keyword == "format") {
            std::string format;
            words >> format;
            if (format == "binary_little_endian" || format == "binary_big_endian") {
                binary = true;
                bigEndian = format == "binary_big_endian";
            }
            else if (format != "ascii")
                failAtLine("unknown format '" + format + "'");
        } else if (keyword == "element") {
            std::string name, items;
            if (!(words >> name >> items) || (words >> extra) || items.size() > 18 ||
                items.find_first_not_of("0123456789") != std::string::npos)
                failAtLine("an element needs a name and a count, and nothing more");
            // Two elements of one name made assimp free memory twice (found by fuzzing).
            if (std::find(names.begin(), names.end(), name) != names.end())
                failAtLine("a second element named '" + name + "'");
            names.push_back(name);
            finishElement();
            count = std::stod(items);
            bytesPerItem = 0.0;
            inElement = true;
            elements.push_back({std::stoll(items), {}});
        } else if (keyword == "property") {
            std::string type, countType, itemType, name;
            words >> type;
            const bool list = type == "list";
            if (list) words >> countType >> itemType;
            words >> name;
            const size_t size = plyTypeSize(list ? countType : type);
            if (!inElement || size == 0 || (list && plyTypeSize(itemType) == 0) ||
                name.empty() || (words >> extra))
                failAtLine("a property needs an element, a known type and a name");
            bytesPerItem += binary ? double(size) : 1.0;
            const bool integer = list && countType.find("float") == std::string::npos &&
                                 countType != "double";
            if (list && !integer) failAtLine("a list's count must be an integer type");
            const bool isSigned = countType == "char" || countType == "short" ||
                                  countType == "int" || countType == "int8" ||
                                  countType == "int16" || countType == "int32";
            elements.back().second.push_back({size, list ? plyTypeSize(itemType) : 0, isSigned});
        } else {
            failAtLine("unknown keyword '" + keyword + "'");
        }
    }
    fail("has no end_header line");
}

std::string lowerCaseExtension(const std::string& path)
{
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

Vec3 facetNormal(const TriangleMesh& mesh, const std::array<int, 3>& tri)
{
    const Vec3& a = mesh.vertices[tri[0]];
    const Vec3 n = (mesh.vertices[tri[1]] - a).cross(mesh.vertices[tri[2]] - a);
    const double length = n.norm();
    return length > 0.0 ? Vec3(n / length) : Vec3::Zero();
}

void writeObj(const TriangleMesh& mesh, std::ostream& out)
{
    out << "# written by lsdem\n";
    for (const Vec3& v : mesh.vertices)
        out << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    // OBJ indices start at 1.
    for (const auto& t : mesh.triangles)
        out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
}

void writeStl(const TriangleMesh& mesh, std::ostream& out)
{
    out << "solid lsdem\n";
    for (const auto& t : mesh.triangles) {
        const Vec3 n = facetNormal(mesh, t);
        out << "  facet normal " << n.x() << ' ' << n.y() << ' ' << n.z() << "\n    outer loop\n";
        for (int k = 0; k < 3; ++k) {
            const Vec3& v = mesh.vertices[t[k]];
            out << "      vertex " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
        }
        out << "    endloop\n  endfacet\n";
    }
    out << "endsolid lsdem\n";
}

void writePly(const TriangleMesh& mesh, std::ostream& out)
{
    out << "ply\nformat ascii 1.0\ncomment written by lsdem\n"
        << "element vertex " << mesh.vertices.size() << '\n'
        << "property double x\nproperty double y\nproperty double z\n"
        << "element face " << mesh.triangles.size() << '\n'
        << "property list uchar int vertex_indices\nend_header\n";
    for (const Vec3& v : mesh.vertices) out << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    for (const auto& t : mesh.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
}

} // namespace

TriangleMesh readMesh(const std::string& path)
{
    std::error_code ec;
    if (!fs::exists(path, ec))
        throw Error(path, "no such file", "check the path and the working folder");
    if (fs::is_directory(path, ec))
        throw Error(path, "this is a folder, not a mesh file", "give the path of the mesh file");
    if (!std::ifstream(path, std::ios::binary))
        throw Error(path, "the file cannot be read", "check its permissions");

    checkPlyHeader(path);

    // Read first and post-process second, so a file that holds only points or lines is told
    // apart from one assimp cannot parse (post-processing fails on meshes without faces).
    Assimp::Importer importer;
    if (importer.ReadFile(path, 0) == nullptr)
        throw Error(path,
                    std::string("cannot read the mesh (unknown or invalid format): ") +
                        importer.GetErrorString(),
                    "export it as OBJ, STL or PLY");
    checkFaces(*importer.GetScene(), path);
    if (!hasPolygons(*importer.GetScene()))
        throw Error(path, kNoTriangles, kNoTrianglesFix);
    // PreTransformVertices applies node transforms; nothing here reorders or reorients faces,
    // because the orientation is how we tell inside from outside.
    const aiScene* scene = importer.ApplyPostProcessing(aiProcess_Triangulate |
                                                        aiProcess_JoinIdenticalVertices |
                                                        aiProcess_PreTransformVertices);
    if (scene == nullptr)
        throw Error(path, std::string("cannot process the mesh: ") + importer.GetErrorString(),
                    "export it again as OBJ, STL or PLY");

    TriangleMesh mesh;
    std::map<Position, int> index;  // welds vertices repeated across meshes and STL facets
    for (unsigned m = 0; m < scene->mNumMeshes; ++m)
        appendTriangles(mesh, index, *scene->mMeshes[m], path);
    if (mesh.triangles.empty()) throw Error(path, kNoTriangles, kNoTrianglesFix);
    return mesh;
}

void writeMesh(const TriangleMesh& mesh, const std::string& path)
{
    const int vertexCount = static_cast<int>(mesh.vertices.size());
    for (const auto& t : mesh.triangles)
        for (int v : t)
            if (v < 0 || v >= vertexCount)
                throw Error(path, "cannot write the mesh: a triangle refers to vertex " +
                                      std::to_string(v) + " of " + std::to_string(vertexCount));

    const std::string ext = lowerCaseExtension(path);
    std::function<void(const TriangleMesh&, std::ostream&)> writer;
    if (ext == ".obj") writer = writeObj;
    else if (ext == ".stl") writer = writeStl;
    else if (ext == ".ply") writer = writePly;
    else
        throw Error(path, "cannot write a mesh with extension '" + ext + "'",
                    "use one of .obj, .stl, .ply");
    writeStreamAtomically(path, [&](std::ostream& out) {
        out << std::setprecision(17);  // enough digits to read back every double exactly
        writer(mesh, out);
    });
}

} // namespace lsdem
