/// @file PointHashGrid.h
/// @brief A hash grid of points: the points in each cube of a given side, for searches among a
///        point's neighbours (nodeSpacing's nearest node, NodeShape's neighbours, the grains near
///        each grain of NonAffineMotion).
#pragma once

#include "lsdem/core/Vec3.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

namespace lsdem {

class PointHashGrid
{
public:
    /// Cells of side @a cell from the positions' lowest corner.
    PointHashGrid(const std::vector<Vec3>& positions, double cell) : mCell(cell)
    {
        mLow = Vec3::Constant(std::numeric_limits<double>::infinity());
        mHigh = -mLow;
        for (const Vec3& p : positions) {
            mLow = mLow.cwiseMin(p);
            mHigh = mHigh.cwiseMax(p);
        }
        for (size_t i = 0; i < positions.size(); ++i)
            mCells[key(cellOf(positions[i]))].push_back(static_cast<int>(i));
    }

    Eigen::Vector3i cellOf(const Vec3& p) const
    {
        return Eigen::Vector3i(static_cast<int>(std::floor((p.x() - mLow.x()) / mCell)),
                               static_cast<int>(std::floor((p.y() - mLow.y()) / mCell)),
                               static_cast<int>(std::floor((p.z() - mLow.z()) / mCell)));
    }
    /// The nodes in cell @a c (none: null).
    const std::vector<int>* nodesIn(const Eigen::Vector3i& c) const
    {
        const auto it = mCells.find(key(c));
        return it == mCells.end() ? nullptr : &it->second;
    }
    /// Call @a visit(j) for every point j in the 27 cells around cell @a c (cell by cell, each
    /// in the order its points were given): every point within one cell side of a point of c.
    template <typename Visit>
    void around(const Eigen::Vector3i& c, Visit&& visit) const
    {
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const std::vector<int>* inCell = nodesIn(c + Eigen::Vector3i(dx, dy, dz));
                    if (!inCell) continue;
                    for (const int j : *inCell) visit(j);
                }
    }
    /// The most cells the positions span along an axis.
    int cellsAcross() const { return static_cast<int>(((mHigh - mLow) / mCell).maxCoeff()) + 1; }

private:
    /// Three cell coordinates (each offset by one so the −1 neighbours of the first cell stay
    /// non-negative) packed into 21 bits apiece; shifting unsigned values is well defined.
    static int64_t key(const Eigen::Vector3i& c)
    {
        const auto field = [](int v) { return uint64_t(int64_t(v) + 1) & 0x1FFFFFu; };
        return int64_t((field(c.x()) << 42) | (field(c.y()) << 21) | field(c.z()));
    }

    double mCell;
    Vec3 mLow, mHigh;
    std::unordered_map<int64_t, std::vector<int>> mCells;
};

} // namespace lsdem
