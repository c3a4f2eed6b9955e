#!/usr/bin/env bash
# Fetch the build inputs that Debian 12 does not carry, into a cache outside the repo:
#   - MeshLab 2025.07 sources (headers only are used) from Debian sid's source package `meshlab`
#   - CGAL 6.2.1 headers from Debian sid's libcgal-dev .deb (unpacked, never installed)
# A private apt config (own sources list and lists dir) keeps the system's apt sources untouched.
# Prints nothing but progress; the resulting paths are given by scripts/env.sh.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$here/env.sh"

MESHLAB_TARBALL="meshlab_2025.07~dfsg.orig.tar.xz"
MESHLAB_SHA256="d22c98d362f2a284e481af8dbfc272b2222f5b9c67b3cf8bec57d1c3161886f4"
MESHLAB_DEB_VERSION="2025.07~dfsg-4"
CGAL_DEB_VERSION="6.2.1"          # prefix; whatever sid serves as 6.2.1-*

mkdir -p "$ACD_CACHE"
apt_dir="$ACD_CACHE/apt-sid"
apt_conf="$apt_dir/apt.conf"

private_apt() {
	mkdir -p "$apt_dir/lists/partial" "$apt_dir/archives/partial" "$apt_dir/etc/preferences.d"
	cat > "$apt_dir/sources.list" <<SRC
deb http://deb.debian.org/debian sid main
deb-src http://deb.debian.org/debian sid main
SRC
	cat > "$apt_conf" <<CONF
Dir::Etc::SourceList "$apt_dir/sources.list";
Dir::Etc::SourceParts "/nonexistent";
Dir::Etc::Preferences "/nonexistent";
Dir::Etc::PreferencesParts "$apt_dir/etc/preferences.d";
Dir::State::Lists "$apt_dir/lists";
Dir::Cache::Archives "$apt_dir/archives";
Dir::Cache::pkgcache "";
Dir::Cache::srcpkgcache "";
APT::Get::AllowUnauthenticated "false";
CONF
	# Refresh the private lists at most once a day.
	if [ -z "$(find "$apt_dir/lists" -maxdepth 1 -name '*Sources*' -mtime -1 2>/dev/null | head -n1)" ]; then
		echo "[fetch_deps] updating private apt lists for sid (system sources untouched)"
		APT_CONFIG="$apt_conf" apt-get update -qq -o Debug::NoLocking=1 -o APT::Sandbox::User=root >/dev/null
	fi
}

sha_ok() { [ -f "$1" ] && [ "$(sha256sum "$1" | cut -d' ' -f1)" = "$2" ]; }

# ---- MeshLab sources -------------------------------------------------------------------------
tarball="$ACD_CACHE/$MESHLAB_TARBALL"
if ! sha_ok "$tarball" "$MESHLAB_SHA256"; then
	rm -f "$tarball"
	private_apt
	echo "[fetch_deps] fetching $MESHLAB_TARBALL with apt-get source"
	tmp="$(mktemp -d)"
	# The .dsc / debian tarball may answer 404 while the orig tarball is served: judge by checksum.
	(cd "$tmp" && APT_CONFIG="$apt_conf" apt-get source --download-only -qq -o APT::Sandbox::User=root \
		"meshlab=$MESHLAB_DEB_VERSION" >/dev/null 2>&1) || true
	[ -f "$tmp/$MESHLAB_TARBALL" ] && mv "$tmp/$MESHLAB_TARBALL" "$tarball"
	rm -rf "$tmp"
	if ! sha_ok "$tarball" "$MESHLAB_SHA256"; then
		rm -f "$tarball"
		if [ -n "${ACD_MESHLAB_TARBALL:-}" ] && sha_ok "$ACD_MESHLAB_TARBALL" "$MESHLAB_SHA256"; then
			echo "[fetch_deps] registry did not serve the tarball; using ACD_MESHLAB_TARBALL=$ACD_MESHLAB_TARBALL"
			cp "$ACD_MESHLAB_TARBALL" "$tarball"
		else
			echo "[fetch_deps] ERROR: could not get $MESHLAB_TARBALL with sha256 $MESHLAB_SHA256." >&2
			echo "  Set ACD_MESHLAB_TARBALL to a local copy with that checksum to build offline." >&2
			exit 1
		fi
	fi
fi
if [ ! -f "$ACD_MESHLAB_SRC/.extracted" ]; then
	echo "[fetch_deps] extracting MeshLab sources into $ACD_MESHLAB_SRC"
	rm -rf "$ACD_MESHLAB_SRC" && mkdir -p "$ACD_MESHLAB_SRC"
	tar -xJf "$tarball" -C "$ACD_MESHLAB_SRC" --strip-components=1
	touch "$ACD_MESHLAB_SRC/.extracted"
fi

# ---- CGAL 6.2.1 headers ----------------------------------------------------------------------
if [ ! -f "$ACD_CGAL_ROOT/.extracted" ]; then
	private_apt
	echo "[fetch_deps] downloading libcgal-dev $CGAL_DEB_VERSION from sid (unpacked into the cache only)"
	ver="$(APT_CONFIG="$apt_conf" apt-cache madison libcgal-dev | awk -F'|' '{gsub(/ /,"",$2); print $2}' \
		| grep "^$CGAL_DEB_VERSION" | head -n1 || true)"
	if [ -z "$ver" ]; then
		echo "[fetch_deps] sid serves no libcgal-dev $CGAL_DEB_VERSION; falling back to the system CGAL (5.5)"
	else
		tmp="$(mktemp -d)"
		(cd "$tmp" && APT_CONFIG="$apt_conf" apt-get download -qq -o APT::Sandbox::User=root "libcgal-dev=$ver" >/dev/null)
		rm -rf "$ACD_CGAL_ROOT" && mkdir -p "$ACD_CGAL_ROOT"
		dpkg -x "$tmp"/libcgal-dev_*.deb "$ACD_CGAL_ROOT"
		rm -rf "$tmp"
		echo "$ver" > "$ACD_CGAL_ROOT/.extracted"
	fi
fi
echo "[fetch_deps] MeshLab sources: $ACD_MESHLAB_SRC"
if [ -f "$ACD_CGAL_ROOT/.extracted" ]; then
	echo "[fetch_deps] CGAL: $ACD_CGAL_ROOT (libcgal-dev $(cat "$ACD_CGAL_ROOT/.extracted"))"
fi
