/// @file Scene.h
/// @brief What a scene file describes, as plain data: assets, materials, contact models per
///        pair of materials, grains, boundaries, time stepping, end condition and outputs.
///        SceneFile.h reads it from TOML; World.h turns it into a running system. Units are
///        the user's (declared in the scene and checked for consistency), e.g. mm, N, s, tonne.
#pragma once

#include "lsdem/contact/ContactModel.h"
#include "lsdem/contact/RigidPose.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/simulation/BoundaryShape.h"
#include "lsdem/simulation/GrainMotion.h"
#include "lsdem/simulation/Membrane.h"
#include "lsdem/simulation/StressServo.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lsdem {

/// The declared unit system: force must equal mass·length/time² (e.g. mm, tonne, s, N).
struct UnitSystem
{
    std::string length = "mm", mass = "tonne", time = "s", force = "N";
};

/// Where an asset comes from: a baked .vdb file, or a mesh / analytic shape baked at load, or
/// (for scenes built by a program) an asset already in memory.
struct AssetSpec
{
    std::string name;
    /// An asset already loaded or baked by the program that built the scene: used as it is
    /// (no file is read). @a file, if also set, is where it was saved (for sceneToToml).
    std::shared_ptr<const GrainAsset> loaded;
    std::string file;                  ///< baked asset, absolute path ("" if baked on the fly)
    std::string meshFile;              ///< mesh to bake on the fly, absolute path
    std::optional<AnalyticShape> shape;  ///< analytic shape to bake on the fly
    BakeOptions bake;                  ///< voxel size, node placement, areas (on-the-fly only)
    std::string where;                 ///< "scene.toml:12" for messages
    std::string set;                   ///< the [asset_sets] entry it came from ("" if none)
};

/// [asset_sets.NAME]: many assets at once, from a catalogue (lsdem-bake --out-dir writes
/// DIR/catalog.csv) or from the files a glob matches (baked .vdb files, or meshes baked at load
/// with the set's options). Each becomes an AssetSpec named "NAME/ASSET" (ASSET: the
/// catalogue's name column, or the file's stem), appended to Scene::assets in the catalogue's
/// row order or the matches' name order.
struct AssetSetSpec
{
    std::string name;
    std::string catalog;  ///< the catalogue, absolute path ("" if glob)
    std::string glob;     ///< the pattern, absolute ("" if catalog); wildcards in the file name
    bool meshes = false;  ///< the glob matches meshes, baked at load with @a bake
    BakeOptions bake;
    std::string where;
};

struct MaterialSpec
{
    std::string name;
    double density = 0.0;  ///< mass/length³; > 0 for materials of free grains
};

/// The contact law between two materials (order does not matter).
struct ContactSpec
{
    int materialA = 0, materialB = 0;  ///< indices into Scene::materials
    ContactModel model;  ///< with its dashpot from the scene's restitution (model.damping)
    std::string where;
};

/// The name of an unnamed grain, from its index in Scene::grains: grain0, grain1, ...
inline std::string defaultGrainName(size_t index)
{
    return "grain" + std::to_string(index);
}

struct GrainSpec
{
    std::string name;                    ///< optional; "" means defaultGrainName(index)
    int asset = 0;                       ///< index into Scene::assets
    int material = 0;                    ///< index into Scene::materials
    RigidPose pose;                      ///< centroid position and asset-to-world rotation
    Vec3 velocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();
    double mass = 0.0;                   ///< > 0 overrides density × asset volume
    GrainMotion motion = GrainMotion::Free;
    std::string where;
};

/// Grains read from a CSV table (GrainsCsv.h) by [[grain_files]]: they are
/// Scene::grains[first, first + count), and the writer refers to the file instead of listing them.
struct GrainFileSpec
{
    std::string file;          ///< absolute path
    int material = 0;          ///< for rows without a material column
    size_t first = 0, count = 0;
    /// Largest overlap (penetration depth of a node into another grain's level set, length)
    /// allowed between a grain of the file and any other grain; < 0: 5 % of the smaller
    /// grain's bounding radius.
    double maxOverlap = -1.0;
    std::string where;
};

struct BoundarySpec
{
    std::string name;
    BoundaryShape shape = BoundaryShape::Plane;
    int material = 0;
    // Plane: a point, the unit normal, and optionally a finite rectangular patch: nodes count
    // only if their projection lies within ±extent/2 along the in-plane axes (axisU and
    // normal × axisU) and they are less than `thickness` behind the plane.
    Vec3 point = Vec3::Zero();
    Vec3 normal = Vec3::UnitZ();
    double extentU = 0.0, extentV = 0.0;  ///< 0: unbounded
    Vec3 axisU = Vec3::UnitX();
    double thickness = 0.0;               ///< 0: unbounded; Orifice: the plate's, > 0
    // Sphere: centre and radius. Cylinder (grains inside): a point of its axis, the axis and
    // the radius. Orifice (a plate with a hole; grains outside the plate): the hole's centre in
    // the plate's mid-plane, its axis (the plate's normal), its radius and the thickness above.
    Vec3 center = Vec3::Zero();
    double radius = 0.0;
    Vec3 axis = Vec3::UnitZ();
    // Level set: the asset and where it sits.
    int asset = -1;
    RigidPose pose;
    /// Prescribed velocity (zero: fixed). The reaction force on the boundary is recorded.
    Vec3 velocity = Vec3::Zero();
    /// Plane: keep a target normal stress instead (StressServo.h); its areaWalls are the
    /// boundaries named by areaWallNames, resolved once every boundary is read.
    StressServo servo;
    std::vector<std::string> areaWallNames;
    std::string where;
};

/// [[membranes]]: a flexible membrane (Membrane.h), for now a tube: the side of a cylinder
/// as placed, its vertices at rest. Grains meet it through the law between their material and
/// its @a material. Its rims are held by the plane boundaries @a hold, each rim
/// by the nearest of them (a triaxial sample's membrane sealed to its platens).
struct MembraneSpec
{
    std::string name;
    int material = 0;           ///< index into Scene::materials
    MembraneMaterial rubber;    ///< E, ν, thickness, density (mass scaling: Membrane.h)
    double pressure = 0.0;      ///< on its outer side, pushing in (force/area), >= 0
    double drag = 0.0;          ///< the cell fluid's viscous drag (Membrane::drag), >= 0
    // The tube: its axis from @a base along @a axis, its radius and height as placed, @a
    // segments vertices round each of @a rings + 1 rings.
    Vec3 base = Vec3::Zero();
    Vec3 axis = Vec3::UnitZ();
    double radius = 0.0, height = 0.0;
    int segments = 0, rings = 0;
    /// Its hoop stretch as placed (>= 1): the rubber's unstretched radius is radius/prestretch,
    /// so it is taut round what it wraps from the start (a slack membrane has no stiffness).
    double prestretch = 1.0;
    std::vector<int> hold;  ///< indices into Scene::boundaries (a file names them: `hold`)
    /// Optional: a CSV of its vertices as a run left them (MembraneStateCsv.h), absolute. The
    /// tube's keys then give only its rubber's unstretched shape and its vertices' order.
    std::string state;
    std::string where;
};

/// When a run stops: the first of the conditions given.
struct EndCondition
{
    double time = 0.0;               ///< > 0: stop at this simulated time
    long long steps = 0;             ///< > 0: stop after this many steps
    int boundary = -1;               ///< >= 0: stop when this boundary has moved ...
    double displacement = 0.0;       ///< ... this far (length, > 0)
};

struct TimeStepSpec
{
    double fixed = 0.0;    ///< > 0: this step; 0: automatic
    double safety = 0.2;   ///< automatic: dt = safety · 2·sqrt(m_eff / k_node)
};

struct OutputSpec
{
    long long historyEvery = 0;     ///< steps between history rows (0: derived from period)
    double historyPeriod = 0.0;     ///< time between history rows
    double vtkPeriod = 0.0;         ///< time between ParaView frames (0: none)
    double checkpointPeriod = 0.0;  ///< time between checkpoints (0: only at the end / signal)
    bool contactForces = true;      ///< write contact force points in the VTK frames
    /// The spacing of each grain's surface in the VTK frames, length (0: its asset's node
    /// spacing). Coarser makes lighter frames of many grains.
    double frameSpacing = 0.0;
    bool micromechanics = false;    ///< write micromechanics.csv at each history row
};

struct Scene
{
    std::string path;       ///< the scene file, as given
    std::string directory;  ///< its folder: relative asset paths are resolved from here
    std::string text;       ///< the file's text (kept in checkpoints)
    UnitSystem units;
    std::vector<AssetSpec> assets;
    std::vector<AssetSetSpec> assetSets;
    std::vector<MaterialSpec> materials;
    std::vector<ContactSpec> contacts;
    std::vector<GrainSpec> grains;
    std::vector<GrainFileSpec> grainFiles;  ///< which grains came from CSV files
    std::vector<BoundarySpec> boundaries;
    std::vector<MembraneSpec> membranes;
    Vec3 gravity = Vec3::Zero();
    /// Global non-viscous damping λ in [0, 1): each force component on a free grain is
    /// reduced by λ·|F| against the velocity (as YADE's NewtonIntegrator).
    double globalDamping = 0.0;
    /// A periodic cell (PeriodicCell.h): its period along each axis (0: not periodic along
    /// it) and its corner; every grain is moved into it by whole periods.
    Vec3 periodicCell = Vec3::Zero();
    Vec3 periodicOrigin = Vec3::Zero();
    /// The periodic cell's stretching rate along each periodic axis (1/time; < 0 compresses).
    Vec3 periodicStrainRate = Vec3::Zero();
    /// Stress control of periodic axes: a target stress (compressive, > 0; 0: the axis keeps
    /// its strain rate) and the fastest the servo may strain it (1/time).
    Vec3 periodicStress = Vec3::Zero();
    Vec3 periodicMaxStrainRate = Vec3::Zero();
    TimeStepSpec timeStep;
    EndCondition end;
    OutputSpec output;
};

} // namespace lsdem
