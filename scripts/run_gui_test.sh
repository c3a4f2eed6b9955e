#!/usr/bin/env bash
# The GUI test: builds (once, cached) the MeshLab 2025.07 GUI and a small Qt probe, then drives MeshLab
# under Xvfb with our plugin through the Filters menu (tests/gui/test_gui.py). The last run's
# screenshots (menu, dialog, coloured parts) are kept in ./out/gui, or in $ACD_GUI_SHOTS.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$here/env.sh"
bash "$here/setup.sh" >/dev/null
exe="$(bash "$here/build_meshlab_gui.sh" | tail -n 1)"

probe="$ACD_CACHE/gui-probe/qt_probe.so"
src="$ACD_REPO/tests/gui/qt_probe.cpp"
if [ ! -f "$probe" ] || [ "$src" -nt "$probe" ]; then
	mkdir -p "$(dirname "$probe")"
	g++ -O1 -fPIC -shared -std=c++17 "$src" -o "$probe" $(pkg-config --cflags --libs Qt5Widgets)
fi

export ACD_MESHLAB_GUI="$exe" ACD_GUI_PROBE_SO="$probe"
export ACD_PLUGIN="$ACD_BUILD_DIR/filter_acd/libfilter_acd.so"
export ACD_GUI_SHOTS="${ACD_GUI_SHOTS:-$ACD_REPO/out/gui}"
rm -rf "$ACD_GUI_SHOTS"
set +e
python3 -m pytest -q -s -p no:cacheprovider "$ACD_REPO/tests/gui" "$@"
rc=$?
set -e
echo "[gui] screenshots: $ACD_GUI_SHOTS"
[ $rc -eq 5 ] && { echo "the GUI test was not collected" >&2; exit 1; }
exit $rc
