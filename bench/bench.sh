#!/usr/bin/env bash
# Benchmark against CoACD, V-HACD 4 and CGAL's ACD (see bench/bench.py --help); with --robots, the
# robot corpus with the certificate and the peers on a sample (bench/bench_robots.py); with --rotation,
# the pose-dependence table instead (bench/bench_rotation.py); with --scale, time against face count on a
# scan and a CAD series (bench/bench_scale.py); with --open, open meshes against closed ones
# (bench/bench_open.py); with --robot-descriptions, every URDF of example-robot-data through the robot command,
# loaded and dropped in PyBullet and MuJoCo (bench/bench_robot_descriptions.py); with --polygons, the 2D table against
# CGAL's Partition_2 (bench/bench_polygons.py). Installs what it needs on top of
# scripts/setup.sh: the peers from PyPI and the C++ metric/peer tools.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bash "$here/../scripts/setup.sh"
source "$here/../scripts/env.sh"
python3 -m pip install -q "coacd==1.0.14" "vhacdx==0.1.1" "matplotlib>=3.7" 2>&1 | grep -v "running pip as the 'root'" || true
if [ "${1:-}" = "--polygons" ]; then   # 2D: ours vs CGAL Partition_2 (no Python peers needed)
	shift
	cmake --build "$ACD_BUILD_DIR" --target polygon_peer -- -j"$(nproc)" >/dev/null
	exec python3 "$here/bench_polygons.py" "$@"
fi
cmake --build "$ACD_BUILD_DIR" --target acd_metrics cgal_acd_peer -- -j"$(nproc)" >/dev/null
if [ "${1:-}" = "--robot-descriptions" ]; then   # whole robots: rewrite, load, drop, budgets, cache
	shift
	exec python3 "$here/bench_robot_descriptions.py" "$@"
fi
if [ "${1:-}" = "--robots" ]; then   # the example-robot-data corpus: ours on every mesh, the peers on a sample
	shift
	exec python3 "$here/bench_robots.py" "$@"
fi
if [ "${1:-}" = "--scale" ]; then   # time against face count: a scan series and a CAD series
	shift
	exec python3 "$here/bench_scale.py" "$@"
fi
if [ "${1:-}" = "--open" ]; then   # open meshes against closed ones, per set, and a 1M-face open scan
	shift
	exec python3 "$here/bench_open.py" "$@"
fi
if [ "${1:-}" = "--rotation" ]; then
	shift
	exec python3 "$here/bench_rotation.py" "$@"
fi
exec python3 "$here/bench.py" "$@"
