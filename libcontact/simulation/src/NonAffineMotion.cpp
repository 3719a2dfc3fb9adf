#include "lsdem/simulation/NonAffineMotion.h"

#include "lsdem/core/PointHashGrid.h"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>

namespace lsdem {

std::vector<std::vector<int>> neighboursWithin(const std::vector<Vec3>& centres,
                                               const std::vector<double>& radii, double reach)
{
    std::vector<std::vector<int>> out(centres.size());
    if (centres.empty()) return out;
    // Two grains within reach·(r_i + r_j) are within 2·reach·r_max: cells that wide hold
    // every neighbour in the 27 around a grain's.
    const double side = std::max(2.0 * reach * *std::max_element(radii.begin(), radii.end()), 1e-300);
    const PointHashGrid cells(centres, side);
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
