/// @file VtkSeries.h
/// @brief A ParaView time series: one `.pvd` collection naming, per output step, a `.vtu` file
///        of every grain's surface (its asset's zero isosurface, posed) and a `.vtu` file of
///        the contact forces as points with force vectors, and, when the world has membranes, a
///        `.vtu` file of their triangles. Every file is written atomically and the `.pvd` is
///        rewritten after each frame, so an interrupted run leaves a valid series of the frames
///        written so far.
///
/// A simulation split over ranks writes each frame as a parallel one: every rank a piece
/// (`<base>_grains_<frame>_<rank>.vtu`, the grains it owns and the forces on them), rank 0 a
/// `.pvtu` per kind naming the pieces, and the `.pvd` names the `.pvtu` files: ParaView opens
/// the series as one.
#pragma once

#include "lsdem/contact/RigidPose.h"
#include "lsdem/mesh/TriangleMesh.h"
#include "lsdem/simulation/Membrane.h"

#include <string>
#include <vector>
#include <utility>

namespace lsdem {

/// A grain's micromechanics in a frame (micromechanics.md), written over its surface.
struct VtkGrainMeasures
{
    Vec3 displacement = Vec3::Zero();  ///< since the run's start
    double rotation = 0.0;             ///< the angle turned since the run's start, rad
    double d2min = 0.0;                ///< non-affine displacement since then (NonAffineMotion.h)
    Mat3 stress = Mat3::Zero();        ///< its Love–Weber stress (Micromechanics.h)
};

/// One grain in a frame: its surface in the asset frame (shared by all grains of the asset)
/// and where it is.
struct VtkGrain
{
    const TriangleMesh* surface = nullptr;
    RigidPose pose;
    int id = 0;
    Vec3 velocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();
    /// Written as point data (displacement, rotation, d2min, stress) when the frame's grains
    /// carry them (every grain or none; not in a parallel frame's pieces).
    const VtkGrainMeasures* measures = nullptr;
};

/// One contact force, as it acts on grain @a grain (boundaries: -1 - boundary index).
struct VtkForcePoint
{
    Vec3 point = Vec3::Zero();
    Vec3 force = Vec3::Zero();
    int grain = 0;
};

class VtkSeries
{
public:
    /// Frames go to @a directory as `<baseName>_grains_<frame>.vtu` and
    /// `<baseName>_contacts_<frame>.vtu` (and `<baseName>_membranes_<frame>.vtu` for a frame
    /// with membranes), listed in `<baseName>.pvd`.
    VtkSeries(std::string directory, std::string baseName);

    /// Write frame number @a frame (0, 1, 2, ...) at simulated @a time and rewrite the .pvd.
    /// Frames numbered @a frame and above that were listed before are dropped from the .pvd
    /// (a restart rewrites them).
    /// Given @a membranes, the frame also holds them all in one grid of triangles, listed as
    /// part 2: per vertex its `velocity`, `grain_force` (the grains' push on it, Membrane::
    /// grainForces; zero where that is empty) and `held` (1 if a boundary holds it, else 0),
    /// per triangle the `membrane` it belongs to (its index). Without membranes the frame is
    /// written as it always was (no file, no part).
    void writeFrame(int frame, double time, const std::vector<VtkGrain>& grains,
                    const std::vector<VtkForcePoint>& forces,
                    const std::vector<Membrane>& membranes = {});

    /// Write frame @a frame as a parallel one of @a pieces pieces: this rank's piece
    /// @a piece (its grains and forces); piece 0 also writes the `.pvtu` files and rewrites
    /// the .pvd, as writeFrame does. Every rank calls it for every frame, with the same
    /// @a measured: whether the grains carry their measures (each grain must then have them;
    /// a piece without grains gets the arrays empty, as the `.pvtu` declares them). The
    /// @a membranes, which every rank holds whole, piece 0 writes as a whole `.vtu` (part 2).
    void writeParallelFrame(int frame, double time, int piece, int pieces,
                            const std::vector<VtkGrain>& grains,
                            const std::vector<VtkForcePoint>& forces, bool measured = false,
                            const std::vector<Membrane>& membranes = {});

    int framesWritten() const { return static_cast<int>(mTimes.size()); }

    /// The times of the frames listed so far (kept in checkpoints) and, on restart, restored;
    /// a restored frame is listed as parallel if its `.pvtu` is in the folder, and with its
    /// membranes if their `.vtu` is.
    const std::vector<double>& frameTimes() const { return mTimes; }
    void restoreFrameTimes(std::vector<double> times);

private:
    /// Frame @a frame's membranes as one whole `.vtu` (none if there are none).
    void writeMembranes(size_t frame, const std::vector<Membrane>& membranes) const;
    /// Frame @a frame at @a time is written: list it (rewriting the .pvd if @a writeCollection).
    void list(int frame, double time, bool parallel, bool membranes, bool writeCollection);

    std::string mDirectory, mBaseName;
    std::vector<double> mTimes;    ///< time of each frame listed in the .pvd
    std::vector<char> mParallel;   ///< whether each is a parallel frame (.pvtu)
    std::vector<char> mMembranes;  ///< whether each has a membranes part
};

} // namespace lsdem
