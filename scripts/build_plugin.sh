#!/usr/bin/env bash
# Build the core, its tests and the MeshLab plugin.
#   scripts/build_plugin.sh            double precision, linked to pymeshlab's libmeshlab-common (pymeshlab,
#                                      and MeshLab GUIs built with MESHLAB_BUILD_WITH_DOUBLE_SCALAR=ON)
#   ACD_SCALAR=float scripts/build_plugin.sh   single precision, for MeshLab's stock (float) GUI builds
# Output: $ACD_BUILD_DIR/filter_acd/libfilter_acd.so (see scripts/env.sh)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$here/env.sh"
bash "$here/fetch_deps.sh" >/dev/null

scalar="$ACD_SCALAR"
build="$ACD_BUILD_DIR"
extra=()
if [ "$scalar" = "double" ]; then
	common="$(python3 -c 'import os, pymeshlab; print(os.path.join(os.path.dirname(pymeshlab.__file__), "lib", "libmeshlab-common.so"))')"
	extra+=("-DMESHLAB_COMMON_LIB=$common")
fi
cgal_dir="$ACD_CGAL_ROOT/usr/lib/x86_64-linux-gnu/cmake/CGAL"
[ -d "$cgal_dir" ] || cgal_dir=""
cmake -S "$ACD_REPO/plugin" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
	-DMESHLAB_SRC_DIR="$ACD_MESHLAB_SRC" -DACD_SCALAR="$scalar" ${cgal_dir:+-DCGAL_DIR="$cgal_dir"} \
	"${extra[@]}" ${ACD_CMAKE_ARGS:-} >/dev/null
cmake --build "$build" -- -j"$(nproc)"
echo "[build_plugin] $scalar plugin: $build/filter_acd/libfilter_acd.so"
