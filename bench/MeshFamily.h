/// @file MeshFamily.h
/// @brief Closed meshes of about 100k triangles and a size of about 10 (R ≈ 5), each hard for a
///        node placer in its own way, for the bake benchmarks (issue 35: speed must hold on
///        inputs nobody tuned for). None is used to tune anything alone.
#pragma once

#include "lsdem/ls/Bake.h"
#include "lsdem/mesh/TriangleMesh.h"

#include <string>
#include <vector>

namespace lsdem::bench {

struct FamilyMesh
{
    std::string name;
    TriangleMesh mesh;
};

/// How many meshes meshFamily() has.
constexpr int kFamilySize = 7;

/// Member @a index (0 .. kFamilySize-1) of the family:
///  0 pebble     — the original benchmark's icosphere with smooth bumps (100,820 triangles)
///  1 bumpy      — an icosphere of frequency 64 (81,920 triangles), radius 5 ± 13 %
///  2 grain      — an lsdem-grains sand grain (seed 1, grain 0) of 100k triangles, d = 10
///  3 uv-sphere  — a latitude–longitude sphere (102,080 triangles): slivers at the poles
///  4 graded     — an icosphere bent by a conformal map so triangle areas vary 100× (81,920)
///  5 peanut     — two lobes and a concave waist, bumpy (81,920 triangles)
///  6 noisy      — the grain with a scan's noise: vertices moved ±0.03 along their radius,
///                 so thousands of edges are sharp (over 30°)
FamilyMesh familyMesh(int index);

/// Bakes a small sphere once per process (later calls return at once): TBB's threads, their
/// malloc heaps and stacks and OpenVDB's set-up are made once in a process, and a bake's
/// memory figure taken after this counts what that bake needs, not the process's start-up
/// (about 1-3 MiB, which a first bake would add to its figure).
void warmUpProcess();

/// The bake settings for the family (a grain of size 10): VDP 0.05, SDP 0.12.
BakeOptions familyBakeOptions();

} // namespace lsdem::bench
