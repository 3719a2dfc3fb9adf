#include "lsdem/simulation/NonAffineMotion.h"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace lsdem {

namespace {

/// Cells of side @a side holding the grains whose centres fall in them.
class CentreCells
{
public:
    CentreCells(const std::vector<Vec3>& centres, double side) : mSide(side)
    {
        for (size_t i = 0; i < centres.size(); ++i)
            mCells[key(cellOf(centres[i]))].push_back(static_cast<int>(i));
    }
    Eigen::Vector3i cellOf(const Vec3& x) const
    {
        return Eigen::Vector3i(int(std::floor(x.x() / mSide)), int(std::floor(x.y() / mSide)),
                               int(std::floor(x.z() / mSide)));
    }
    /// Call @a visit(j) for every grain in the 27 cells around cell @a c.
    template <typename Visit>
    void around(const Eigen::Vector3i& c, Visit&& visit) const
    {
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const auto it = mCells.find(key(c + Eigen::Vector3i(dx, dy, dz)));
                    if (it == mCells.end()) continue;
                    for (const int j : it->second) visit(j);
                }
    }

private:
    /// Three cell coordinates in 21 bits each (offset so negative ones pack too).
    static int64_t key(const Eigen::Vector3i& c)
    {
        const auto field = [](int v) { return uint64_t(int64_t(v) + (1 << 20)) & 0x1FFFFFu; };
        return int64_t((field(c.x()) << 42) | (field(c.y()) << 21) | field(c.z()));
    }

    double mSide;
    std::unordered_map<int64_t, std::vector<int>> mCells;
};

} // namespace

std::vector<std::vector<int>> neighboursWithin(const std::vector<Vec3>& centres,
                                               const std::vector<double>& radii, double reach)
{
    std::vector<std::vector<int>> out(centres.size());
    if (centres.empty()) return out;
    // Two grains within reach·(r_i + r_j) are within 2·reach·r_max: cells that wide hold
    // every neighbour in the 27 around a grain's.
    const double side = std::max(2.0 * reach * *std::max_element(radii.begin(), radii.end()), 1e-300);
    const CentreCells cells(centres, side);
    for (size_t i = 0; i < centres.size(); ++i) {
        cells.around(cells.cellOf(centres[i]), [&](int j) {
            if (j == static_cast<int>(i)) return;
            const double limit = reach * (radii[i] + radii[size_t(j)]);
            if ((centres[size_t(j)] - centres[i]).squaredNorm() < limit * limit) out[i].push_back(j);
        });
        std::sort(out[i].begin(), out[i].end());
    }
    return out;
}

std::vector<double> nonAffineDisplacement(const std::vector<Vec3>& reference,
                                          const std::vector<Vec3>& current,
                                          const std::vector<std::vector<int>>& neighbours)
{
    std::vector<double> out(reference.size(), 0.0);
    for (size_t i = 0; i < reference.size(); ++i) {
        if (neighbours[i].empty()) continue;
        Mat3 x = Mat3::Zero(), y = Mat3::Zero();
        for (const int j : neighbours[i]) {
            const Vec3 was = reference[size_t(j)] - reference[i], now = current[size_t(j)] - current[i];
            x += now * was.transpose();
            y += was * was.transpose();
        }
        const Mat3 j = x * y.completeOrthogonalDecomposition().pseudoInverse();
        double sum = 0.0;
        for (const int k : neighbours[i]) {
            const Vec3 was = reference[size_t(k)] - reference[i], now = current[size_t(k)] - current[i];
            sum += (now - j * was).squaredNorm();
        }
        out[i] = sum;
    }
    return out;
}

} // namespace lsdem
