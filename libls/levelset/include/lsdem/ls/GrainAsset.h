/// @file GrainAsset.h
/// @brief A baked grain shape: level set, surface nodes, mass properties and provenance. One
///        asset is loaded once and shared, read-only, by every grain made from it.
#pragma once

#include "lsdem/ls/MassProperties.h"
#include "lsdem/ls/NodeShape.h"
#include "lsdem/ls/SurfaceNodes.h"

#include <limits>
#include <memory>
#include <string>

namespace lsdem {

/// The narrowest exterior band, voxels: interpolation in a cell the surface crosses reads
/// corners up to √3 voxels outside it, which a narrower band would leave at the background.
constexpr int kMinExteriorBandVoxels = 2;
/// The widest exterior band a bake makes, in voxels (wider only costs memory).
constexpr int kMaxExteriorBandVoxels = 64;

/// The OpenVDB signed-distance grid of an asset. Opaque here so that this header stays light;
/// include "lsdem/ls/LevelSetGrid.h" (which pulls in OpenVDB) to use it.
struct LevelSetGrid;

/// Where an asset came from, kept in the file so results can be traced to their inputs.
struct AssetProvenance
{
    std::string source;        ///< input mesh path, or an analytic description ("sphere R=5")
    std::string sourceSha256;  ///< SHA-256 of the input file's bytes ("" for analytic shapes)
    std::string options;       ///< the bake options, as given
    std::string lsdemVersion;  ///< version of lsdem that baked it
    /// How the nodes were placed: "centroidal", "remesh" (a mesh remeshed), "mesh vertices",
    /// "remesh, projected" (a curved analytic shape), "face grids" (an analytic box); "" for
    /// assets baked before it was recorded.
    std::string nodeLayout;
};

struct GrainAsset
{
    /// Signed distance, negative inside, in the asset (principal) frame; never modified after
    /// baking or loading, so any number of threads may sample it (one accessor each).
    std::shared_ptr<const LevelSetGrid> levelSet;
    double voxelSize = 0.0;              ///< VDP, length
    int exteriorBandVoxels = 0;          ///< width of the exterior band; the interior is filled

    SurfaceNodes nodes;                  ///< in the asset frame, stored in Morton order
    /// Runs of nearby nodes with bounding spheres, derived from @a nodes when an asset is
    /// baked or loaded (not stored in the file); empty means "one block of all nodes".
    NodeBlocks nodeBlocks;
    /// The box (asset frame) outside which the trilinear φ is never negative: the voxels with
    /// φ < 0, widened by one voxel. Outside it no node can be in contact. Derived from the
    /// level set when an asset is baked or loaded; unbounded by default.
    Vec3 insideBoxMin = Vec3::Constant(-std::numeric_limits<double>::infinity());
    Vec3 insideBoxMax = Vec3::Constant(std::numeric_limits<double>::infinity());
    /// An upper bound on |∇φ| of the level set's interpolant wherever φ ≥ 0
    /// (levelSetSlopeBound), derived when an asset is baked or loaded; infinite (nothing
    /// known) by default. With it, φ ≥ g at a node means the node stays outside while it
    /// moves less than g over this.
    double levelSetSlope = std::numeric_limits<double>::infinity();
    /// The surface's shape at each node (NodeShape.h), for contacts that integrate over each
    /// node's patch; empty unless a simulation's contacts ask for it (withNodeShapes): not
    /// stored in the file, and at 144 bytes a node not kept where no law reads it.
    std::vector<NodeShape> nodeShapes;
    double patchReach = 0.0;  ///< patchReachOf(nodeShapes), length; 0 without them
    /// concavityOf(nodeShapes), 1/length: how sharply the surface bends toward a patch that
    /// faces it (0 for a convex grain); 0 without them
    double patchConcavity = 0.0;
    AreaRule areaRule = AreaRule::Mesh;
    NodeSpacing spacing;                 ///< nearest-neighbour node spacing (SDP statistics)

    /// Unit-density mass properties in the asset frame: centroid at the origin, inertia
    /// diagonal (principal moments ascending).
    MassProperties mass;
    /// How the input maps to the asset frame: x_asset = rotation * (x_input - centroid).
    PrincipalFrame inputFrame;

    double boundingRadius = 0.0;         ///< max |node|, length: a sphere holding the surface
    AssetProvenance provenance;
};

} // namespace lsdem
