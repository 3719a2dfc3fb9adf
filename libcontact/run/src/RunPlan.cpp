#include "RunPlan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace lsdem::runplan {

long long stepsPer(double period, double dt)
{
    const double steps = std::round(period / dt);
    return steps < 1.0 ? 1 : steps > 1e18 ? static_cast<long long>(1e18)
                                          : static_cast<long long>(steps);
}

double plannedSteps(const Scene& scene, const World& w, double dt)
{
    double planned = -1.0;
    auto consider = [&](double n) { planned = planned < 0.0 ? n : std::min(planned, n); };
    if (scene.end.steps > 0) consider(static_cast<double>(scene.end.steps));
    if (scene.end.time > 0.0) consider(std::ceil(scene.end.time / dt - 1e-9));
    if (scene.end.boundary >= 0) {
        const double speed = w.boundaries[scene.end.boundary].velocity.norm();
        if (speed > 0.0) consider(std::ceil(scene.end.displacement / (speed * dt)));
    }
    return planned;
}

std::string formatDuration(double seconds)
{
    char buffer[48];
    const double day = 86400.0, year = 365.25 * day;
    if (!std::isfinite(seconds)) return "forever";
    if (seconds < 60)
        std::snprintf(buffer, sizeof buffer, "%.0fs", seconds);
    else if (seconds < 3600)
        std::snprintf(buffer, sizeof buffer, "%dm%02ds", int(seconds) / 60, int(seconds) % 60);
    else if (seconds < 2 * day)
        std::snprintf(buffer, sizeof buffer, "%dh%02dm", int(seconds) / 3600,
                      (int(seconds) / 60) % 60);
    else if (seconds < year)
        std::snprintf(buffer, sizeof buffer, "%.0fd", seconds / day);
    else
        std::snprintf(buffer, sizeof buffer, "%.2g years", seconds / year);
    return buffer;
}

std::string longRunWarning(const Scene& scene, double planned, double dt, double secondsPerStep)
{
    const double seconds = planned * secondsPerStep;
    if (!(planned > 1e9 || seconds > 7 * 86400.0)) return "";
    std::ostringstream s;
    s.precision(3);
    s << "the end condition (";
    const char* separator = "";
    if (scene.end.time > 0.0) s << separator << "end_time = " << scene.end.time, separator = ", ";
    if (scene.end.steps > 0) s << separator << "end_steps = " << scene.end.steps, separator = ", ";
    if (scene.end.boundary >= 0)
        s << separator << "end_displacement = " << scene.end.displacement << " of '"
          << scene.boundaries[scene.end.boundary].name << "'";
    s << ") means " << planned << " steps of " << dt << ": about " << formatDuration(seconds)
      << " at the speed of the first force evaluation; is that what you meant? (stop with "
         "Ctrl-C, which writes a checkpoint)";
    return s.str();
}

} // namespace lsdem::runplan
