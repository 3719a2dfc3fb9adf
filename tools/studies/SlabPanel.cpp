#include "studies/SlabPanel.h"

#include "lsdem/core/NumberText.h"

#include "lsdem/core/Error.h"
#include "lsdem/core/Constants.h"

#include <cmath>
#include <sstream>

namespace lsdem {

namespace {

/// A quarter turn about z: maps the reference (σ = +1) block onto a σ = −1 block.
Mat3 quarterTurn()
{
    Mat3 r;
    r << 0, -1, 0, 1, 0, 0, 0, 0, 1;
    return r;
}

SlabFace makeFace(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
    SlabFace f;
    f.corners = {a, b, c, d};
    // Newell's normal: exact for a planar polygon, independent of which corner starts.
    Vec3 n = Vec3::Zero();
    for (int k = 0; k < 4; ++k) n += f.corners[k].cross(f.corners[(k + 1) % 4]);
    f.normal = n.normalized();
    return f;
}

} // namespace

void checkSlabPanelOptions(const SlabPanelOptions& o)
{
    if (o.blocksPerSide < 3 || o.blocksPerSide % 2 == 0 || o.blocksPerSide > 41)
        throw Error("", "--blocks must be an odd number from 3 to 41 (one block at the centre), got " +
                            std::to_string(o.blocksPerSide),
                    "e.g. --blocks 5");
    auto positive = [](double v, const std::string& option, const std::string& example) {
        if (!(v > 0.0) || !std::isfinite(v))
            throw Error("", option + " must be a positive length in mm, got " + roundedText(v),
                        "e.g. " + option + " " + example);
    };
    positive(o.blockSize, "--block-size", "8");
    positive(o.thickness, "--thickness", "3");
    if (!(o.angleDeg >= 0.0 && o.angleDeg < 90.0))
        throw Error("", "--angle must be in [0, 90) degrees, got " + roundedText(o.angleDeg),
                    "e.g. --angle 15");
    const double h = std::tan(o.angleDeg * kPi / 180.0) * 0.5 * o.thickness;
    if (!(h < 0.5 * o.blockSize * 0.95))
        throw Error("", "the faces lean out by tan(angle)·t/2 = " + roundedText(h) +
                            " mm, too close to half the block size " + roundedText(0.5 * o.blockSize) +
                            " (the narrow ends of the blocks vanish)",
                    "use a smaller --angle or --thickness, or a larger --block-size");
}

SlabPanel::SlabPanel(const SlabPanelOptions& options) : mOptions(options)
{
    checkSlabPanelOptions(options);
    mOverhang = std::tan(options.angleDeg * kPi / 180.0) * 0.5 * options.thickness;
    const int count = n();
    for (int j = 0; j < count; ++j)
        for (int i = 0; i < count; ++i)
            mBlocks.push_back(makeBlock(i, j, "b" + std::to_string(i) + "_" + std::to_string(j)));
    for (int k = 0; k < count; ++k) mFrame.push_back(makeBlock(-1, k, "frame_W" + std::to_string(k)));
    for (int k = 0; k < count; ++k) mFrame.push_back(makeBlock(count, k, "frame_E" + std::to_string(k)));
    for (int k = 0; k < count; ++k) mFrame.push_back(makeBlock(k, -1, "frame_S" + std::to_string(k)));
    for (int k = 0; k < count; ++k) mFrame.push_back(makeBlock(k, count, "frame_N" + std::to_string(k)));
}

SlabBlock SlabPanel::makeBlock(int i, int j, const std::string& name) const
{
    SlabBlock b;
    b.i = i;
    b.j = j;
    b.sign = ((i + j) % 2 == 0) ? 1 : -1;  // (i + j) may be negative: −1 is odd
    const double mid = 0.5 * (n() - 1);
    b.center = Vec3((i - mid) * mOptions.blockSize, (j - mid) * mOptions.blockSize,
                    0.5 * mOptions.thickness);
    b.rotation = b.sign > 0 ? Mat3::Identity() : quarterTurn();
    b.name = name;
    return b;
}

double SlabPanel::blockVolume() const
{
    // Section (L + 2s)(L − 2s) = L² − 4s², s = tanθ·(z − t/2): ∫ over z gives L²t − 4tan²θ·t³/12.
    const double L = mOptions.blockSize, t = mOptions.thickness;
    const double tanTheta = std::tan(mOptions.angleDeg * kPi / 180.0);
    return L * L * t - tanTheta * tanTheta * t * t * t / 3.0;
}

double SlabPanel::sharedFaceArea() const
{
    // Width in contact L − 2|s(z)| over the slant height dz/cosθ.
    const double cosTheta = std::cos(mOptions.angleDeg * kPi / 180.0);
    return (mOptions.blockSize - mOverhang) * mOptions.thickness / cosTheta;
}

std::array<Vec3, 8> SlabPanel::referenceCorners() const
{
    const double half = 0.5 * mOptions.blockSize, h = mOverhang, zt = 0.5 * mOptions.thickness;
    const double narrow = half - h, wide = half + h;
    // Bottom: narrow along x, wide along y; top: wide along x, narrow along y.
    return {Vec3(-narrow, -wide, -zt), Vec3(narrow, -wide, -zt), Vec3(narrow, wide, -zt),
            Vec3(-narrow, wide, -zt),  Vec3(-wide, -narrow, zt), Vec3(wide, -narrow, zt),
            Vec3(wide, narrow, zt),    Vec3(-wide, narrow, zt)};
}

std::array<SlabFace, 6> SlabPanel::referenceFaces() const
{
    const std::array<Vec3, 8> c = referenceCorners();
    return {makeFace(c[0], c[3], c[2], c[1]),   // bottom (−z)
            makeFace(c[4], c[5], c[6], c[7]),   // top (+z)
            makeFace(c[0], c[4], c[7], c[3]),   // −x
            makeFace(c[1], c[2], c[6], c[5]),   // +x
            makeFace(c[0], c[1], c[5], c[4]),   // −y
            makeFace(c[2], c[3], c[7], c[6])};  // +y
}

TriangleMesh SlabPanel::referenceMesh() const
{
    TriangleMesh mesh;
    const std::array<Vec3, 8> c = referenceCorners();
    mesh.vertices.assign(c.begin(), c.end());
    // The faces of referenceFaces by corner index, each split along one diagonal.
    const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 4, 7, 3},
                             {1, 2, 6, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}};
    for (const auto& q : quads) {
        mesh.triangles.push_back({q[0], q[1], q[2]});
        mesh.triangles.push_back({q[0], q[2], q[3]});
    }
    return mesh;
}

std::array<Vec3, 8> SlabPanel::corners(const SlabBlock& block) const
{
    std::array<Vec3, 8> c = referenceCorners();
    for (Vec3& v : c) v = block.rotation * v + block.center;
    return c;
}

std::array<SlabFace, 6> SlabPanel::faces(const SlabBlock& block) const
{
    return faces(block, Mat3::Identity(), block.center);
}

std::array<SlabFace, 6> SlabPanel::faces(const SlabBlock& block, const Mat3& rotation,
                                         const Vec3& currentCenter) const
{
    std::array<SlabFace, 6> f = referenceFaces();
    const Mat3 r = rotation * block.rotation;
    for (SlabFace& face : f) {
        for (Vec3& v : face.corners) v = r * v + currentCenter;
        face.normal = r * face.normal;
    }
    return f;
}

RigidPose slabBlockPose(const SlabBlock& block, const PrincipalFrame& frame)
{
    // x_asset = F·(x_ref − c) and x_panel = B·x_ref + b, so x_panel = B·Fᵀ·x_asset + (B·c + b).
    RigidPose pose;
    pose.position = block.rotation * frame.centroid + block.center;
    pose.orientation = Quat(Mat3(block.rotation * frame.rotation.transpose())).normalized();
    return pose;
}

} // namespace lsdem
