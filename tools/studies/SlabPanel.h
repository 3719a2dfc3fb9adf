/// @file SlabPanel.h
/// @brief The geometry of a slab-like topologically interlocked panel (Feldfogel et al. 2024,
///        Fig. 5; after Mirkhalaf et al. 2019): n×n planar-faced blocks on a square grid of
///        pitch L, thickness t, whose four side faces are inclined alternately by +θ and −θ
///        around each block, so that every block rests on two neighbours and carries the other
///        two. A ring of 4n "ghost" blocks of the same shape around the panel is the rigid
///        frame: their inner faces are exactly the outer faces of the border blocks.
///
/// Construction. Panel coordinates: x, y in the plane (the panel centred at the origin), z up
/// from the bottom face (z = 0) to the top (z = t). Block (i, j) (column i along x, row j
/// along y, both 0 … n−1; the frame uses −1 and n) has its centre at
/// (x_i, y_j) = ((i − (n−1)/2)·L, (j − (n−1)/2)·L) and its sign σ = (−1)^(i+j). With
/// s(z) = tanθ·(z − t/2), the plane between columns i and i+1 beside row j is
/// x = x_{i+1/2} + σ_ij·s(z), and the plane between rows j and j+1 beside column i is
/// y = y_{j+1/2} − σ_ij·s(z). So every horizontal section of a block is a rectangle,
/// (L + 2σs) × (L − 2σs): a σ = +1 block is wide at the top along x (it rests on its x
/// neighbours) and narrow at the top along y (its y neighbours rest on it); a σ = −1 block is
/// the same solid turned by 90° about z. All blocks are therefore one shape, baked once.
///
/// What tiles and what does not: neighbours share their cutting plane (coplanar, conforming,
/// flat on flat), but their faces are trapezoids of opposite taper, so the area in contact is
/// the hexagon where both overlap, (L − h)·t/cosθ with h = tanθ·t/2. At every grid vertex the
/// four surrounding blocks leave a square hole of side 2|s(z)| (closing at mid-thickness): no
/// convex blocks with these alternating faces can fill the slab. Each block's volume is
/// L²t − tan²θ·t³/3, the hole at a vertex is tan²θ·t³/3.
#pragma once

#include "lsdem/contact/RigidPose.h"
#include "lsdem/ls/MassProperties.h"

#include <array>
#include <string>
#include <vector>

namespace lsdem {

struct SlabPanelOptions
{
    int blocksPerSide = 5;     ///< n, odd so that one block sits at the centre
    double blockSize = 8.0;    ///< L, grid pitch, mm
    double thickness = 3.0;    ///< t, mm
    double angleDeg = 15.0;    ///< θ, interlocking angle, degrees
};

/// One block of the panel or of the frame.
struct SlabBlock
{
    int i = 0, j = 0;         ///< column (x) and row (y); −1 or n for frame blocks
    int sign = 1;             ///< σ = (−1)^(i+j)
    Vec3 center = Vec3::Zero();  ///< (x_i, y_j, t/2): the reference block's origin in the panel
    /// Maps the reference block (σ = +1, centred at the origin) onto this one: identity for
    /// σ = +1, a quarter turn about z for σ = −1. Panel point = rotation·reference + center.
    Mat3 rotation = Mat3::Identity();
    std::string name;         ///< "b<i>_<j>" for panel blocks, "frame_<W|E|S|N><k>" for the frame
};

/// A planar face of a block: four corners counter-clockwise seen from outside.
struct SlabFace
{
    std::array<Vec3, 4> corners;
    Vec3 normal = Vec3::Zero();  ///< unit, outward
};

class SlabPanel
{
public:
    /// @throw Error naming the bad option: n must be odd and ≥ 3, L, t > 0, 0 ≤ θ < 90°,
    ///        and h = tanθ·t/2 < 0.95·L/2 (else the narrow end of a face vanishes or is a sliver).
    explicit SlabPanel(const SlabPanelOptions& options);

    const SlabPanelOptions& options() const { return mOptions; }
    int n() const { return mOptions.blocksPerSide; }
    /// h = tanθ·t/2: how far a face leans out (or in) between mid-thickness and the top.
    double overhang() const { return mOverhang; }
    /// Exact volume of one block, L²t − tan²θ·t³/3 (mm³).
    double blockVolume() const;
    /// Exact area in contact between two neighbours, (L − h)·t/cosθ (mm²).
    double sharedFaceArea() const;

    /// The reference block (σ = +1, centred at the origin, z from −t/2 to t/2): corners 0–3
    /// the bottom counter-clockwise from (−x, −y), 4–7 the top likewise.
    std::array<Vec3, 8> referenceCorners() const;
    /// Its six faces: bottom, top, −x, +x, −y, +y.
    std::array<SlabFace, 6> referenceFaces() const;
    /// A closed, outward-oriented triangle mesh of the reference block (12 triangles): the
    /// input to bakeMesh. Remeshing (NodePlacement::Spacing) keeps its sharp edges.
    TriangleMesh referenceMesh() const;

    /// The n² panel blocks, index j·n + i.
    const std::vector<SlabBlock>& blocks() const { return mBlocks; }
    /// The 4n frame blocks (west, east, south, north of the panel).
    const std::vector<SlabBlock>& frame() const { return mFrame; }
    /// Index of the central block in blocks().
    int centralBlock() const { return (n() / 2) * n() + n() / 2; }

    /// Corners and faces of @a block in panel coordinates (block at rest).
    std::array<Vec3, 8> corners(const SlabBlock& block) const;
    std::array<SlabFace, 6> faces(const SlabBlock& block) const;
    /// The same, after the block has moved rigidly: panel point = R·(rest point − c0) + c, with
    /// c0 the block's rest centre (block.center) and c its current centre.
    std::array<SlabFace, 6> faces(const SlabBlock& block, const Mat3& rotation,
                                  const Vec3& currentCenter) const;

private:
    SlabBlock makeBlock(int i, int j, const std::string& name) const;

    SlabPanelOptions mOptions;
    double mOverhang = 0.0;
    std::vector<SlabBlock> mBlocks, mFrame;
};

/// Check the options; the messages name the command-line options of `lsdem-study slab`.
void checkSlabPanelOptions(const SlabPanelOptions& options);

/// Where a grain made from the baked reference block sits when it is @a block at rest: the
/// asset's frame is the principal frame of referenceMesh() (@a frame, GrainAsset::inputFrame).
RigidPose slabBlockPose(const SlabBlock& block, const PrincipalFrame& frame);

} // namespace lsdem
