#!/usr/bin/env bash
# Build the MeshLab 2025.07 GUI (double precision, minimal plugin set) from the same Debian source
# tarball used for the plugin's headers, cached in $ACD_CACHE/meshlab-gui (about 4-8 minutes on 2
# cores, once). Prints the path of the meshlab executable on its last line.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$here/env.sh"
bash "$here/fetch_deps.sh" >/dev/null

# Qt's SVG and tools for MeshLab; Xvfb, xdotool, ImageMagick, Mesa's software GL and a font for its test
APT_PKGS=(libqt5svg5-dev qttools5-dev xvfb xdotool x11-utils imagemagick libgl1-mesa-dri fonts-dejavu-core)
missing=()
for p in "${APT_PKGS[@]}"; do
	dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
	SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
	$SUDO apt-get update -qq
	DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi

build="$ACD_CACHE/meshlab-gui"
# io_base reads/writes meshes and projects; filter_create, filter_meshing and filter_layer are what
# the GUI test and the .mlx examples lean on besides our plugin.
plugins="meshlabplugins/io_base;meshlabplugins/filter_create;meshlabplugins/filter_meshing;meshlabplugins/filter_layer"
if [ ! -x "$build/meshlab" ] || [ "${ACD_REBUILD_GUI:-0}" = 1 ]; then
	cmake -S "$ACD_MESHLAB_SRC" -B "$build/tree" -G Ninja -DCMAKE_BUILD_TYPE=Release \
		-DMESHLAB_BUILD_MINI=ON -DMESHLAB_BUILD_WITH_DOUBLE_SCALAR=ON -DMESHLAB_PLUGINS="$plugins" \
		>/dev/null
	# the plugins are not in the default target: name them
	cmake --build "$build/tree" --target meshlab io_base filter_create filter_meshing filter_layer -- -j"$(nproc)"
	# Run from the build tree's distrib folder (plugins beside it); no install step needed.
	exe="$build/tree/src/distrib/meshlab"
	ln -sf "$exe" "$build/meshlab"
fi
echo "$build/meshlab"
