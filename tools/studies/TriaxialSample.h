/// @file TriaxialSample.h
/// @brief The triaxial study's sample: its grain assets baked at one resolution, the loose
///        cloud the test starts from, and the scene that holds them inside six plane walls.
///
///        The cloud is a cubic lattice whose spacing keeps every grain's bounding sphere clear
///        of its neighbours', each site given a mesh and an orientation drawn from the seed.
///        It depends only on the seed, the spacing and the number of meshes, so every
///        resolution of a study starts from the same grains in the same places.
#pragma once

#include "studies/TriaxialCell.h"
#include "studies/TriaxialOptions.h"

#include "lsdem/scene/Scene.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lsdem {

/// The meshes baked at one (VDP, SDP).
struct TriaxialAssets
{
    std::vector<std::shared_ptr<const GrainAsset>> assets;  ///< one per mesh file, in order
    std::vector<std::string> names;                          ///< triaxialAssetNames
    double vdp = 0.0, sdp = 0.0;
    double meanNodes = 0.0;          ///< nodes per asset
    double meanNodeArea = 0.0;       ///< mm², over every node of every asset
    double meanDiameter = 0.0;       ///< equivalent (same volume) sphere diameter, mm
    double largestBoundingRadius = 0.0;
    double bakeSeconds = 0.0;        ///< wall time of the bake (the files in parallel)
};

/// The assets' names (the shear scene's [assets.NAME] and assets/NAME.vdb): each file's stem,
/// a second file of the same stem (from another folder) NAME_2, a third NAME_3, skipping the
/// stems of the other files.
std::vector<std::string> triaxialAssetNames(const std::vector<std::string>& meshFiles);

/// Bake @a meshFiles at voxel @a vdp and node spacing @a sdp (mm), the files in parallel.
/// @throw Error naming the file that failed.
TriaxialAssets bakeTriaxialAssets(const std::vector<std::string>& meshFiles, double vdp,
                                  double sdp);

/// bakeTriaxialAssets, once per process for each (@a vdp, @a sdp): the runs of a study that
/// share a resolution (adapted and original) share its assets. Thread-safe.
std::shared_ptr<const TriaxialAssets> sharedTriaxialAssets(const std::vector<std::string>& meshFiles,
                                                           double vdp, double sdp);

struct TriaxialCloud
{
    std::vector<int> asset;        ///< per grain, an index into TriaxialAssets::assets
    std::vector<RigidPose> pose;   ///< per grain
    Vec3 boxMin = Vec3::Zero(), boxMax = Vec3::Zero();  ///< where the walls start
};

/// @a count grains on a lattice of @a spacing (at least the largest bounding diameter), its
/// height @a heightRatio times its width as near as the count allows (1: a cube), meshes and
/// orientations drawn from @a seed; the walls half a spacing outside the outermost sites.
TriaxialCloud makeTriaxialCloud(long long count, int meshCount, double spacing,
                                std::uint64_t seed, double heightRatio = 1.0);

/// The lattice spacing for @a assets: 10 % more than the largest bounding diameter (the
/// margin covers the bounding radius changing a little with the node spacing).
double triaxialCloudSpacing(const TriaxialAssets& assets);

/// The scene of one run: materials "grain" (density) and "wall", the grain–grain law of
/// formulation @a f with normal stiffness @a kn (kn* or kn) and friction o.friction (the test
/// switches it for consolidation), the grain–wall law with o.wallFriction, no gravity, global
/// damping, the grains of @a cloud and six fixed plane walls named x0, x1, y0, y1, z0, z1,
/// boundaries 0 to 5 in that order (triaxialWalls()); with o.periodic no walls but a periodic
/// cell over the cloud's box (periodicTriaxialCell()).
Scene triaxialScene(const TriaxialOptions& o, const TriaxialAssets& assets,
                    const TriaxialCloud& cloud, Formulation f, double kn);

/// The walls of triaxialScene: boundaries 0 to 5.
TriaxialWalls triaxialWalls();

} // namespace lsdem
