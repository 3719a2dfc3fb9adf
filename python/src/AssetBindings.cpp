// Grain assets in Python: bake from a mesh or an analytic shape, load, save, and read the
// level set's companions (nodes, mass properties, provenance) as numpy arrays.
#include "Bindings.h"

#include "lsdem/ls/AssetIO.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/core/Error.h"

#include <pybind11/stl.h>

#include <cmath>
#include <filesystem>
#include <iterator>
#include <map>
#include <optional>
#include <sstream>

namespace lsdem::python {

namespace fs = std::filesystem;

namespace {

/// rememberAssetFile's table, by address. An entry whose asset has died may share its address
/// with a newer one: the weak pointer tells them apart.
struct RememberedFile
{
    std::weak_ptr<const GrainAsset> asset;
    std::string path;
};
std::map<const GrainAsset*, RememberedFile>& rememberedFiles()
{
    static std::map<const GrainAsset*, RememberedFile> files;
    return files;
}

} // namespace

void rememberAssetFile(const std::shared_ptr<const GrainAsset>& asset, const std::string& path)
{
    auto& files = rememberedFiles();
    for (auto it = files.begin(); it != files.end();)  // forget the dead, so it stays small
        it = it->second.asset.expired() ? files.erase(it) : std::next(it);
    files[asset.get()] = {asset, fs::absolute(path).lexically_normal().string()};
}

std::string rememberedAssetFile(const GrainAsset* asset)
{
    const auto& files = rememberedFiles();
    const auto it = files.find(asset);
    if (it == files.end() || it->second.asset.lock().get() != asset) return "";
    return it->second.path;
}

namespace {

/// The node placement and area rule from the keyword arguments shared by every bake_*.
BakeOptions bakeOptions(double voxel, std::optional<double> nodeSpacing,
                        std::optional<int> nodeCount, bool meshNodes, const std::string& areas,
                        int band, const std::string& nodeLayout = "auto")
{
    // Checked here as well as by the bake, whose messages name lsdem-bake's options.
    if (!(voxel > 0.0) || !std::isfinite(voxel))
        throw Error("", "voxel (the voxel size, VDP) must be a positive finite length",
                    "pass e.g. voxel=0.05, in the shape's length unit");
    if (nodeSpacing && (!(*nodeSpacing > 0.0) || !std::isfinite(*nodeSpacing)))
        throw Error("", "node_spacing (SDP) must be a positive finite length",
                    "pass e.g. node_spacing=0.1, or nodes=N");
    if (band < kMinExteriorBandVoxels || band > kMaxExteriorBandVoxels)
        throw Error("", "band must be " + std::to_string(kMinExteriorBandVoxels) + " to " +
                            std::to_string(kMaxExteriorBandVoxels) + " voxels, got " +
                            std::to_string(band),
                    "leave it at its default (" +
                        std::to_string(BakeOptions().exteriorBandVoxels) + ")");
    BakeOptions o;
    o.voxelSize = voxel;
    o.exteriorBandVoxels = band;
    const int placements = int(nodeSpacing.has_value()) + int(nodeCount.has_value()) +
                           int(meshNodes);
    if (placements != 1)
        throw Error("", "say how to place surface nodes, once",
                    "give exactly one of node_spacing=SDP, nodes=N or mesh_nodes=True");
    if (nodeSpacing) {
        o.nodePlacement = NodePlacement::Spacing;
        o.nodeSpacing = *nodeSpacing;
    } else if (nodeCount) {
        if (*nodeCount < 4 || *nodeCount > kMaxNodeCount)
            throw Error("", "nodes wants a count from 4 to 1e8, got " +
                                std::to_string(*nodeCount));
        o.nodePlacement = NodePlacement::Count;
        o.nodeCount = *nodeCount;
    } else {
        o.nodePlacement = NodePlacement::MeshVertices;
    }
    if (areas == "mesh") o.areaRule = AreaRule::Mesh;
    else if (areas == "uniform") o.areaRule = AreaRule::Uniform;
    else throw Error("", "areas wants 'mesh' or 'uniform', got '" + areas + "'");
    if (nodeLayout != "auto" && nodeLayout != "centroidal" && nodeLayout != "remesh")
        throw Error("", "node_layout wants 'auto', 'centroidal' or 'remesh', got '" + nodeLayout +
                            "'");
    o.nodeLayout = nodeLayoutNamed(nodeLayout);
    if (meshNodes && o.nodeLayout != NodeLayout::Automatic)
        throw Error("", "node_layout has no effect with mesh_nodes=True",
                    "drop node_layout, or give node_spacing or nodes");
    // Provenance: the call as a script wrote it.
    std::ostringstream text;
    text.precision(17);
    text << "python: voxel=" << voxel;
    if (nodeSpacing) text << " node_spacing=" << *nodeSpacing;
    if (nodeCount) text << " nodes=" << *nodeCount;
    if (meshNodes) text << " mesh_nodes=True";
    text << " areas=" << areas << " band=" << band;
    if (o.nodeLayout != NodeLayout::Automatic) text << " node_layout=" << nodeLayout;
    o.optionsText = text.str();
    return o;
}

/// Bake with the GIL released, then hand the non-fatal messages to Python's warnings.
template <typename Bake>
AssetHandle bakeAndWarn(Bake&& bake)
{
    std::vector<std::string> warnings;
    GrainAsset asset;
    {
        py::gil_scoped_release release;
        asset = bake(warnings);
    }
    for (const std::string& w : warnings)
        if (PyErr_WarnEx(PyExc_UserWarning, ("lsdem: " + w).c_str(), 2) != 0)
            throw py::error_already_set();  // warnings turned into errors
    return {std::make_shared<const GrainAsset>(std::move(asset)), ""};
}

AssetHandle bakeShape(const AnalyticShape& shape, double voxel, std::optional<double> spacing,
                      std::optional<int> nodes, const std::string& areas, int band)
{
    const BakeOptions o = bakeOptions(voxel, spacing, nodes, false, areas, band);
    return bakeAndWarn([&](std::vector<std::string>& w) { return bakeAnalytic(shape, o, w); });
}

/// The nodes of an asset; its arrays are views kept valid by this object (which holds the
/// asset).
struct NodesHandle
{
    std::shared_ptr<const GrainAsset> asset;
};

const char* kBakeKeywords =
    "voxel: level-set voxel size (VDP), in the shape's length unit.\n"
    "node_spacing / nodes: place surface nodes about this far apart (SDP), or about this many "
    "nodes; give one.\n"
    "areas: 'mesh' (each node's own share of the surface) or 'uniform' (total area / N).\n"
    "band: exterior narrow-band width in voxels (the interior is filled).\n"
    "Returns an Asset in its principal frame (centroid at the origin). Warnings that do not "
    "stop the bake arrive as Python UserWarnings; bad input raises lsdem.Error.";

} // namespace

// Long by nature: one .def per method and property of Asset, in the order help() lists them.
void bindAssets(py::module_& m)
{
    py::class_<NodesHandle>(m, "Nodes",
                            "The surface nodes of an asset (quadrature points of the contact "
                            "traction), in its principal frame and Morton order. The arrays "
                            "are read-only views into the asset, valid as long as they live.")
        .def("__len__", [](const NodesHandle& n) { return n.asset->nodes.size(); })
        .def_property_readonly(
            "positions",
            [](py::object self) {
                const auto& n = self.cast<const NodesHandle&>().asset->nodes;
                return vectorView(n.positions.data(), n.size(), sizeof(Vec3), self);
            },
            "(N, 3) float64, length: node positions (read-only view)")
        .def_property_readonly(
            "normals",
            [](py::object self) {
                const auto& n = self.cast<const NodesHandle&>().asset->nodes;
                if (!n.hasNormals())  // (a simulation's copy; Python's own assets keep them)
                    throw Error("", "these nodes hold no normals",
                                "load the asset with lsdem.load to read them");
                return vectorView(n.normals.data(), n.size(), sizeof(Vec3), self);
            },
            "(N, 3) float64: outward unit normals (read-only view)")
        .def_property_readonly(
            "areas",
            [](py::object self) {
                const auto& n = self.cast<const NodesHandle&>().asset->nodes;
                return scalarView(n.areas.data(), n.size(), sizeof(double), self);
            },
            "(N,) float64, length²: tributary areas (read-only view)")
        .def("__repr__", [](const NodesHandle& n) {
            return "<lsdem.Nodes: " + std::to_string(n.asset->nodes.size()) + " nodes>";
        });

    py::class_<AssetHandle>(
        m, "Asset",
        "A baked grain shape: the signed-distance level set (an OpenVDB grid), the surface "
        "nodes and the unit-density mass properties, all in the grain's principal frame "
        "(centroid at the origin, principal axes along x, y, z). Read-only and shared: many "
        "grains of a scene may use one asset.\n\n"
        "Make one with bake_mesh, bake_sphere, bake_box, bake_ellipsoid or load.")
        .def("save",
             [](AssetHandle& a, const std::string& path) {
                 {
                     py::gil_scoped_release release;
                     saveAsset(*a.asset, path);
                 }
                 a.path = path;
                 rememberAssetFile(a.asset, path);
             },
             py::arg("path"),
             "Write the asset to a .vdb file (atomically: a temporary file, then a rename). "
             "Any OpenVDB tool opens it; lsdem.load reads it back identically.")
        .def_property_readonly("path", [](const AssetHandle& a) { return a.path; },
                               "The file it was loaded from or last saved to ('' if none).")
        .def_property_readonly("volume", [](const AssetHandle& a) { return a.asset->mass.volume; },
                               "Volume (length³); the mass for unit density.")
        .def_property_readonly("inertia",
                               [](const AssetHandle& a) { return toArray(a.asset->mass.inertia); },
                               "(3, 3) inertia tensor about the centroid for unit density "
                               "(length⁵), diagonal: the asset is in its principal frame.")
        .def_property_readonly(
            "principal_moments",
            [](const AssetHandle& a) { return toArray(Vec3(a.asset->mass.inertia.diagonal())); },
            "(3,) principal moments of inertia for unit density, ascending.")
        .def("mass_properties",
             [](const AssetHandle& a, double density) {
                 py::dict d;
                 d["mass"] = density * a.asset->mass.volume;
                 d["centroid"] = toArray(a.asset->mass.centroid);
                 d["inertia"] = toArray(Mat3(density * a.asset->mass.inertia));
                 return d;
             },
             py::arg("density") = 1.0,
             "Mass, centroid (3,) and inertia (3, 3) for a density (mass/length³).")
        .def_property_readonly("surface_area",
                               [](const AssetHandle& a) { return a.asset->nodes.totalArea(); },
                               "Sum of the nodes' tributary areas (length²).")
        .def_property_readonly("voxel_size", [](const AssetHandle& a) { return a.asset->voxelSize; },
                               "Level-set voxel size (VDP), length.")
        .def_property_readonly("bounding_radius",
                               [](const AssetHandle& a) { return a.asset->boundingRadius; },
                               "Largest node distance from the centroid (length).")
        .def_property_readonly(
            "node_spacing",
            [](const AssetHandle& a) {
                py::dict d;
                d["mean"] = a.asset->spacing.mean;
                d["min"] = a.asset->spacing.min;
                d["max"] = a.asset->spacing.max;
                return d;
            },
            "Nearest-neighbour node spacing statistics (SDP): dict of mean, min, max.")
        .def_property_readonly(
            "area_rule",
            [](const AssetHandle& a) {
                return a.asset->areaRule == AreaRule::Mesh ? "mesh" : "uniform";
            },
            "How node areas were set: 'mesh' or 'uniform'.")
        .def_property_readonly(
            "node_layout", [](const AssetHandle& a) { return a.asset->provenance.nodeLayout; },
            "How the nodes were placed: 'centroidal', 'remesh', 'mesh vertices', 'remesh, "
            "projected' (a sphere or ellipsoid), 'face grids' (a box); '' for an asset baked "
            "before it was recorded.")
        .def_property_readonly(
            "input_frame",
            [](const AssetHandle& a) {
                py::dict d;
                d["rotation"] = toArray(a.asset->inputFrame.rotation);
                d["centroid"] = toArray(a.asset->inputFrame.centroid);
                return d;
            },
            "How the input maps to the asset frame: x_asset = rotation @ (x_input - centroid).")
        .def_property_readonly(
            "provenance",
            [](const AssetHandle& a) {
                const AssetProvenance& p = a.asset->provenance;
                py::dict d;
                d["source"] = p.source;
                d["source_sha256"] = p.sourceSha256;
                d["options"] = p.options;
                d["lsdem_version"] = p.lsdemVersion;
                return d;
            },
            "Where the asset came from: source, source_sha256, options, lsdem_version.")
        .def_property_readonly(
            "nodes", [](const AssetHandle& a) { return NodesHandle{a.asset}; },
            "The surface nodes: .positions, .normals (N, 3) and .areas (N,), read-only views.")
        .def("__repr__", [](const AssetHandle& a) {
            std::ostringstream s;
            s << "<lsdem.Asset '" << a.asset->provenance.source << "': "
              << a.asset->nodes.size() << " nodes, voxel " << a.asset->voxelSize
              << ", volume " << a.asset->mass.volume << ">";
            return s.str();
        });

    m.def("load",
          [](const std::string& path) {
              std::shared_ptr<const GrainAsset> asset;
              {
                  py::gil_scoped_release release;
                  asset = loadAsset(path);
              }
              rememberAssetFile(asset, path);
              return AssetHandle{asset, path};
          },
          py::arg("path"),
          "Read an asset .vdb written by Asset.save or lsdem-bake. Raises lsdem.Error naming "
          "the file if it is missing, corrupt or not an lsdem asset.");

    m.def("bake_mesh",
          [](const std::string& path, double voxel, std::optional<double> nodeSpacing,
             std::optional<int> nodes, bool meshNodes, const std::string& areas, int band,
             const std::string& nodeLayout) {
              const BakeOptions o =
                  bakeOptions(voxel, nodeSpacing, nodes, meshNodes, areas, band, nodeLayout);
              return bakeAndWarn(
                  [&](std::vector<std::string>& w) { return bakeMeshFile(path, o, w); });
          },
          py::arg("path"), py::kw_only(), py::arg("voxel"), py::arg("node_spacing") = py::none(),
          py::arg("nodes") = py::none(), py::arg("mesh_nodes") = false,
          py::arg("areas") = "mesh", py::arg("band") = BakeOptions().exteriorBandVoxels,
          py::arg("node_layout") = "auto",
          (std::string("Bake the closed mesh in path (OBJ, STL, PLY, or anything assimp "
                       "reads) into an Asset, as lsdem-bake does.\n"
                       "mesh_nodes=True: use the mesh's own vertices as nodes.\n"
                       "node_layout: 'auto' (centroidal unless the mesh has sharp edges in lines, "
                       "as a block's; a scan's scattered noise is not), "
                       "'centroidal' (nodes at the centroids of a centroidal Voronoi "
                       "tessellation of the mesh) or 'remesh' (the "
                       "vertices of the mesh remeshed, sharp edges kept).\n") +
           kBakeKeywords)
              .c_str());
    m.def("bake_sphere",
          [](double radius, double voxel, std::optional<double> spacing,
             std::optional<int> nodes, const std::string& areas, int band) {
              return bakeShape(AnalyticShape::sphere(radius), voxel, spacing, nodes, areas, band);
          },
          py::arg("radius"), py::kw_only(), py::arg("voxel"),
          py::arg("node_spacing") = py::none(), py::arg("nodes") = py::none(),
          py::arg("areas") = "mesh", py::arg("band") = BakeOptions().exteriorBandVoxels,
          (std::string("Bake a sphere of the given radius with its exact signed distance.\n") +
           kBakeKeywords)
              .c_str());
    m.def("bake_box",
          [](double a, double b, double c, double voxel, std::optional<double> spacing,
             std::optional<int> nodes, const std::string& areas, int band) {
              return bakeShape(AnalyticShape::box(a, b, c), voxel, spacing, nodes, areas, band);
          },
          py::arg("a"), py::arg("b"), py::arg("c"), py::kw_only(), py::arg("voxel"),
          py::arg("node_spacing") = py::none(), py::arg("nodes") = py::none(),
          py::arg("areas") = "mesh", py::arg("band") = BakeOptions().exteriorBandVoxels,
          (std::string("Bake a box with full edge lengths a, b, c.\n") + kBakeKeywords).c_str());
    m.def("bake_ellipsoid",
          [](double a, double b, double c, double voxel, std::optional<double> spacing,
             std::optional<int> nodes, const std::string& areas, int band) {
              return bakeShape(AnalyticShape::ellipsoid(a, b, c), voxel, spacing, nodes, areas,
                               band);
          },
          py::arg("a"), py::arg("b"), py::arg("c"), py::kw_only(), py::arg("voxel"),
          py::arg("node_spacing") = py::none(), py::arg("nodes") = py::none(),
          py::arg("areas") = "mesh", py::arg("band") = BakeOptions().exteriorBandVoxels,
          (std::string("Bake an ellipsoid with semi-axes a, b, c.\n") + kBakeKeywords).c_str());
}

} // namespace lsdem::python
