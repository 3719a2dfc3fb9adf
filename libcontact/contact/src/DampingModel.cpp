#include "lsdem/contact/DampingModel.h"

#include "lsdem/core/Constants.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

namespace lsdem {

namespace {

/// Runge–Kutta steps per unit of the one-body equation's time: e to about 2e-4 (the equation
/// is not smooth where x = 0 or where the force lets go, which limits RK4 to first order
/// there).
constexpr int kStepsPerUnitTime = 2000;

/// x'' of the one-body equation (DampingModel.h) at penetration @a x and rate @a v: the spring
/// and the dashpot, together never attracting.
double acceleration(double x, double v, double ratio, double exponent)
{
    if (x <= 0.0) return 0.0;
    // sqrt(p·x^(p−1)) and x^p from one logarithm.
    const double logX = std::log(x);
    const double stiffnessRoot = std::sqrt(exponent) * std::exp(0.5 * (exponent - 1.0) * logX);
    return -std::max(0.0, std::exp(exponent * logX) + 2.0 * ratio * stiffnessRoot * v);
}

/// The linear spring-dashpot's β for @a restitution (the damped oscillator's half period, when
/// the dashpot may pull): a first guess, near the answer for small damping.
double linearRatio(double restitution)
{
    const double logE = std::log(restitution);
    return -logE / std::sqrt(kPi * kPi + logE * logE);
}

/// The table of β over exponents for one restitution, computed once per value and shared:
/// scenes and studies build many worlds with the same few restitutions.
std::array<double, ViscousDamping::kTableSize> ratioTable(double restitution)
{
    static std::mutex lock;
    static std::map<double, std::array<double, ViscousDamping::kTableSize>> tables;
    {
        const std::lock_guard<std::mutex> guard(lock);
        const auto it = tables.find(restitution);
        if (it != tables.end()) return it->second;
    }
    std::array<double, ViscousDamping::kTableSize> table{};
    for (int k = 0; k < ViscousDamping::kTableSize; ++k)
        table[size_t(k)] = dampingRatioFor(restitution, 1.0 + k * ViscousDamping::kExponentStep);
    const std::lock_guard<std::mutex> guard(lock);
    tables.emplace(restitution, table);
    return table;
}

} // namespace

double restitutionOfImpact(double ratio, double exponent)
{
    if (!(ratio >= 0.0) || !(exponent >= 1.0))
        throw std::invalid_argument("restitutionOfImpact: needs ratio >= 0 and exponent >= 1");
    if (ratio == 0.0) return 1.0;  // no dashpot: the equation conserves x'²/2 + x^(p+1)/(p+1)
    // Classical Runge–Kutta from x = 0, x' = 1 until x crosses 0 again; the crossing's speed
    // by linear interpolation within the last step (once the force has let go, the body
    // coasts). The undamped contact lasts under 3.2 time units for p ≤ 4
    // (2·∫₀¹ dx/sqrt(1 − x^(p+1)) ≤ π); a damped one that is still inside after 200 has crept to
    // rest: it leaves at no speed.
    constexpr double h = 1.0 / kStepsPerUnitTime;
    double x = 0.0, v = 1.0;
    for (long step = 0; step < 200 * kStepsPerUnitTime; ++step) {
        const auto a = [&](double xx, double vv) { return acceleration(xx, vv, ratio, exponent); };
        const double k1x = v, k1v = a(x, v);
        const double k2x = v + 0.5 * h * k1v, k2v = a(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
        const double k3x = v + 0.5 * h * k2v, k3v = a(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
        const double k4x = v + h * k3v, k4v = a(x + h * k3x, v + h * k3v);
        const double xNext = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        const double vNext = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        if (step > 0 && xNext <= 0.0) {
            const double s = x / (x - xNext);  // where in the step x reaches 0
            return std::max(0.0, -(v + s * (vNext - v)));
        }
        x = xNext;
        v = vNext;
        // Leaving, with the force let go: the body coasts out at this speed, exactly (the
        // spring's share against the dashpot's, x^((p+1)/2) / (2β·sqrt(p)·|x'|), only falls as
        // x does at a constant x', so the force never takes hold again). A heavily damped
        // impact would otherwise creep out over thousands of steps.
        if (v < 0.0 && x > 0.0 && acceleration(x, v, ratio, exponent) == 0.0) return -v;
    }
    return 0.0;
}

double dampingRatioFor(double restitution, double exponent)
{
    if (!(restitution > 0.0 && restitution <= 1.0))
        throw std::invalid_argument("dampingRatioFor: restitution must be in (0, 1], got " +
                                    std::to_string(restitution));
    if (restitution == 1.0) return 0.0;
    // e(β) falls from 1 as β grows: bracket the root from the pulling linear spring-dashpot's
    // β, then regula falsi with the Illinois modification (superlinear, and the bracket always
    // holds the root).
    double low = 0.0, high = std::max(linearRatio(restitution), 1e-3);
    double eLow = 1.0, eHigh = restitutionOfImpact(high, exponent);
    while (eHigh > restitution) {
        low = high;
        eLow = eHigh;
        high *= 2.0;
        if (high > 1e6)
            throw std::invalid_argument("dampingRatioFor: restitution " +
                                        std::to_string(restitution) + " is out of reach");
        eHigh = restitutionOfImpact(high, exponent);
    }
    // f(β) = e(β) − e_target: positive at low, not positive at high.
    double fLow = eLow - restitution, fHigh = eHigh - restitution;
    int lastMoved = 0;  // which end moved last: -1 low, +1 high
    for (int iteration = 0; iteration < 200; ++iteration) {
        const double guess = high - fHigh * (high - low) / (fHigh - fLow);
        const double f = restitutionOfImpact(guess, exponent) - restitution;
        if (std::abs(f) < 1e-13 || high - low < 1e-14 * high) return guess;
        if (f > 0.0) {
            low = guess;
            fLow = f;
            if (lastMoved == -1) fHigh *= 0.5;  // the same end twice: halve the other's weight
            lastMoved = -1;
        } else {
            high = guess;
            fHigh = f;
            if (lastMoved == +1) fLow *= 0.5;
            lastMoved = +1;
        }
    }
    return 0.5 * (low + high);
}

ViscousDamping::ViscousDamping(double restitution) : mRestitution(restitution)
{
    if (!(restitution > 0.0 && restitution <= 1.0))
        throw std::invalid_argument("ViscousDamping: restitution must be in (0, 1], got " +
                                    std::to_string(restitution));
    if (restitution == 1.0) return;
    mRatios = ratioTable(restitution);
    mLargestRatio = *std::max_element(mRatios.begin(), mRatios.end());
}

double ViscousDamping::ratio(double exponent) const
{
    if (!active()) return 0.0;
    const double position =
        (std::clamp(exponent, 1.0, kLargestExponent) - 1.0) / kExponentStep;
    const int k = std::min(static_cast<int>(position), kTableSize - 2);
    const double s = position - k;
    return (1.0 - s) * mRatios[size_t(k)] + s * mRatios[size_t(k) + 1];
}

double ViscousDamping::dashpot(double effectiveMass, double stiffness, double exponent) const
{
    if (!active() || !(stiffness > 0.0) || !(effectiveMass > 0.0)) return 0.0;
    return 2.0 * ratio(exponent) * std::sqrt(effectiveMass * stiffness);
}

} // namespace lsdem
