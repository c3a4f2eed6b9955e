#!/usr/bin/env bash
# Every test: the core's C++ tests (ctest) and the pytest suite through pymeshlab.
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
python3 -m pytest -q "$ACD_REPO/tests" "$@"
rc=$?
set -e
if [ $rc -eq 5 ]; then
	echo "pytest collected no tests" >&2
	exit 1
fi
exit $rc
