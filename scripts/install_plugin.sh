#!/usr/bin/env bash
# Copy the plugin into MeshLab's extra-plugins folder for the current user, where MeshLab 2025.07
# loads it at start-up:
#   double builds (pymeshlab, GUIs built with MESHLAB_BUILD_WITH_DOUBLE_SCALAR=ON):
#     ~/.local/share/VCG/MeshLab_64bit_dp/MeshLabExtraPlugins/2025.07d/
#   float builds (MeshLab's stock releases):  ACD_SCALAR=float scripts/install_plugin.sh
#     ~/.local/share/VCG/MeshLab_64bit_fp/MeshLabExtraPlugins/2025.07/
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$here/env.sh"
so="$ACD_BUILD_DIR/filter_acd/libfilter_acd.so"
[ -f "$so" ] || bash "$here/build_plugin.sh" >/dev/null
if [ "$ACD_SCALAR" = double ]; then dest="$HOME/.local/share/VCG/MeshLab_64bit_dp/MeshLabExtraPlugins/2025.07d"
else dest="$HOME/.local/share/VCG/MeshLab_64bit_fp/MeshLabExtraPlugins/2025.07"; fi
mkdir -p "$dest"
cp "$so" "$dest/"
echo "[install_plugin] $ACD_SCALAR-precision plugin installed: $dest/libfilter_acd.so"
echo "Restart MeshLab 2025.07 ($ACD_SCALAR build); the filters are under Filters > Quality Measure and"
echo "Computations (Notch Concavity) and Filters > Remeshing, Simplification and Reconstruction"
echo "(Approximate Convex Decomposition)."
