/// @file VerifyReport.h
/// @brief What the verification suite finds: checks (a quantity lsdem computed against its
///        reference, with the tolerance and why), series (the curves of its figures) and
///        frames (grains to see in ParaView).
#pragma once

#include "lsdem/contact/RigidPose.h"

#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace lsdem {
struct GrainAsset;
}

namespace lsdem::verify {

/// One quantity of one case against its reference. The error is (value − reference)/scale:
/// relative when scale is the reference itself, otherwise against a stated scale (a rebound
/// speed against the impact speed, say, where the reference may be zero).
struct Check
{
    std::string caseName;     ///< "normal-wall", "oblique-wall 30°", ...
    std::string formulation;  ///< "adapted", ..., or "-" for no contact law
    std::string quantity;     ///< "max overlap", ...
    std::string unit;         ///< "mm", "N", "s", "" (dimensionless)
    double reference = 0.0;
    double value = 0.0;
    double scale = 1.0;       ///< the error's denominator (> 0)
    double tolerance = 0.0;   ///< on |error|
    std::string basis;        ///< where the tolerance comes from (docs/verification.md)
    /// Shown, not judged: a configuration the law is known not to resolve, kept in the table
    /// so the figure the issue asked for is reported (its basis says why).
    bool informative = false;

    double error() const { return (value - reference) / scale; }
    bool passes() const { return informative || std::abs(error()) <= tolerance; }
};

/// The data of a figure: named columns, one row per point.
struct Series
{
    std::string name;  ///< file stem: verify_<name>.csv
    std::vector<std::string> columns;
    std::vector<std::vector<double>> rows;
};

/// One frame of a case for ParaView: the grains' shapes and poses at one time.
struct VerifyFrame
{
    struct Grain
    {
        std::shared_ptr<const GrainAsset> asset;
        RigidPose pose;
    };
    double time = 0.0;  ///< since the case's start, s
    std::vector<Grain> grains;
};

/// A case's frames: written by the command as `<name>_frames/frames.pvd` and its files.
struct FrameSeries
{
    std::string name;
    std::vector<VerifyFrame> frames;
};

struct Report
{
    std::vector<Check> checks;
    std::vector<Series> series;
    std::vector<FrameSeries> frames;

    void add(Check c) { checks.push_back(std::move(c)); }
    bool allPass() const;
    int failures() const;
};

/// The checks as CSV (case, formulation, quantity, unit, reference, value, error, tolerance,
/// pass, basis), written atomically to @a path.
void writeChecksCsv(const Report& report, const std::string& path);
/// A series as CSV, written atomically to @a path.
void writeSeriesCsv(const Series& series, const std::string& path);

} // namespace lsdem::verify
