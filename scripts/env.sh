# Shared paths for the scripts (sourced, not run). Everything downloaded or built lives in a cache
# outside the repository; override ACD_CACHE to move it.
ACD_REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export ACD_REPO
export ACD_CACHE="${ACD_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/meshlab-acd}"
export ACD_MESHLAB_SRC="$ACD_CACHE/meshlab-2025.07-src"
export ACD_CGAL_ROOT="$ACD_CACHE/cgal-6.2.1"
# One build tree per checkout and precision (CMake ties a build tree to its source folder).
ACD_SCALAR="${ACD_SCALAR:-double}"
export ACD_SCALAR
export ACD_BUILD_DIR="${ACD_BUILD_DIR:-$ACD_CACHE/build-$ACD_SCALAR-$(printf %s "$ACD_REPO" | sha1sum | cut -c1-8)}"
