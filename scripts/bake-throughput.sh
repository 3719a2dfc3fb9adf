#!/usr/bin/env bash
# Bake throughput of lsdem-bake's batch mode: generate N sand-like grains with lsdem-grains
# (default shape options, 2000 triangles each, equivalent diameter 1) and bake them all at
# --voxel-per-size 0.03 --nodes 600 on T threads; prints grains per second.
#   bash scripts/bake-throughput.sh [N=1000] [T=2] [BUILD=build]
set -euo pipefail
cd "$(dirname "$0")/.."
count=${1:-1000}
threads=${2:-2}
build=${3:-build}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build/tools/lsdem-grains" --count "$count" --seed 1 --out-dir "$work/scans" -q
start=$(date +%s.%N)
"$build/tools/lsdem-bake" "$work"/scans/*.stl --out-dir "$work/assets" \
    --voxel-per-size 0.03 --nodes 600 --threads "$threads" -q
end=$(date +%s.%N)
rows=$(($(wc -l < "$work/assets/catalog.csv") - 1))
awk -v n="$rows" -v t0="$start" -v t1="$end" -v th="$threads" -v cat="$work/assets/catalog.csv" 'BEGIN {
    s = t1 - t0
    printf "baked %d grains on %d threads in %.1f s: %.2f grains/s\n", n, th, s, n / s
}'
# Per-grain bake time (the catalogue's bake_seconds column): median and 90th percentile.
col=$(head -1 "$work/assets/catalog.csv" | tr ',' '\n' | grep -n '^bake_seconds$' | cut -d: -f1)
tail -n +2 "$work/assets/catalog.csv" | awk -F, -v c="$col" '{print $c}' | sort -g |
    awk '{v[NR] = $1} END {printf "per grain: median %.3f s, 90th percentile %.3f s\n", v[int((NR + 1) / 2)], v[int(0.9 * NR)]}'
