// [assets.NAME]: where an asset comes from, and how to bake it if it is not baked yet.
#include "SceneSections.h"

#include <filesystem>
#include <sstream>

namespace lsdem::scenefile {

namespace fs = std::filesystem;

std::string resolveScenePath(const std::string& directory, const std::string& file)
{
    fs::path p(file);
    if (p.is_relative()) p = fs::path(directory) / p;
    return fs::absolute(p).lexically_normal().string();
}

void readBakeKeys(TableReader& t, BakeOptions& b, bool analytic, const std::string& provenance)
{
    b.voxelSize = t.positive("voxel");
    const int placements = int(t.has("node_spacing")) + int(t.has("nodes")) +
                           int(t.has("mesh_nodes") && t.boolean("mesh_nodes", false));
    if (placements != 1)
        t.fail("", placements == 0 ? "says nothing about its surface nodes"
                                   : "gives more than one way to place surface nodes",
               "give exactly one of node_spacing = SDP, nodes = N or mesh_nodes = true");
    std::ostringstream opts;
    opts << provenance << ": voxel " << b.voxelSize;
    if (t.has("node_spacing")) {
        b.nodePlacement = NodePlacement::Spacing;
        b.nodeSpacing = t.positive("node_spacing");
        opts << " node_spacing " << b.nodeSpacing;
    } else if (t.has("nodes")) {
        b.nodePlacement = NodePlacement::Count;
        const long long n = t.positiveInteger("nodes");
        if (n > kMaxNodeCount) t.fail("nodes", "is absurdly large", "give at most 1e8 nodes");
        b.nodeCount = static_cast<int>(n);
        opts << " nodes " << b.nodeCount;
    } else {
        if (analytic) t.fail("mesh_nodes", "an analytic shape has no mesh vertices",
                             "use node_spacing or nodes");
        b.nodePlacement = NodePlacement::MeshVertices;
        opts << " mesh_nodes";
    }
    const std::string areas = t.choice("areas", {"mesh", "uniform"}, "mesh");
    b.areaRule = areas == "mesh" ? AreaRule::Mesh : AreaRule::Uniform;
    opts << " areas " << areas;
    if (t.has("node_layout")) {
        if (analytic)
            t.fail("node_layout", "applies to meshes: an analytic shape's nodes are remeshed "
                                  "onto its exact surface", "remove it");
        if (b.nodePlacement == NodePlacement::MeshVertices)
            t.fail("node_layout", "has no effect with mesh_nodes = true",
                   "remove it, or give node_spacing or nodes");
        const std::string layout = t.choice("node_layout", {"auto", "centroidal", "remesh"}, "auto");
        b.nodeLayout = nodeLayoutNamed(layout);
        opts << " node_layout " << layout;
    }
    b.optionsText = opts.str();
}

AssetSpec readAsset(const std::string& name, const toml::table& table, const Scene& scene)
{
    TableReader t(table, "[assets." + name + "]", scene.path);
    AssetSpec a;
    a.name = name;
    a.where = t.where();
    const int sources = int(t.has("file")) + int(t.has("mesh")) + int(t.has("shape"));
    if (sources != 1)
        t.fail("", sources == 0 ? "has no source" : "has more than one source",
               "give exactly one of file = \"grain.vdb\", mesh = \"grain.stl\" or "
               "shape = \"sphere\" | \"box\" | \"ellipsoid\"");
    auto existing = [&](const std::string& key) {
        const std::string p = resolveScenePath(scene.directory, t.string(key));
        // The error_code form: a path the system refuses (too long, say) is not found either,
        // rather than a filesystem_error without the scene's line (found by fuzzing).
        std::error_code ec;
        if (!fs::is_regular_file(p, ec))
            t.fail(key, "file not found: " + p + (ec ? " (" + ec.message() + ")" : ""),
                   "give a path relative to the scene's folder or an absolute one");
        return p;
    };
    if (t.has("file")) {
        a.file = existing("file");
        // A baked asset carries its own voxels and nodes; baking keys would be ignored.
        for (const char* key :
             {"voxel", "node_spacing", "nodes", "mesh_nodes", "areas", "node_layout"})
            if (t.has(key))
                t.fail(key, "has no effect on a baked asset (file = ...)",
                       "remove it, or bake again with lsdem-bake, or use mesh = ... instead");
        t.rejectUnknownKeys();
        return a;
    }
    if (t.has("mesh")) {
        a.meshFile = existing("mesh");
    } else {
        const std::string kind = t.choice("shape", {"sphere", "box", "ellipsoid"}, "");
        if (kind == "sphere") {
            if (t.has("size")) t.fail("size", "a sphere takes radius, not size", "write radius = R");
            a.shape = AnalyticShape::sphere(t.positive("radius"));
        } else {
            if (t.has("radius"))
                t.fail("radius", "a " + kind + " takes size, not radius",
                       kind == "box" ? "write size = [A, B, C] (full edge lengths)"
                                     : "write size = [a, b, c] (semi-axes)");
            const Vec3 s = t.vec3("size");
            if (!(s.minCoeff() > 0.0)) t.fail("size", "every size must be > 0", "");
            a.shape = kind == "box" ? AnalyticShape::box(s.x(), s.y(), s.z())
                                    : AnalyticShape::ellipsoid(s.x(), s.y(), s.z());
        }
    }
    readBakeKeys(t, a.bake, bool(a.shape), "scene " + scene.path + " asset " + name);
    t.rejectUnknownKeys();
    return a;
}

} // namespace lsdem::scenefile
