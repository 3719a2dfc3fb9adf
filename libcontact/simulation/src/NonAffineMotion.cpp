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

namespace {

/// D²min of one grain from its neighbours' relative positions in the reference (@a was) and
/// now (@a now), the neighbour's k-th as given by @a relative(k, was, now).
template <class Relative>
double nonAffineOf(size_t count, Relative relative)
{
    Mat3 x = Mat3::Zero(), y = Mat3::Zero();
    Vec3 was, now;
    for (size_t k = 0; k < count; ++k) {
        relative(k, was, now);
        x += now * was.transpose();
        y += was * was.transpose();
    }
    const Mat3 j = x * y.completeOrthogonalDecomposition().pseudoInverse();
    double sum = 0.0;
    for (size_t k = 0; k < count; ++k) {
        relative(k, was, now);
        sum += (now - j * was).squaredNorm();
    }
    return sum;
}

} // namespace

std::vector<double> nonAffineDisplacement(const std::vector<Vec3>& reference,
                                          const std::vector<Vec3>& current,
                                          const std::vector<std::vector<int>>& neighbours)
{
    std::vector<double> out(reference.size(), 0.0);
    for (size_t i = 0; i < reference.size(); ++i) {
        const std::vector<int>& near = neighbours[i];
        if (near.empty()) continue;
        out[i] = nonAffineOf(near.size(), [&](size_t k, Vec3& was, Vec3& now) {
            was = reference[size_t(near[k])] - reference[i];
            now = current[size_t(near[k])] - current[i];
        });
    }
    return out;
}

std::vector<std::vector<PeriodicNeighbour>> neighboursWithin(const std::vector<Vec3>& centres,
                                                             const std::vector<double>& radii,
                                                             double reach, const PeriodicCell& cell)
{
    // The grains and the images of those near the faces, searched together: a grain's
    // neighbours beyond the grains (index n and up) are images.
    const size_t n = centres.size();
    std::vector<Vec3> all = centres;
    std::vector<double> allRadii = radii;
    std::vector<PeriodicNeighbour> images;
    const double largest = radii.empty() ? 0.0 : *std::max_element(radii.begin(), radii.end());
    for (size_t i = 0; i < n; ++i)
        for (const Vec3& periods : cell.imagePeriodsNear(centres[i], 2.0 * reach * largest)) {
            images.push_back({int(i), periods});
            all.push_back(centres[i] + cell.imageShift(periods));
            allRadii.push_back(radii[i]);
        }
    const std::vector<std::vector<int>> found = neighboursWithin(all, allRadii, reach);
    std::vector<std::vector<PeriodicNeighbour>> out(n);
    for (size_t i = 0; i < n; ++i)
        for (int j : found[i]) {
            if (size_t(j) < n) {
                out[i].push_back({j, Vec3::Zero()});
            } else if (images[size_t(j) - n].grain != int(i)) {  // (never its own image: the
                out[i].push_back(images[size_t(j) - n]);           //  cell is 4.5 radii wide)
            }
        }
    return out;
}

std::vector<double> nonAffineDisplacement(const std::vector<Vec3>& reference,
                                          const Vec3& referenceSize,
                                          const std::vector<Vec3>& current,
                                          const Vec3& currentSize,
                                          const std::vector<std::vector<PeriodicNeighbour>>& neighbours)
{
    std::vector<double> out(reference.size(), 0.0);
    for (size_t i = 0; i < reference.size(); ++i) {
        const std::vector<PeriodicNeighbour>& near = neighbours[i];
        if (near.empty()) continue;
        out[i] = nonAffineOf(near.size(), [&](size_t k, Vec3& was, Vec3& now) {
            const size_t j = size_t(near[k].grain);
            const Vec3& periods = near[k].periods;
            was = reference[j] + periods.cwiseProduct(referenceSize) - reference[i];
            now = current[j] + periods.cwiseProduct(currentSize) - current[i];
        });
    }
    return out;
}

} // namespace lsdem
