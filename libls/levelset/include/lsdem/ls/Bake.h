/// @file Bake.h
/// @brief Turn a mesh file or an analytic shape into a grain asset: validate, move to the
///        principal frame, sample the signed distance on a sparse grid, place surface nodes.
#pragma once

#include "lsdem/ls/AnalyticShape.h"
#include "lsdem/ls/GrainAsset.h"

#include <string>
#include <vector>

namespace lsdem {

/// The most surface nodes a bake places (--nodes N, or a spacing estimated to give more, is
/// refused): remeshing to more runs away in memory.
constexpr int kMaxNodeCount = 100000000;

enum class NodePlacement {
    Spacing,       ///< nodes about nodeSpacing apart (the SDP)
    Count,         ///< about nodeCount nodes
    MeshVertices,  ///< the input mesh's own vertices
};

/// How a mesh's nodes are placed for NodePlacement::Spacing or Count.
enum class NodeLayout {
    /// Centroidal for a mesh without sharp edges, remeshing for one with them (and for a
    /// mesh with a part thinner than the node spacing, which the centroidal cells misread).
    Automatic,
    Remesh,      ///< the vertices of the mesh remeshed isotropically (CGAL), sharp edges kept
    Centroidal,  ///< a centroidal Voronoi tessellation of the mesh (CentroidalNodes.h)
};

/// "auto", "remesh" or "centroidal", as lsdem-bake --node-layout takes them.
std::string nodeLayoutName(NodeLayout layout);
/// @throw Error naming the three words if @a name is none of them.
NodeLayout nodeLayoutNamed(const std::string& name);

struct BakeOptions
{
    double voxelSize = 0.0;          ///< VDP, > 0, in the mesh's length unit
    NodePlacement nodePlacement = NodePlacement::Spacing;
    double nodeSpacing = 0.0;        ///< SDP for NodePlacement::Spacing
    int nodeCount = 0;               ///< for NodePlacement::Count
    AreaRule areaRule = AreaRule::Mesh;
    NodeLayout nodeLayout = NodeLayout::Automatic;  ///< for meshes; analytic shapes remesh
    /// Exterior narrow band width, voxels (the interior is filled); at least the default.
    int exteriorBandVoxels = kMinExteriorBandVoxels;
    double memoryBudgetBytes = 4.0 * 1024 * 1024 * 1024;  ///< refuse grids estimated larger
    std::string optionsText;         ///< the options as the user gave them (provenance)
};

/// Bake the closed mesh in @a meshPath. Messages that do not stop the bake (repairs made, a
/// node spacing much finer than the voxels) are appended to @a warnings.
/// @throw Error for bad input (see MeshValidation.h and checkBakeOptions).
GrainAsset bakeMeshFile(const std::string& meshPath, const BakeOptions& options,
                        std::vector<std::string>& warnings);

/// Bake an already loaded mesh; @a sourceName names it in messages and provenance.
GrainAsset bakeMesh(TriangleMesh mesh, const std::string& sourceName, const BakeOptions& options,
                    std::vector<std::string>& warnings);

/// The mesh whose vertices become the nodes: @a surface remeshed isotropically to the node
/// spacing or count of @a options (NodePlacement::Spacing or Count). One stage of bakeMesh,
/// which remeshes fine scans as they are (@a keepFineInput, see RemeshOptions).
TriangleMesh nodeSurface(const TriangleMesh& surface, const BakeOptions& options,
                         bool keepFineInput);

/// The nodes of a bake of @a mesh (in its principal frame), placed as @a options ask: its
/// vertices, a remeshed surface's or a centroidal tessellation's (NodeLayout). One stage of
/// bakeMesh; a mesh whose sharp edges look like a scan's noise is named in @a warnings, and
/// the layout used ("centroidal", "remesh", "mesh vertices") put in @a layoutUsed.
SurfaceNodes placeNodesOnMesh(const TriangleMesh& mesh, const BakeOptions& options,
                              std::vector<std::string>* warnings = nullptr,
                              std::string* layoutUsed = nullptr);

/// Bake an analytic shape with its exact signed distance; nodes are projected onto the exact
/// surface. NodePlacement::MeshVertices is refused (there is no input mesh).
GrainAsset bakeAnalytic(const AnalyticShape& shape, const BakeOptions& options,
                        std::vector<std::string>& warnings);

} // namespace lsdem
