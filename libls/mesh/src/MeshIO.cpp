#include "lsdem/mesh/MeshIO.h"

#include "PlyCheck.h"

#include "lsdem/core/AtomicFile.h"

#include "lsdem/core/Error.h"
#include "lsdem/core/PortableRandom.h"
#include "lsdem/core/ReleaseMemory.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>


#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <unordered_map>

#include <Eigen/Geometry>

namespace fs = std::filesystem;

namespace lsdem {

namespace {

using Position = std::array<double, 3>;

/// A hash of a finite position's bits, with -0 read as +0 (they weld: they compare equal).
struct PositionHash
{
    size_t operator()(const Position& p) const
    {
        uint64_t h = 0;
        for (double c : p) {
            const double positive = c + 0.0;  // -0 + 0 = +0
            uint64_t bits = 0;
            std::memcpy(&bits, &positive, sizeof bits);
            h = splitMix64(h ^ bits);
        }
        return size_t(h);
    }
};
/// Each welded position's vertex index.
using PositionIndex = std::unordered_map<Position, int, PositionHash>;

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
/// count as equal). Non-finite positions are never merged (a NaN equals nothing), and
/// validation reports them by index.
int weldVertex(TriangleMesh& mesh, PositionIndex& index, const Position& p)
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
void appendTriangles(TriangleMesh& mesh, PositionIndex& index, const aiMesh& src,
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

/// The triangles of the file at @a path as assimp reads them, welded.
TriangleMesh importMesh(const std::string& path)
{
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
    const aiScene* scene =
        importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_PreTransformVertices);
    if (scene == nullptr)
        throw Error(path, std::string("cannot process the mesh: ") + importer.GetErrorString(),
                    "export it again as OBJ, STL or PLY");

    TriangleMesh mesh;
    // assimp is not asked to join identical vertices: on a million-triangle OBJ its pass held
    // 440 MB more and took 1.7 s, and this weld by exact position gives the same mesh, numbered
    // in the order the faces first use the vertices. (assimp's also merged positions apart by
    // subnormal amounts, ~1e-38, or not finite: seen only in fuzzed files.)
    PositionIndex index;  // welds vertices repeated across faces, meshes and STL facets
    for (unsigned m = 0; m < scene->mNumMeshes; ++m)
        appendTriangles(mesh, index, *scene->mMeshes[m], path);
    if (mesh.triangles.empty()) throw Error(path, kNoTriangles, kNoTrianglesFix);
    return mesh;
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

    checkPlyFile(path);

    TriangleMesh mesh = importMesh(path);
    // assimp's copies of a large scan (hundreds of MB for a million triangles) were freed in
    // malloc's heaps; the pages go back before the caller bakes beside them.
    releaseFreedMemory();
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
