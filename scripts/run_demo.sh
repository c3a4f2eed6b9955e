#!/usr/bin/env bash
# The main job on the embedded default: measure and decompose pymeshlab's bundled bunny.
# Output files go to ${1:-./out/demo} (printed at the end).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bash "$here/setup.sh"
out="$(realpath -m "${1:-$PWD/out/demo}")"
mkdir -p "$out"
echo
echo "== Notch concavity of the bundled bunny =="
python3 -m pymeshlab_acd concavity --demo --no-progress --out "$out"
for tau in 8 4; do
	echo
	echo "== Approximate convex decomposition, tau = $tau% of the bunny's size =="
	python3 -m pymeshlab_acd decompose --demo --tau "$tau" --tree --out "$out/tau_$tau"
done
echo
echo "== From the tree: a coarser level without recomputing, the skeleton, the hull union (tau = 3%) =="
python3 -m pymeshlab_acd structure --demo --tau 3 --coarser 6 --no-progress --out "$out/structure"
echo
echo "Output files: $out"
