#!/usr/bin/env bash
# Prepare OpenFOAM v1912 development sources (headers + wmake) matching Debian's `openfoam`
# package, so foam-solvers/ can compile solvers against the libraries in /usr/lib.
#
#   foam-solvers/prepare-openfoam-sources.sh DEST      (e.g. /opt/talus/openfoam-v1912)
#
# Idempotent: DEST/.talus-prepared marks a finished tree and makes a re-run a no-op; a failed
# run leaves no marker and the next run picks up where it stopped. Needs root the first time
# (it adds a deb-src entry derived from the machine's own Debian entry and runs apt-get update).
set -euo pipefail

dest=${1:?usage: $0 DEST}
dest=$(realpath -m "$dest")
orig=openfoam_1912.200626.orig.tar.bz2
say() { printf 'prepare-openfoam-sources: %s\n' "$*"; }

if [ -e "$dest/.talus-prepared" ]; then
  say "$dest is already prepared"
  exit 0
fi

# 1. A deb-src entry, copied from the machine's main Debian entry (never a hard-coded archive).
if grep -rqsE '^(Types:.*deb-src|deb-src )' /etc/apt/sources.list /etc/apt/sources.list.d/; then
  say "a deb-src entry exists"
elif [ -f /etc/apt/sources.list.d/debian.sources ]; then
  # First stanza only (the main archive), source packages, first suite only (the release).
  awk '/^[[:space:]]*$/ { exit }
       /^Types:/  { print "Types: deb-src"; next }
       /^Suites:/ { print "Suites: " $2; next }
       { print }' /etc/apt/sources.list.d/debian.sources >/etc/apt/sources.list.d/talus-deb-src.sources
  say "wrote /etc/apt/sources.list.d/talus-deb-src.sources"
elif grep -qE '^deb ' /etc/apt/sources.list 2>/dev/null; then
  grep -m1 -E '^deb ' /etc/apt/sources.list | sed 's/^deb /deb-src /' \
    >/etc/apt/sources.list.d/talus-deb-src.list
  say "wrote /etc/apt/sources.list.d/talus-deb-src.list"
else
  say "no Debian archive entry found to derive a deb-src entry from" >&2
  exit 1
fi

# 2. Download the source package and unpack the upstream tarball into DEST.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
chown _apt "$tmp" 2>/dev/null || true   # lets apt download as _apt (no "unsandboxed" warning)
say "apt-get update"
apt-get update -qq
say "downloading the openfoam source package"
(cd "$tmp" && apt-get source -qq --download-only openfoam)
[ -f "$tmp/$orig" ] || { say "apt-get source did not fetch $orig" >&2; exit 1; }
say "unpacking $orig into $dest"
mkdir -p "$dest"
tar -xjf "$tmp/$orig" -C "$dest" --strip-components=1 --no-same-owner

# 3. The environment Debian built with (foam-solvers/foam-env.sh.in sets the same for wmake).
export WM_PROJECT_DIR=$dest WM_DIR=$dest/wmake WM_PROJECT=OpenFOAM WM_PROJECT_VERSION=v1912 \
       WM_ARCH=linux64 WM_COMPILER=Gcc WM_COMPILER_TYPE=system WM_COMPILE_OPTION=Opt \
       WM_PRECISION_OPTION=DP WM_LABEL_SIZE=32 WM_LABEL_OPTION=Int32 \
       WM_OPTIONS=linux64GccDPInt32Opt WM_MPLIB=SYSTEMOPENMPI FOAM_SRC=$dest/src FOAM_LIBBIN=/usr/lib
export PATH=$WM_DIR:$PATH

# 4. wmake's helper programs, then the lnInclude folders of the libraries solvers include.
say "building wmake helpers"
if ! (cd "$WM_DIR/src" && ./Allmake) >"$tmp/allmake.log" 2>&1; then
  tail -n 30 "$tmp/allmake.log" >&2
  say "building wmake helpers failed (needs g++, make, flex)" >&2
  exit 1
fi
for lib in OpenFOAM OSspecific/POSIX finiteVolume meshTools fileFormats surfMesh dynamicMesh \
           lagrangian/basic Pstream/mpi; do
  say "lnInclude src/$lib"
  out=$(wmakeLnInclude -u "$FOAM_SRC/$lib" 2>&1) || { echo "$out" >&2; exit 1; }
done

touch "$dest/.talus-prepared"
say "done: $dest"
