/// @file GrainGenerator.h
/// @brief Sand-like grain meshes without scans: star-shaped surfaces whose log-radius is a
///        random sum of real spherical harmonics with a power-law spectrum, stretched to a
///        target elongation and flatness and scaled to a target equivalent diameter.
///        Reproducible: grain i of seed s is the same on every machine, whatever the count.
///
/// The surface is x(u) = S · exp(f(u)) · u over unit directions u, with
///   f(u) = Σ_{l=2..L} Σ_m a_lm Y_lm(u),   a_lm = c · l^(-decay) / sqrt(2l+1) · g_lm,
/// g_lm standard normal, so the amplitude of degree l, sqrt(Σ_m a_lm²), falls off about as
/// l^(-decay) (the power-law decay measured on natural sands); c is set so that the RMS of f
/// over the sphere equals the roughness exactly. Degrees 0 and 1 are left out: they only
/// scale and shift the grain. S = diag(1, elongation, elongation·flatness) (Zingg's ratios
/// I/L and S/I of a grain whose f is zero), then the mesh is scaled so that its volume is
/// π d³/6. A radial graph over a triangulated sphere never intersects itself, so every mesh
/// is closed, manifold and outward.
#pragma once

#include "lsdem/mesh/TriangleMesh.h"

#include <cstdint>
#include <string>

namespace lsdem {

struct GrainShapeOptions
{
    double elongation = 0.8;  ///< intermediate / long axis of the base ellipsoid, (0, 1]
    double flatness = 0.8;    ///< short / intermediate axis of the base ellipsoid, (0, 1]
    double roughness = 0.12;  ///< RMS of the log-radius perturbation f, >= 0 (0: an ellipsoid)
    double decay = 1.6;       ///< spectral exponent: degree-l amplitude ∝ l^-decay, >= 0
    int maxDegree = 16;       ///< highest harmonic degree L, 2 .. 60
    double size = 1.0;        ///< median equivalent diameter d (sphere of equal volume), length
    double sizeSpread = 0.0;  ///< standard deviation of ln d across grains (log-normal), >= 0
    int triangles = 2000;     ///< about this many triangles per grain (20 n², n >= 2)
};

/// @throw Error naming the option (as "--elongation" etc.) if a value is out of range.
void checkGrainShapeOptions(const GrainShapeOptions& options);

/// Grain @a index of the run seeded with @a seed, in the frame where its base ellipsoid's long,
/// intermediate and short axes lie along x, y, z, centred near the origin.
TriangleMesh generateGrain(const GrainShapeOptions& options, uint64_t seed, uint64_t index);

/// The equivalent diameter grain @a index is scaled to (its log-normal draw).
double generatedGrainSize(const GrainShapeOptions& options, uint64_t seed, uint64_t index);

/// Write a generated grain compactly and reproducibly: .obj as text with 7 significant digits
/// ("%.7g", the same bytes for the same mesh), .stl as binary STL (float32, little-endian, the
/// format of scan archives such as the Sand Atlas). Written atomically.
/// @throw Error for another extension or a write failure.
void writeGrainMesh(const TriangleMesh& mesh, const std::string& path);

} // namespace lsdem
