// The silo's settled fill as Beverloo's law reads it (SiloFill.h).
#include "studies/verify/SiloFill.h"

#include "lsdem/core/Constants.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace lsdem::verify {

double fillSurface(const World& w, double size)
{
    const double width = 2.0 * size;
    std::map<std::pair<long long, long long>, double> highest;
    for (const Grain& g : w.grains) {
        const Vec3& x = g.body.pose.position;
        const std::pair<long long, long long> column{static_cast<long long>(std::floor(x.x() / width)),
                                                     static_cast<long long>(std::floor(x.y() / width))};
        const auto [at, added] = highest.emplace(column, x.z());
        if (!added) at->second = std::max(at->second, x.z());
    }
    if (highest.empty()) return 0.0;
    std::vector<double> tops;
    tops.reserve(highest.size());
    for (const auto& [column, z] : highest) tops.push_back(z);
    std::sort(tops.begin(), tops.end());
    const size_t n = tops.size();
    return n % 2 == 1 ? tops[n / 2] : 0.5 * (tops[n / 2 - 1] + tops[n / 2]);
}

double bulkDensity(const World& w, const SiloPlan& p, double size)
{
    const double radius = p.siloRadius - 2.0 * size;
    const double bottom = 0.5 * p.plateThickness + 2.0 * size;
    const double height = fillSurface(w, size) - 2.0 * size - bottom;
    if (!(radius > 0.0) || !(height > 0.0)) return 0.0;
    double mass = 0.0;
    for (const Grain& g : w.grains) {
        const Vec3& x = g.body.pose.position;
        if (std::hypot(x.x(), x.y()) < radius && x.z() > bottom && x.z() < bottom + height)
            mass += g.body.mass;
    }
    return mass / (kPi * radius * radius * height);
}

} // namespace lsdem::verify
