#!/usr/bin/env bash
# The main job on the bundled default case: install dependencies, build, then bake the bundled
# grains (an analytic sphere and box, and the pebble mesh in assets/meshes) into results/demo/
# and inspect them (summaries, slice pictures, isosurfaces); then run the two-sphere, 27-sphere,
# a small triaxial and the interlocked-slab studies and simulate the 27-sphere stack of assets/scenes/cube27.toml.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
out=results/demo
mkdir -p "$out"
bake=build/tools/lsdem-bake
inspect=build/tools/lsdem-inspect

echo "== baking (lengths in mm)"
"$bake" --sphere 5 --voxel 0.1 --nodes 4000 -o "$out/sphere.vdb"
"$bake" --box 10 6 4 --voxel 0.1 --node-spacing 0.25 -o "$out/box.vdb"
"$bake" assets/meshes/pebble.obj --voxel 0.1 --node-spacing 0.25 -o "$out/pebble.vdb"

for grain in sphere box pebble; do
    echo "== $out/$grain.vdb"
    "$inspect" "$out/$grain.vdb"
    "$inspect" "$out/$grain.vdb" --slice z=0 --png "$out/$grain-z0.png" --mesh "$out/$grain-surface.obj"
done
echo "== the generated sand grains of assets/meshes/sand: one batch, one catalogue"
"$bake" assets/meshes/sand/*.obj --out-dir "$out/sand" --voxel-per-size 0.03 --nodes 600
echo "== two-sphere study (Feldfogel et al. 2024, Fig. 1 and 3)"
build/tools/lsdem-study two-spheres --out results/two-spheres
echo "== 27-sphere stack study (Fig. 4; about 10 s)"
build/tools/lsdem-study cube27 --out results/cube27-study
echo "== simulation: the 27-sphere stack compressed by a wall (assets/scenes/cube27.toml)"
# --overwrite: a second run of this script replaces the first one's outputs (refused without it).
build/tools/lsdem-run assets/scenes/cube27.toml --out results/cube27 --overwrite
echo "== simulation: the 16 generated sand grains settling in a box (assets/scenes/sand.toml; a few seconds)"
build/tools/lsdem-run assets/scenes/sand.toml --out results/sand --overwrite
echo "== triaxial test: a first look with 27 sand grains, adapted and original (a few seconds; docs/triaxial.md)"
build/tools/lsdem-study triaxial --grains 27 --sdps 0.1 --axial-strain 0.05 --out results/triaxial-look
echo "== interlocked slab study (Fig. 5 and 6; about 2 minutes on 2 cores)"
build/tools/lsdem-study slab --out results/slab
echo "== done: assets in $out (open the .png slices; the .obj isosurfaces load in any viewer;"
echo "   $out/sand holds the baked sand grains and their catalog.csv),"
echo "   two-sphere study in results/two-spheres (two_spheres.csv and *.png),"
echo "   the stack study in results/cube27-study (cube27.csv and *.png),"
echo "   the stack in results/cube27 (boundary_top.csv: P-δ of the top wall; frames.pvd for ParaView),"
echo "   the sand grains in results/sand (frames.pvd for ParaView),"
echo "   the triaxial look in results/triaxial-look (triaxial.csv, triaxial_runs.csv, *.png; scene/ for lsdem-run),"
echo "   the slab study in results/slab (slab_failure.txt, slab.csv, slab_*.png; slab_scene.toml for lsdem-run)"
