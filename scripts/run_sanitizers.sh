#!/usr/bin/env bash
# The core's C++ tests built with AddressSanitizer + UndefinedBehaviorSanitizer (no plugin: the
# plugin is loaded by an uninstrumented host). Any finding aborts the run with a report.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$here/env.sh"
bash "$here/fetch_deps.sh" >/dev/null
build="$ACD_CACHE/build-sanitize-$(printf %s "$ACD_REPO" | sha1sum | cut -c1-8)"
cgal_dir="$ACD_CGAL_ROOT/usr/lib/x86_64-linux-gnu/cmake/CGAL"
[ -d "$cgal_dir" ] || cgal_dir=""
cmake -S "$ACD_REPO/plugin" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DACD_SANITIZE=ON \
	-DACD_BUILD_PLUGIN=OFF ${cgal_dir:+-DCGAL_DIR="$cgal_dir"} >/dev/null
cmake --build "$build" --target acd_core_tests acd_run -- -j"$(nproc)"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:halt_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# The doctests in two processes at once: the first two thirds in file order, and the rest (the later
# files hold the longer cases), about equal times.
n="$("$build/core/acd_core_tests" --count | grep -o '[0-9]*$')"
logs="$(mktemp -d)"
"$build/core/acd_core_tests" --last=$((n * 2 / 3)) >"$logs/a" 2>&1 & a=$!
"$build/core/acd_core_tests" --first=$((n * 2 / 3 + 1)) >"$logs/b" 2>&1 & b=$!
rc=0
wait $a || rc=$?
wait $b || rc=$?
cat "$logs/a" "$logs/b"
rm -rf "$logs"
[ $rc -eq 0 ] || { echo "[sanitizers] a core test failed or a sanitizer reported (above)" >&2; exit $rc; }
# and a real decomposition: the bundled bunny (56k faces) through both cutting-plane modes
bunny="$(python3 -c 'import os, pymeshlab; print(os.path.join(os.path.dirname(pymeshlab.__file__), "tests", "sample_meshes", "bunny.obj"))')"
"$build/core/acd_run" "$bunny" 5 bisector 2>/dev/null
"$build/core/acd_run" "$bunny" 5 best 4 2>/dev/null
echo "[sanitizers] ASan + UBSan: core tests and bunny decompositions ran with no findings"
