#!/usr/bin/env bash
# Every test: the core's C++ tests (ctest), the pytest suite through pymeshlab, and the MeshLab GUI
# test under Xvfb (ACD_SKIP_SANITIZERS=1 / ACD_SKIP_GUI=1 skip the slower targets while developing).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$here/env.sh"
bash "$here/setup.sh"

echo "== C++ core tests =="
ctest --test-dir "$ACD_BUILD_DIR" --output-on-failure

if [ "${ACD_SKIP_SANITIZERS:-0}" != 1 ]; then
	echo "== C++ core under AddressSanitizer + UndefinedBehaviorSanitizer =="
	bash "$here/run_sanitizers.sh"
fi

echo "== pytest (through pymeshlab) =="
set +e
# Two workers: most tests spend their time in single-threaded Python checks, and the suite takes a
# little over half its one-worker time on two cores (ACD_TEST_WORKERS=0 runs it in one process).
python3 -m pytest -q -n "${ACD_TEST_WORKERS:-2}" --durations=15 --ignore="$ACD_REPO/tests/gui" "$ACD_REPO/tests" "$@"
rc=$?
set -e
if [ $rc -eq 5 ]; then
	echo "pytest collected no tests" >&2
	exit 1
fi
[ $rc -ne 0 ] && exit $rc

if [ "${ACD_SKIP_GUI:-0}" != 1 ]; then
	echo "== MeshLab GUI under Xvfb (builds MeshLab once, cached) =="
	bash "$here/run_gui_test.sh"
fi
