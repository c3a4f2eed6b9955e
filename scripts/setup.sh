#!/usr/bin/env bash
# Install everything meshlab-acd needs on Debian 12, idempotently, then build and install the plugin
# and the pymeshlab_acd package. Downloads and builds go to $ACD_CACHE (outside the repo).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$here/env.sh"

APT_PKGS=(build-essential cmake ninja-build pkg-config xz-utils dpkg-dev
	qtbase5-dev libqt5opengl5-dev libglew-dev libeigen3-dev libgmp-dev libmpfr-dev libboost-dev libtbb-dev nlohmann-json3-dev doctest-dev)
missing=()
for p in "${APT_PKGS[@]}"; do
	dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
	echo "[setup] apt-get install ${missing[*]}"
	SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
	$SUDO apt-get update -qq
	DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi

PY="${PYTHON:-python3}"
pip_need() { ! "$PY" -c "import importlib.metadata as m, sys; sys.exit(0 if m.version('$1') == '$2' or '$2' == '*' else 1)" 2>/dev/null; }
if pip_need pymeshlab 2025.7.post1; then "$PY" -m pip install -q "pymeshlab==2025.7.post1"; fi
for p in numpy pytest wheel setuptools; do
	if pip_need "$p" '*'; then "$PY" -m pip install -q "$p"; fi
done
# pytest-xdist runs the pytest suite on two workers. Batch and simulator export, robots (yourdfpy for URDF, usd-core for USD); trimesh, scipy (Qhull), libigl (exact point-mesh distances) and manifold3d
# (exact CAD-shaped solids) for the independent checks in the tests.
for pv in pytest-xdist:3.6.1 tqdm:4.70.1 ray:2.60.0 mujoco:4.0.0 pybullet:3.2.7 yourdfpy:0.0.60 usd-core:26.11 trimesh:5.2.0 scipy:1.17.1 manifold3d:3.5.4 libigl:2.6.1; do
	if pip_need "${pv%%:*}" "${pv#*:}"; then "$PY" -m pip install -q "${pv%%:*}==${pv#*:}"; fi
done

bash "$here/build_plugin.sh"
# Reinstall the package when the plugin binary or its Python sources changed (or it is missing).
built="$ACD_BUILD_DIR/filter_acd/libfilter_acd.so"
installed="$("$PY" -c 'import importlib.util as u, os; s=u.find_spec("pymeshlab_acd"); print(os.path.join(os.path.dirname(s.origin), "lib", "libfilter_acd.so") if s else "")' 2>/dev/null || true)"
stale=0
if [ -n "$installed" ]; then   # the package's Python sources changed since it was installed
	for f in "$ACD_REPO"/pymeshlab_bindings/pymeshlab_acd/*.py; do
		cmp -s "$f" "$(dirname "$(dirname "$installed")")/$(basename "$f")" || stale=1
	done
fi
if [ -z "$installed" ] || [ $stale = 1 ] || ! cmp -s "$built" "$installed"; then
	echo "[setup] pip install ./pymeshlab_bindings"
	"$PY" -m pip install -q --no-build-isolation --force-reinstall --no-deps "$ACD_REPO/pymeshlab_bindings"
fi
echo "[setup] ready: $("$PY" -c 'import pymeshlab_acd; print(pymeshlab_acd.plugin_path())')"
