/// @file NumberRange.h
/// @brief The ranges a number given by a user may be asked to lie in (a scene's settings, a
///        contact law's coefficients), with the words messages and docs use for them. NaN and
///        the infinities lie in none.
#pragma once

#include "lsdem/core/NumberText.h"

#include <cmath>
#include <optional>
#include <string>

namespace lsdem {

enum class NumberRange {
    Finite,            ///< any finite number
    Positive,          ///< > 0
    NonNegative,       ///< >= 0
    Fraction,          ///< in [0, 1)
    PositiveFraction,  ///< in (0, 1]
};

/// Whether @a value lies in @a range.
inline bool inNumberRange(NumberRange range, double value)
{
    if (!std::isfinite(value)) return false;
    switch (range) {
    case NumberRange::Finite: return true;
    case NumberRange::Positive: return value > 0.0;
    case NumberRange::NonNegative: return value >= 0.0;
    case NumberRange::Fraction: return value >= 0.0 && value < 1.0;
    case NumberRange::PositiveFraction: return value > 0.0 && value <= 1.0;
    }
    return false;
}

/// "finite", "> 0", ">= 0", "in [0, 1)", "in (0, 1]": "must be " + this reads as a rule.
inline std::string numberRangeText(NumberRange range)
{
    switch (range) {
    case NumberRange::Finite: return "finite";
    case NumberRange::Positive: return "> 0";
    case NumberRange::NonNegative: return ">= 0";
    case NumberRange::Fraction: return "in [0, 1)";
    case NumberRange::PositiveFraction: return "in (0, 1]";
    }
    return "";
}

/// "must be > 0 (got -1)" if @a value is not in @a range: the words every check of a user's
/// number uses (after the key it is about).
inline std::optional<std::string> outOfRange(NumberRange range, double value)
{
    if (inNumberRange(range, value)) return std::nullopt;
    return "must be " + numberRangeText(range) + " (got " + numberText(value) + ")";
}

} // namespace lsdem
