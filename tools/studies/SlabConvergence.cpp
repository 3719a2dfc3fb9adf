#include "studies/SlabConvergence.h"

#include "studies/SlabFailure.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lsdem {

double slabCurveDifference(const std::vector<SlabSample>& a, const std::vector<SlabSample>& b,
                           bool wholeCurve)
{
    if (a.size() < 2 || b.empty()) return std::numeric_limits<double>::infinity();
    double peakA = 0.0, peakB = 0.0, peakDelta = 0.0;
    for (const SlabSample& s : a) peakA = std::max(peakA, s.force);
    for (const SlabSample& s : b)
        if (s.force > peakB) {
            peakB = s.force;
            peakDelta = s.delta;
        }
    if (!(peakB > 0.0)) return std::numeric_limits<double>::infinity();
    const double end = wholeCurve ? b.back().delta : peakDelta;
    double sum = 0.0;
    int count = 0;
    size_t k = 0;
    for (const SlabSample& s : b) {
        if (s.delta > end || s.delta > a.back().delta) break;
        while (k + 2 < a.size() && a[k + 1].delta < s.delta) ++k;
        const SlabSample &u = a[k], &v = a[k + 1];
        const double span = v.delta - u.delta;
        const double w = span > 0 ? std::clamp((s.delta - u.delta) / span, 0.0, 1.0) : 0.0;
        const double pa = u.force + w * (v.force - u.force);
        sum += (pa - s.force) * (pa - s.force);
        ++count;
    }
    if (count == 0) return std::numeric_limits<double>::infinity();
    const double rms = std::sqrt(sum / count) / peakB;
    return wholeCurve ? rms : std::max(rms, std::abs(peakA - peakB) / peakB);
}

int slabConvergedRun(const SlabPanel& panel, const std::vector<SlabRunResult>& runs,
                     const std::vector<int>& series, double tolerance, bool& converged)
{
    converged = false;
    if (series.empty()) return -1;
    const int finest = series.back();
    if (runs[finest].stopped) return finest;  // no reference to converge to
    const SlabFailureMode mode = slabFailureMode(panel, runs[finest]);
    int chosen = finest;
    for (int k = int(series.size()) - 2; k >= 0; --k) {
        const SlabRunResult& r = runs[series[k]];
        if (r.stopped || slabFailureMode(panel, r) != mode ||
            slabCurveDifference(r.curve, runs[finest].curve) > tolerance)
            break;
        chosen = series[k];
        converged = true;
    }
    return chosen;
}

} // namespace lsdem
