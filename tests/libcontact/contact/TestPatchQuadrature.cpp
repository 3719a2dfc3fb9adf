// Patch quadrature (PatchQuadrature.h): the integrals of d⁺ over a node's disk, for
// d(u) = d0 + g·u − ½·uᵀCu, against references computed here without the code under test:
// the closed forms of a disk wholly in contact and of a circular segment (a linear field), and a
// brute-force polar midpoint grid for general quadratics (saddles, bowls, islands off the
// centre). Also: nothing from a patch wholly clear, patchPeakBound above the true maximum, no
// jump where integratePatch switches from its closed form to its rays, a patch given by its
// extents along the rays (a disk; a square Voronoi cell), patchDepth's second-order geometry
// against exact distances, fillPatchContact's means, and the quadrature's names.
#include "lsdem/contact/PatchQuadrature.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace lsdem;

namespace {

double depthAt(const PatchDepth& d, double u1, double u2)
{
    return d.d0 + d.g1 * u1 + d.g2 * u2 -
           0.5 * (d.c11 * u1 * u1 + 2.0 * d.c12 * u1 * u2 + d.c22 * u2 * u2);
}

PatchDepth quadratic(double d0, double g1, double g2, double c11, double c12, double c22)
{
    PatchDepth d;
    d.d0 = d0;
    d.g1 = g1;
    d.g2 = g2;
    d.c11 = c11;
    d.c12 = c12;
    d.c22 = c22;
    return d;
}

/// The integrals of d⁺ over the disk by the midpoint rule on a polar grid of @a rings × @a
/// sectors cells (the rim is exact; only the cells the zero line of d crosses err), with the
/// largest |d| and the largest d met at the cells' centres.
struct GridIntegrals
{
    double area = 0.0, depth = 0.0, squareDepth = 0.0, moment1 = 0.0, moment2 = 0.0;
    double largestMagnitude = 0.0, largest = -HUGE_VAL;
};

GridIntegrals gridIntegrals(const PatchDepth& d, double rho, int rings = 400, int sectors = 800)
{
    GridIntegrals out;
    const double dr = rho / rings, dt = 2.0 * kPi / sectors;
    for (int j = 0; j < sectors; ++j) {
        const double t = (j + 0.5) * dt, c = std::cos(t), s = std::sin(t);
        for (int i = 0; i < rings; ++i) {
            const double r = (i + 0.5) * dr, u1 = r * c, u2 = r * s;
            const double v = depthAt(d, u1, u2);
            out.largestMagnitude = std::max(out.largestMagnitude, std::abs(v));
            out.largest = std::max(out.largest, v);
            if (!(v > 0.0)) continue;
            const double w = r * dr * dt;
            out.area += w;
            out.depth += v * w;
            out.squareDepth += v * v * w;
            out.moment1 += v * u1 * w;
            out.moment2 += v * u2 * w;
        }
    }
    return out;
}

/// The eigenvalues of [[c11, c12], [c12, c22]], smallest first (Eigen, not the code's own).
std::pair<double, double> eigenvalues(const PatchDepth& d)
{
    Eigen::Matrix2d c;
    c << d.c11, d.c12, d.c12, d.c22;
    const Eigen::Vector2d e = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(c).eigenvalues();
    return {e(0), e(1)};
}

/// The true maximum of d over the disk: the vertex u* = C⁻¹g where d is concave (C positive
/// definite) and u* lies in the disk, else on the rim (a trigonometric polynomial of degree 2
/// in the angle, sampled at 20000 angles: it then errs by < ½·max|d''|·(π/20000)² ≈ 1e-8·|d|).
double trueMaximum(const PatchDepth& d, double rho)
{
    double best = -HUGE_VAL;
    const int angles = 20000;
    for (int k = 0; k < angles; ++k) {
        const double t = 2.0 * kPi * k / angles;
        best = std::max(best, depthAt(d, rho * std::cos(t), rho * std::sin(t)));
    }
    if (eigenvalues(d).first > 0.0) {
        Eigen::Matrix2d c;
        c << d.c11, d.c12, d.c12, d.c22;
        const Eigen::Vector2d vertex = c.ldlt().solve(Eigen::Vector2d(d.g1, d.g2));
        if (vertex.norm() <= rho) best = std::max(best, depthAt(d, vertex(0), vertex(1)));
    }
    return best;
}

/// Random quadratics over disks of random radius, their slope and bend scaled with the radius
/// so that every kind turns up: wholly in, wholly clear, cut once or twice, islands, rings.
std::vector<std::pair<PatchDepth, double>> randomPatches(int count, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), radius(0.2, 2.0);
    std::vector<std::pair<PatchDepth, double>> out;
    for (int n = 0; n < count; ++n) {
        const double rho = radius(rng);
        PatchDepth d;
        d.d0 = unit(rng);
        d.g1 = unit(rng) / rho;
        d.g2 = unit(rng) / rho;
        d.c11 = 3.0 * unit(rng) / (rho * rho);
        d.c22 = 3.0 * unit(rng) / (rho * rho);
        d.c12 = 2.0 * unit(rng) / (rho * rho);
        out.emplace_back(d, rho);
    }
    return out;
}

} // namespace

// A patch wholly in contact: the integrals of the quadratic over the disk, derived here in
// polar coordinates (u = r(cos θ, sin θ), uᵀCu = r²·c(θ) with ∫c dθ = π·tr C and
// ∫c² dθ = (π/4)(3·tr²C − 4·det C), odd powers of u integrating to zero):
//   ∫1 = πρ²,  ∫d = πρ²(d0 − ρ²·tr C/8),  ∫d·u = (πρ⁴/4)·g,
//   ∫d² = πρ²d0² + (πρ⁴/4)(|g|² − d0·tr C) + (πρ⁶/96)(3·tr²C − 4·det C).
// integratePatch takes its own closed form then: equal to round-off (1e-12 of each integral's
// scale, the integrand's largest magnitude times the powers of ρ), and the formulas above are
// checked against the brute-force grid too (to 1e-5 of the scale, the grid's midpoint error).
TEST(PatchQuadrature, PatchWhollyInContactGivesTheDiskIntegralsInClosedForm)
{
    const struct
    {
        PatchDepth d;
        double rho;
    } cases[] = {
        {quadratic(0.3, 0.0, 0.0, 0.0, 0.0, 0.0), 0.5},     // flat, level
        {quadratic(0.5, 0.2, -0.1, 0.0, 0.0, 0.0), 1.0},    // flat, tilted
        {quadratic(1.2, 0.1, 0.3, 1.2, 0.3, 0.7), 1.0},     // convex patch (a ball's)
        {quadratic(0.4, -0.05, 0.02, -2.0, 0.5, -1.0), 0.3},  // concave: C negative definite
        {quadratic(2.0, 0.4, 0.1, 3.0, -1.5, -2.0), 0.8},   // saddle
        {quadratic(1e-3, 1e-4, 2e-4, 5.0, 1.0, 4.0), 0.01}, // a small patch
    };
    for (const auto& c : cases) {
        const PatchDepth& d = c.d;
        const double rho = c.rho, rho2 = rho * rho;
        const auto [lowest, highest] = eigenvalues(d);
        // The case is wholly in: d0 − |g|ρ − ½ρ²·max(λ, 0) > 0 bounds d from below.
        ASSERT_GT(d.d0 - std::hypot(d.g1, d.g2) * rho - 0.5 * rho2 * std::max(highest, 0.0), 0.0);
        const double trace = d.c11 + d.c22, det = d.c11 * d.c22 - d.c12 * d.c12;
        const double disk = kPi * rho2;
        const double area = disk;
        const double depth = disk * (d.d0 - rho2 * trace / 8.0);
        const double moment1 = disk * rho2 / 4.0 * d.g1, moment2 = disk * rho2 / 4.0 * d.g2;
        const double square = disk * d.d0 * d.d0 +
                              disk * rho2 / 4.0 * (d.g1 * d.g1 + d.g2 * d.g2 - d.d0 * trace) +
                              kPi * rho2 * rho2 * rho2 / 96.0 * (3.0 * trace * trace - 4.0 * det);
        // The scale: the largest |d| over the disk bounds every integrand.
        const double largest = std::abs(d.d0) + std::hypot(d.g1, d.g2) * rho +
                               0.5 * rho2 * std::max(std::abs(lowest), std::abs(highest));
        // Each integral to @a relative of its scale (the disk times the largest |d| to its power).
        auto expectClosedForms = [&](const auto& got, double relative) {
            EXPECT_NEAR(got.area, area, relative * disk);
            EXPECT_NEAR(got.depth, depth, relative * disk * largest);
            EXPECT_NEAR(got.moment1, moment1, relative * disk * largest * rho);
            EXPECT_NEAR(got.moment2, moment2, relative * disk * largest * rho);
            EXPECT_NEAR(got.squareDepth, square, relative * disk * largest * largest);
        };
        expectClosedForms(integratePatch(d, rho), 1e-12);
        // The formulas themselves, against the grid.
        expectClosedForms(gridIntegrals(d, rho), 1e-5);
    }
}

// A linear field (C = 0) cutting the disk along the line ĝ·u = x0 (x0 = −d0/a, a = |g|): the
// part in contact is a circular segment, whose integrals are, with s = √(ρ² − x0²),
//   S0 = ∫1 = ρ²·acos(x0/ρ) − x0·s,   S1 = ∫ĝ·u = (2/3)s³,
//   S2 = ∫(ĝ·u)² = 2[G(ρ) − G(x0)],  G(x) = (x/8)(2x² − ρ²)√(ρ² − x²) + (ρ⁴/8)·asin(x/ρ),
// and d = a(ĝ·u − x0): area S0, ∫d = a(S1 − x0·S0), ∫d² = a²(S2 − 2x0·S1 + x0²·S0), the moment
// a(S2 − x0·S1) along ĝ and none across it.
//
// Here the 16-ray trapezoid rule is not exact: along each ray the integral is exact, but as a
// function of the ray's angle it has kinks where the cut meets the rim (cos θ = x0/ρ), so the
// rule errs by O(w²) (w = 2π/16) times the kinks' jumps in slope, which are set by the slope of
// d over the patch, not by the size of the part in contact: the errors are measured against
// the scales πρ²·(aρ)ᵏ of the whole patch (relative to the segment itself they grow without
// bound as it shrinks: a sliver between two rays is missed). Measured over x0/ρ from −0.95 to
// 0.95 by 0.01 and every direction of g (0.125° apart): depth ≤ 2.7e-3·πρ³a, ∫d² ≤ 1.5e-4·πρ⁴a²,
// the moment along ĝ ≤ 2.6e-4·πρ⁴a and across it ≤ 1.3e-3·πρ⁴a; the tolerances are those with
// a margin (4e-3, 3e-4, 5e-4, 2e-3). The area is
// worst: near x0 = 0 the length in contact of the rays across ĝ jumps from ρ to 0 within an
// angle of about 2|x0|/ρ, twice around, and the rule can take the wrong side of both jumps:
// an error up to 2·(w/2)·(ρ²/2) = πρ²/16, reached when g is along a ray and x0 = 0.
TEST(PatchQuadrature, LinearFieldCuttingTheDiskMatchesTheCircularSegment)
{
    const double rho = 0.7, a = 0.3;
    const double disk = kPi * rho * rho;
    auto G = [&](double x) {
        return x / 8.0 * (2.0 * x * x - rho * rho) * std::sqrt(std::max(0.0, rho * rho - x * x)) +
               std::pow(rho, 4) / 8.0 * std::asin(x / rho);
    };
    for (double fraction : {-0.9, -0.6, -0.35, -0.1, 0.0, 0.1, 0.35, 0.6, 0.85}) {
        const double x0 = fraction * rho, s = std::sqrt(rho * rho - x0 * x0);
        const double S0 = rho * rho * std::acos(x0 / rho) - x0 * s;
        const double S1 = 2.0 / 3.0 * s * s * s;
        const double S2 = 2.0 * (G(rho) - G(x0));
        const double area = S0, depth = a * (S1 - x0 * S0);
        const double square = a * a * (S2 - 2.0 * x0 * S1 + x0 * x0 * S0);
        const double along = a * (S2 - x0 * S1);
        // g along the first axis, along a ray (π/16), between rays, and anywhere.
        for (double alpha : {0.0, kPi / 16.0, 0.1, 0.9, 2.0, -2.7, 4.0}) {
            const double c = std::cos(alpha), sn = std::sin(alpha);
            const PatchDepth d = quadratic(-a * x0, a * c, a * sn, 0.0, 0.0, 0.0);
            const PatchIntegral p = integratePatch(d, rho);
            const std::string what =
                "x0/rho " + std::to_string(fraction) + ", angle of g " + std::to_string(alpha);
            EXPECT_NEAR(p.area, area, disk / 16.0 + 1e-12 * disk) << what;
            EXPECT_NEAR(p.depth, depth, 4e-3 * disk * a * rho) << what;
            EXPECT_NEAR(p.squareDepth, square, 3e-4 * disk * a * a * rho * rho) << what;
            EXPECT_NEAR(p.moment1 * c + p.moment2 * sn, along, 5e-4 * disk * a * rho * rho) << what;
            EXPECT_NEAR(-p.moment1 * sn + p.moment2 * c, 0.0, 2e-3 * disk * a * rho * rho) << what;
            // Away from the centre the area's error is the kinks' alone, O(w²): measured
            // ≤ 1.1e-2·πρ² for |x0| ≥ 0.5ρ.
            if (std::abs(fraction) >= 0.5) {
                EXPECT_NEAR(p.area, area, 1.5e-2 * disk) << what;
            }
        }
    }
    // The exact half disk, d0 = 0 and g between rays: each ray is wholly in or wholly out, and
    // the rays split 8 to 8, so the area is exactly πρ²/2.
    const PatchIntegral half = integratePatch(quadratic(0.0, a, 0.0, 0.0, 0.0, 0.0), rho);
    EXPECT_NEAR(half.area, 0.5 * disk, 1e-12 * disk);
}

// General quadratics against the brute-force grid (400 rings × 800 sectors; halving the cells
// moves its integrals by < 4e-5·πρ² in area and < 1e-6 of the other scales, negligible beside
// the rule's errors). The rule errs as for the linear field, by O(w²) times the kinks of the rays'
// integrals, so the tolerances are in the patch's scales: M = max |d| over the disk, and for the
// designed cases P = max d over the disk (their parts in contact span several rays). Measured
// over 200 random quadratics: depth ≤ 2.6e-3·πρ²M, ∫d² ≤ 2.8e-4·πρ²M², moments ≤ 1.1e-3·πρ³M,
// area ≤ 3.7e-2·πρ² (the bound πρ²/16 of the linear case: the zero line through the centre);
// for the designed cases depth ≤ 1.5e-3·πρ²P. Tolerances: 5e-3, 1e-3, 2.5e-3, πρ²/16, 5e-3.
TEST(PatchQuadrature, GeneralQuadraticsMatchABruteForceGrid)
{
    const struct
    {
        const char* what;
        PatchDepth d;
        double rho;
    } cases[] = {
        // d0 < 0 and a convex patch tilted toward the body: an island around (0.4, 0), radius
        // 0.245, the node's centre clear (its rays at ±11.25° from the island's axis).
        {"island off the centre", quadratic(-0.1, 0.8, 0.0, 2.0, 0.0, 2.0), 1.0},
        {"island off the centre, turned", quadratic(-0.1, 0.8 * std::cos(0.5), 0.8 * std::sin(0.5), 2.0, 0.0, 2.0), 1.0},
        {"island cut by the rim", quadratic(-0.05, 0.6, -0.3, 1.0, 0.2, 1.4), 1.0},
        // C with negative eigenvalues: the patch bends toward the body.
        {"bowl, centre clear: a ring in contact", quadratic(-0.2, 0.0, 0.1, -1.2, 0.1, -0.8), 1.0},
        {"concave, almost wholly in", quadratic(0.02, 0.1, 0.05, -1.0, 0.3, -0.5), 1.0},
        {"saddle across the centre", quadratic(0.05, 0.2, -0.1, 1.5, 0.4, -1.0), 1.0},
        {"saddle, centre clear", quadratic(-0.05, 0.0, 0.0, 2.0, 0.0, -2.0), 1.0},
        {"a ball's patch at the contact's edge", quadratic(0.01, 0.15, 0.02, 0.2, 0.0, 0.2), 1.0},
        {"small patch, steep", quadratic(-2e-4, 0.3, 0.1, 40.0, 5.0, 20.0), 0.01},
    };
    for (const auto& c : cases) {
        const PatchIntegral p = integratePatch(c.d, c.rho);
        const GridIntegrals g = gridIntegrals(c.d, c.rho);
        ASSERT_GT(g.largest, 0.0) << c.what;
        ASSERT_GT(g.area, 0.0) << c.what;
        const double disk = kPi * c.rho * c.rho, P = g.largest;
        EXPECT_NEAR(p.area, g.area, disk / 16.0) << c.what;
        EXPECT_NEAR(p.depth, g.depth, 5e-3 * disk * P) << c.what;
        EXPECT_NEAR(p.squareDepth, g.squareDepth, 1e-3 * disk * P * P) << c.what;
        EXPECT_NEAR(p.moment1, g.moment1, 2.5e-3 * disk * P * c.rho) << c.what;
        EXPECT_NEAR(p.moment2, g.moment2, 2.5e-3 * disk * P * c.rho) << c.what;
    }
    int inContact = 0;
    for (const auto& [d, rho] : randomPatches(200, 11)) {
        const PatchIntegral p = integratePatch(d, rho);
        const GridIntegrals g = gridIntegrals(d, rho, 200, 400);
        const double disk = kPi * rho * rho, M = g.largestMagnitude;
        inContact += g.area > 0.0;
        EXPECT_NEAR(p.area, g.area, disk / 16.0);
        EXPECT_NEAR(p.depth, g.depth, 5e-3 * disk * M);
        EXPECT_NEAR(p.squareDepth, g.squareDepth, 1e-3 * disk * M * M);
        EXPECT_NEAR(p.moment1, g.moment1, 2.5e-3 * disk * M * rho);
        EXPECT_NEAR(p.moment2, g.moment2, 2.5e-3 * disk * M * rho);
    }
    EXPECT_GT(inContact, 50);  // the random set is not all clear
}

// A patch wholly clear of the body: nothing, by the quick test (patchPeakBound ≤ 0) or along the
// rays (a concave d whose peak bound is positive while d itself stays below zero); and
// patchPeakBound is never below the true maximum of d over the disk (the vertex of a concave d
// or the rim, trueMaximum above), for 500 random quadratics.
TEST(PatchQuadrature, PatchWhollyClearGivesNothingAndThePeakBoundIsAnUpperBound)
{
    const struct
    {
        PatchDepth d;
        double rho;
    } clear[] = {
        {quadratic(-0.5, 0.1, 0.2, 0.0, 0.0, 0.0), 1.0},
        {quadratic(-0.5, 0.1, 0.2, -0.3, 0.1, -0.2), 1.0},  // bends toward the body, not enough
        {quadratic(-0.1, 0.3, 0.0, 1.0, 0.0, 1.0), 1.0},    // max −0.055 at (0.3, 0): the vertex
        {quadratic(-1e-3, 0.0, 0.0, 5.0, 0.0, 5.0), 0.01},
    };
    for (const auto& c : clear) {
        ASSERT_LT(trueMaximum(c.d, c.rho), 0.0);
        const PatchIntegral p = integratePatch(c.d, c.rho);
        EXPECT_EQ(p.area, 0.0);
        EXPECT_EQ(p.depth, 0.0);
        EXPECT_EQ(p.squareDepth, 0.0);
        EXPECT_EQ(p.moment1, 0.0);
        EXPECT_EQ(p.moment2, 0.0);
        EXPECT_EQ(p.peak, 0.0);
    }
    EXPECT_LE(patchPeakBound(clear[0].d, 1.0), 0.0);
    EXPECT_LE(patchPeakBound(clear[1].d, 1.0), 0.0);
    // C positive definite: the bound is the vertex's −0.055 itself (the rim's would be 0.2).
    EXPECT_NEAR(patchPeakBound(clear[2].d, 1.0), -0.055, 1e-15);

    int negativeBounds = 0;
    for (const auto& [d, rho] : randomPatches(500, 5)) {
        const double bound = patchPeakBound(d, rho), top = trueMaximum(d, rho);
        // 1e-12 of the terms for round-off.
        const double scale = std::abs(d.d0) + std::hypot(d.g1, d.g2) * rho +
                             rho * rho * (std::abs(d.c11) + std::abs(d.c12) + std::abs(d.c22));
        EXPECT_GE(bound, top - 1e-12 * scale);
        if (bound <= 0.0) {
            ++negativeBounds;
            EXPECT_EQ(integratePatch(d, rho).depth, 0.0);
        }
    }
    EXPECT_GT(negativeBounds, 5);  // the quick exit was taken too
}

// integratePatch's peak is the largest d along its 16 rays: never above the true maximum, and
// below it by at most what d can change between a point and the nearest ray at the same
// radius: every point is within π/16 of a ray, a chord of at most 2ρ·sin(π/32), over which d
// changes by at most max|∇d|·2ρ·sin(π/32), max|∇d| ≤ |g| + ρ·‖C‖.
TEST(PatchQuadrature, PeakIsAttainedAndWithinTheRaysSpacingOfTheTrueMaximum)
{
    int compared = 0;
    for (const auto& [d, rho] : randomPatches(300, 23)) {
        const PatchIntegral p = integratePatch(d, rho);
        const double top = trueMaximum(d, rho);
        if (!(p.depth > 0.0)) continue;
        const auto [lowest, highest] = eigenvalues(d);
        const double steepest =
            std::hypot(d.g1, d.g2) + rho * std::max(std::abs(lowest), std::abs(highest));
        EXPECT_LE(p.peak, top + 1e-7 * (std::abs(top) + steepest * rho));
        EXPECT_GE(p.peak, top - steepest * 2.0 * rho * std::sin(kPi / 32.0));
        EXPECT_GT(p.peak, 0.0);
        ++compared;
    }
    EXPECT_GT(compared, 50);
}

// integratePatch takes its closed form when d0 > |g|ρ + ½ρ²·max(λ_max, 0) (the patch cannot
// leave the body) and its rays otherwise; at the threshold both give the whole disk (the rays'
// integrands are trigonometric polynomials of degree ≤ 4 there, which 16 rays integrate
// exactly), so a step of d0 by ε across it moves each integral by no more than its derivative
// in d0 allows: the area by the sliver cut off (O(ε) here), ∫d by ≤ πρ²·ε, ∫d² by
// ≤ 2πρ²·max d·ε, the moments by ≤ πρ³·ε. With ε = 1e-9 of the scale, a tolerance of 1e-7 of
// each integral's scale catches any jump while leaving room for the O(ε) change.
TEST(PatchQuadrature, IntegralsAreContinuousWhereTheClosedFormTakesOver)
{
    const struct
    {
        double g1, g2, c11, c12, c22, rho;
    } cases[] = {
        {0.3, -0.2, 0.0, 0.0, 0.0, 1.0},  // flat: touches at one point of the rim
        {0.0, 0.0, 1.0, 0.0, 1.0, 0.5},   // a ball's patch, level: touches along the rim
        {0.2, 0.1, 1.5, 0.4, 0.6, 1.0},   // tilted and bent
        {0.1, 0.0, -1.0, 0.2, -0.5, 1.0}, // concave: the threshold is the slope's alone
        {0.05, 0.2, 2.0, -0.8, -1.0, 0.7}, // saddle
    };
    for (const auto& c : cases) {
        PatchDepth d = quadratic(0.0, c.g1, c.g2, c.c11, c.c12, c.c22);
        const double highest = eigenvalues(d).second;
        const double threshold =
            std::hypot(c.g1, c.g2) * c.rho + 0.5 * c.rho * c.rho * std::max(highest, 0.0);
        const double eps = 1e-9 * threshold;
        d.d0 = threshold + eps;
        const PatchIntegral in = integratePatch(d, c.rho);
        d.d0 = threshold - eps;
        const PatchIntegral rays = integratePatch(d, c.rho);
        const double disk = kPi * c.rho * c.rho, M = 2.0 * threshold;
        EXPECT_NEAR(in.area, disk, 1e-12 * disk);  // the closed form's side
        EXPECT_NEAR(rays.area, in.area, 1e-7 * disk);
        EXPECT_NEAR(rays.depth, in.depth, 1e-7 * disk * M);
        EXPECT_NEAR(rays.squareDepth, in.squareDepth, 1e-7 * disk * M * M);
        EXPECT_NEAR(rays.moment1, in.moment1, 1e-7 * disk * M * c.rho);
        EXPECT_NEAR(rays.moment2, in.moment2, 1e-7 * disk * M * c.rho);
        EXPECT_NEAR(rays.peak, in.peak, 1e-7 * M);
    }
}

// patchDepth against exact distances. A node's bent patch is x(u) = x + u₁t₁ + u₂t₂ − ½(uᵀSu)m
// (NodeShape.h); the body's depth there is −φ(x(u)). Against a plane φ is linear, so the
// quadratic is exact (to round-off). Against a sphere (φ = |x − c| − R, ∇φ = n,
// H = (I − nnᵀ)/|x − c|) it is the second-order Taylor expansion: its error is O(|u|³), so
// halving u divides it by about 8 (asserted: by more than 6; an error in C's
// sign or in the body's bend would leave an O(|u|²) error, divided by 4).
TEST(PatchQuadrature, PatchDepthIsTheBodysDepthOverTheBentPatchToSecondOrder)
{
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    auto randomUnit = [&] {
        return Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    };
    for (int trial = 0; trial < 20; ++trial) {
        PatchFrame frame;
        frame.normal = randomUnit();
        frame.tangent1 = frame.normal.cross(randomUnit()).normalized();
        frame.tangent2 = frame.normal.cross(frame.tangent1);
        frame.k11 = 2.0 * unit(rng);
        frame.k22 = 2.0 * unit(rng);
        frame.k12 = unit(rng);
        const Vec3 x(unit(rng), unit(rng), unit(rng));
        auto bent = [&](double u1, double u2) {
            const double q = frame.k11 * u1 * u1 + 2.0 * frame.k12 * u1 * u2 + frame.k22 * u2 * u2;
            return Vec3(x + u1 * frame.tangent1 + u2 * frame.tangent2 - 0.5 * q * frame.normal);
        };
        // A plane facing the node (its normal against the node's).
        const Vec3 n = (-frame.normal + 0.4 * randomUnit()).normalized();
        const Vec3 onPlane = x - 0.05 * n;
        auto planePhi = [&](const Vec3& p) { return (p - onPlane).dot(n); };
        const PatchDepth flat = patchDepth(frame, planePhi(x), n, 0.0, 0.0, 0.0);
        for (int k = 0; k < 10; ++k) {
            const double u1 = 0.3 * unit(rng), u2 = 0.3 * unit(rng);
            EXPECT_NEAR(depthAt(flat, u1, u2), -planePhi(bent(u1, u2)), 1e-14);
        }
        // A sphere of radius 2 in front of the node, the node 0.01 inside it.
        const double R = 2.0;
        const Vec3 centre = x + (R - 0.01) * (-n);
        auto spherePhi = [&](const Vec3& p) { return (p - centre).norm() - R; };
        const Vec3 offset = x - centre;
        const double r = offset.norm();
        const Vec3 m = offset / r;
        auto hessian = [&](const Vec3& a, const Vec3& b) {
            return (a.dot(b) - a.dot(m) * b.dot(m)) / r;
        };
        const PatchDepth round =
            patchDepth(frame, spherePhi(x), m, hessian(frame.tangent1, frame.tangent1),
                       hessian(frame.tangent1, frame.tangent2), hessian(frame.tangent2, frame.tangent2));
        // Summed over 16 directions, so that no near-cancellation of the cubic term in one
        // direction lets a quartic one decide.
        double previous = 0.0;
        for (double size : {0.02, 0.01, 0.005}) {
            double error = 0.0;
            for (int k = 0; k < 16; ++k) {
                const double u1 = size * std::cos(0.4 * k), u2 = size * std::sin(0.4 * k);
                error += std::abs(depthAt(round, u1, u2) + spherePhi(bent(u1, u2)));
            }
            if (previous > 0.0) {
                EXPECT_LT(error, previous / 6.0) << "trial " << trial << " size " << size;
            }
            previous = error;
        }
    }
}

// fillPatchContact: the area in contact, the mean depth and mean square depth over it, the
// deepest point, and the centre of the traction (∫d·u/∫d along the tangents); nothing, and the
// contact untouched, when no part of the patch is in.
TEST(PatchQuadrature, FillPatchContactTakesTheMeansAndTheTractionsCentre)
{
    PatchFrame frame;
    frame.normal = Vec3(0, 0, -1);
    frame.tangent1 = Vec3(1, 0, 0);
    frame.tangent2 = frame.normal.cross(frame.tangent1);  // (0, −1, 0)
    const PatchDepth d = quadratic(0.5, 0.2, -0.1, 0.4, 0.1, 0.3);
    const double rho = 0.6, disk = kPi * rho * rho;
    const PatchIntegral p = integratePatch(d, rho);
    NodeContact c;
    c.node = 7;
    Vec3 offset = Vec3::Constant(99.0);
    ASSERT_TRUE(fillPatchContact(p, frame, c, offset));
    // Wholly in (0.5 − 0.224·0.6 − ½·0.36·0.46 > 0): the closed forms of the first test.
    const double trace = d.c11 + d.c22, det = d.c11 * d.c22 - d.c12 * d.c12;
    const double depth = disk * (d.d0 - rho * rho * trace / 8.0);
    const double square = disk * d.d0 * d.d0 +
                          disk * rho * rho / 4.0 * (d.g1 * d.g1 + d.g2 * d.g2 - d.d0 * trace) +
                          kPi * std::pow(rho, 6) / 96.0 * (3.0 * trace * trace - 4.0 * det);
    EXPECT_NEAR(c.area, disk, 1e-14 * disk);
    EXPECT_NEAR(c.depth, depth / disk, 1e-14);
    EXPECT_NEAR(c.squareDepth, square / disk, 1e-14);
    EXPECT_GE(c.peakDepth, c.depth);
    EXPECT_EQ(c.node, 7);  // the caller's
    const double shift = disk * rho * rho / 4.0 / depth;  // ∫d·u = (πρ⁴/4)g
    const Vec3 expected = shift * d.g1 * frame.tangent1 + shift * d.g2 * frame.tangent2;
    EXPECT_LT((offset - expected).norm(), 1e-14);
    EXPECT_TRUE(c.isPatch());
    EXPECT_NEAR(c.meanSquareDepth(), c.squareDepth, 0.0);

    NodeContact untouched;
    untouched.depth = 3.0;
    Vec3 kept = Vec3::Constant(5.0);
    EXPECT_FALSE(fillPatchContact(integratePatch(quadratic(-1.0, 0.1, 0, 0, 0, 0), rho), frame,
                                  untouched, kept));
    EXPECT_EQ(untouched.depth, 3.0);
    EXPECT_EQ(untouched.area, 0.0);
    EXPECT_EQ(kept, Vec3::Constant(5.0));
}

// A node's patch given by its extents along the rays (NodeShape.h): with every extent ρ it is
// the disk, and its integrals are the disk's (the rays' rule is exact where the disk's closed
// form is used, so to round-off; elsewhere it is the same rule), for the random quadratics.
TEST(PatchQuadrature, PatchOfEqualExtentsIsTheDisk)
{
    for (const auto& [d, rho] : randomPatches(200, 29)) {
        std::array<float, kPatchRays> extents;
        extents.fill(static_cast<float>(rho));
        const double r = double(extents[0]);  // ρ as a float holds it
        const PatchIntegral disk = integratePatch(d, r), cell = integratePatch(d, extents, r);
        const double area = kPi * r * r;
        const double M = std::abs(d.d0) + std::hypot(d.g1, d.g2) * r +
                         r * r * (std::abs(d.c11) + std::abs(d.c12) + std::abs(d.c22));
        EXPECT_NEAR(cell.area, disk.area, 1e-12 * area);
        EXPECT_NEAR(cell.depth, disk.depth, 1e-12 * area * M);
        EXPECT_NEAR(cell.squareDepth, disk.squareDepth, 1e-12 * area * M * M);
        EXPECT_NEAR(cell.moment1, disk.moment1, 1e-12 * area * M * r);
        EXPECT_NEAR(cell.moment2, disk.moment2, 1e-12 * area * M * r);
    }
}

// A patch given by its extents along the rays, pressed wholly and evenly by d0 (d = d0 over
// it): the rays' rule is exact along each ray, so the patch holds d0 times the rule's area,
// Σ ½·e_k²·Δθ, and its contact area is that area, to round-off. For the s × s square cell of a
// face grid (e(ψ) = (s/2)/max(|cos ψ|, |sin ψ|)) that area is not s²: 0.976·s² with a ray
// along a side, 1.049·s² turned by half a ray spacing (the rule cuts the corners or overshoots
// them). So NodeShape scales each cell's extents to the node's own area (TestNodeShape), and a
// face pressed flat holds k·d0·s² a node (TestPlaneContact).
TEST(PatchQuadrature, EvenDepthOverACellHoldsTheRaysRulesArea)
{
    const double s = 0.2, d0 = 0.01;
    const std::pair<double, double> turns[] = {{0.0, 0.976}, {kPi / kPatchRays, 1.049}};
    for (const auto& [turn, ratio] : turns) {
        std::array<float, kPatchRays> extents;
        float reach = 0.0f;
        double ruleArea = 0.0;
        for (int k = 0; k < kPatchRays; ++k) {
            const double psi = (k + 0.5) * 2.0 * kPi / kPatchRays - turn;
            const float e =
                static_cast<float>(0.5 * s / std::max(std::abs(std::cos(psi)), std::abs(std::sin(psi))));
            extents[static_cast<size_t>(k)] = e;
            reach = std::max(reach, e);
            ruleArea += 0.5 * double(e) * double(e) * 2.0 * kPi / kPatchRays;
        }
        const PatchIntegral p = integratePatch(quadratic(d0, 0, 0, 0, 0, 0), extents, reach);
        EXPECT_NEAR(p.area, ruleArea, 1e-12 * ruleArea) << "grid turned by " << turn;
        EXPECT_NEAR(p.depth, d0 * ruleArea, 1e-12 * d0 * ruleArea) << "grid turned by " << turn;
        EXPECT_NEAR(ruleArea / (s * s), ratio, 1e-3) << "grid turned by " << turn;
    }
}

// patchRadius is the radius of the disk of the given area.
TEST(PatchQuadrature, PatchRadiusIsThatOfTheDiskOfTheArea)
{
    for (double rho : {1e-3, 0.25, 1.0, 7.5}) EXPECT_NEAR(patchRadius(kPi * rho * rho), rho, 1e-15 * rho);
}

// The scene key's values: "node" and "patch" read back as themselves; anything else is refused
// with lsdem::Error naming the value and both accepted ones.
TEST(PatchQuadrature, QuadratureNamesRoundTripAndUnknownNamesAreRefused)
{
    EXPECT_EQ(nodeQuadratureName(NodeQuadrature::Point), "node");
    EXPECT_EQ(nodeQuadratureName(NodeQuadrature::Patch), "patch");
    for (NodeQuadrature q : {NodeQuadrature::Point, NodeQuadrature::Patch})
        EXPECT_EQ(parseNodeQuadrature(nodeQuadratureName(q)), q);
    for (const std::string bad : {"gauss", "", "Patch", "nodes", " patch"}) {
        try {
            parseNodeQuadrature(bad);
            ADD_FAILURE() << "'" << bad << "' accepted";
        } catch (const Error& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find("'" + bad + "'"), std::string::npos) << message;
            EXPECT_NE(e.fix().find("node"), std::string::npos) << message;
            EXPECT_NE(e.fix().find("patch"), std::string::npos) << message;
        }
    }
}
