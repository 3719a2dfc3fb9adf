/// @file EntryRules.h
/// @brief The rules of single entries' numbers that several front ends check: a material's
///        density, a grain's orientation. The scene reader, the grains CSV reader,
///        validateScene and Python ask these, so each refuses a value in the same words.
#pragma once

#include "lsdem/contact/RigidPose.h"
#include "lsdem/core/Vec3.h"

#include <optional>
#include <string>

namespace lsdem {

/// A rule an entry's keys break (a servo wall's, a boundary's, a grain's): the key at fault (""
/// for the entry as a whole, e.g. a missing key), what is wrong, the fix. A file's reader shows
/// it at the key's line; Python and validateScene by keyProblemText.
struct KeyProblem
{
    std::string key, problem, fix;
};

/// A vector given under @a key that holds a NaN or an infinity, if it is given and does.
inline std::optional<KeyProblem> nonFiniteProblem(const char* key, const std::optional<Vec3>& v)
{
    if (v && !v->allFinite())
        return KeyProblem{key, "holds a value that is not finite", "give finite numbers"};
    return std::nullopt;
}

/// "radius must be > 0 (got 0)": the key, then the problem.
inline std::string keyProblemText(const KeyProblem& p)
{
    return p.key.empty() ? p.problem : p.key + " " + p.problem;
}

/// A material's density (mass/length³) is >= 0 (0 for a material only boundaries use):
/// "must be >= 0 (got -1)" if @a density is not.
std::optional<std::string> densityProblem(double density);
/// The advice that goes with densityProblem.
extern const char* const kDensityFix;

/// How far from 1 a given orientation's norm may be: a scene's and Python's quaternions are
/// written to many digits; a grains table's may come from another code, printed with fewer.
inline constexpr double kOrientationTolerance = 1e-6;
inline constexpr double kTableOrientationTolerance = 1e-4;

/// What is wrong with @a q as an orientation, if anything: "is not a rotation (zero
/// quaternion)", or "is not a unit quaternion (norm 1.2)" beyond @a tolerance.
std::optional<std::string> orientationProblem(const Quat& q,
                                              double tolerance = kOrientationTolerance);
/// The advice that goes with orientationProblem.
extern const char* const kOrientationFix;

} // namespace lsdem
