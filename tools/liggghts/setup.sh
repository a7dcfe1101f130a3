#!/usr/bin/env bash
# Build LIGGGHTS-PUBLIC 3.8.0 (Debian's source) with superquadric support and the ELLIPSOID_DEP
# adapter (`surface ellipsoid`). Called as `./ellipsoid-dep liggghts setup`; can also be run
# directly. Every step is skipped when already done; prints the binary's path on stdout.
#
#   1. orig tarball  -> $CACHE/src/liggghts_3.8.0+repack1.orig.tar.xz (apt-get source)
#   2. extracted + patched tree -> $CACHE/liggghts-3.8.0-<key>/LIGGGHTS-PUBLIC-3.8.0
#      (<key> = hash of the patches and the machine makefile)
#   3. adapter + kernel sources synced into its src/ (copied only when changed, so an edit of
#      the adapter or the kernel rebuilds only what depends on it)
#   4. make ellipsoid_dep (2 parallel compiles by default, progress shown)
#   5. the binary, copied to this checkout's build/lmp_liggghts (the tree is shared by every
#      checkout on the machine: steps 3-5 hold a lock, and each checkout keeps the binary of
#      its own kernel and adapter); $CACHE/liggghts-current points at the tree.
# Environment: JOBS (parallel compiles, default nproc), XDG_CACHE_HOME.
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
CACHE="${XDG_CACHE_HOME:-$HOME/.cache}/ellipsoid-dep"
VERSION="3.8.0"
TARBALL="liggghts_3.8.0+repack1.orig.tar.xz"
SHA256="c18721d9a870c5170f03b91e4f1ffe13335c66ed1f0ff2c64ebd3be91c37867a"
TOPDIR="LIGGGHTS-PUBLIC-3.8.0"
JOBS="${JOBS:-$(nproc)}"
APT_PACKAGES=(build-essential libopenmpi-dev openmpi-bin libeigen3-dev zlib1g-dev xz-utils
  debian-archive-keyring)

say() { printf '\033[1m[liggghts]\033[0m %s\n' "$*" >&2; }
die() { say "ERROR: $*"; exit 1; }
as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }

KEY="$(cat "$HERE"/patches/*.patch "$HERE/Makefile.ellipsoid_dep" | sha256sum | cut -c1-10)"
BUILD="$CACHE/liggghts-$VERSION-$KEY"
SRC="$BUILD/$TOPDIR/src"
# the LIGGGHTS tree in the cache is shared by every checkout on the machine; each checkout
# builds it with its own kernel and adapter under a lock and keeps its own copy of the binary
EXE="$ROOT/build/lmp_liggghts"
LOCK="$CACHE/liggghts.lock"

install_packages() {
  local missing=()
  for p in "${APT_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  say "installing Debian packages: ${missing[*]}"
  mkdir -p "$CACHE"
  { as_root apt-get update -qq &&
    DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq --no-install-recommends \
      "${missing[@]}"; } >"$CACHE/apt-liggghts.log" 2>&1 ||
    { tail -n 30 "$CACHE/apt-liggghts.log"; die "apt-get install failed"; }
}

tarball_ok() { [ -f "$1" ] && echo "$SHA256  $1" | sha256sum -c --quiet - >/dev/null 2>&1; }

download() {
  local tar="$CACHE/src/$TARBALL"
  tarball_ok "$tar" && return 0
  mkdir -p "$CACHE/src"
  say "downloading the LIGGGHTS $VERSION source from Debian's source archive (6.5 MB)"
  # any deb-src entry that knows a liggghts 3.8.0+repack1 source will do
  if ! apt-cache showsrc liggghts 2>/dev/null | grep -q '^Version: 3.8.0+repack1'; then
    local list=/etc/apt/sources.list.d/ellipsoid-dep-liggghts-src.sources
    say "adding a deb-src entry ($list)"
    as_root tee "$list" >/dev/null <<EOF
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm sid
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
    as_root apt-get update -qq >&2
  fi
  local v
  # the newest 3.8.0+repack1 source revision; all share the same orig tarball. The .dsc and
  # .debian.tar.xz may answer 404 (apt-get then exits non-zero): only the orig tarball matters.
  for v in $(apt-cache showsrc liggghts | sed -n 's/^Version: \(3\.8\.0+repack1.*\)/\1/p' |
             sort -rV); do
    (cd "$CACHE/src" && apt-get source --download-only "liggghts=$v" >/dev/null 2>&1) || true
    tarball_ok "$tar" && break
  done
  [ -f "$tar" ] || die "could not download $TARBALL with apt-get source"
  tarball_ok "$tar" || die "checksum mismatch for $tar"
}

extract_and_patch() {
  [ -f "$BUILD/.patched" ] && return 0
  say "extracting and patching into $BUILD"
  rm -rf "$BUILD/$TOPDIR"; mkdir -p "$BUILD"
  tar -xJf "$CACHE/src/$TARBALL" -C "$BUILD"
  local p
  for p in "$HERE"/patches/*.patch; do
    say "  patch $(basename "$p")"
    patch -d "$BUILD/$TOPDIR" -p1 --forward --quiet <"$p" || die "patch $p failed"
  done
  cp "$HERE/Makefile.ellipsoid_dep" "$SRC/MAKE/Makefile.ellipsoid_dep"
  touch "$BUILD/.patched"
}

# copy $1 to $2 only when the content differs (keeps timestamps, so make rebuilds only what changed)
sync_file() { cmp -s "$1" "$2" || { cp "$1" "$2"; say "  updated $(basename "$2")"; }; }

sync_adapter() {
  local f
  for f in "$ROOT"/src/liggghts/*; do [ -f "$f" ] || continue; sync_file "$f" "$SRC/$(basename "$f")"; done
  # the contact kernel: src/kernel without its force laws (src/kernel/force_laws: LIGGGHTS
  # uses its own)
  for f in "$ROOT"/src/kernel/*.h "$ROOT"/src/kernel/*.cpp; do
    sync_file "$f" "$SRC/$(basename "$f")"
  done
  # a kernel file another checkout synced and this one does not have would be built in
  for f in "$SRC"/ellipsoid_*; do
    [ -e "$ROOT/src/kernel/$(basename "$f")" ] || [ -e "$ROOT/src/liggghts/$(basename "$f")" ] ||
      { rm -f "$f" "$SRC/Obj_ellipsoid_dep/$(basename "${f%.*}").o"; say "  removed $(basename "$f")"; }
  done
}

build() {
  local total log="$BUILD/build.log"
  total=$(ls "$SRC"/*.cpp | wc -l)
  # percentages for a full build; an incremental one (objects exist) just counts its files
  local full=1
  compgen -G "$SRC/Obj_ellipsoid_dep/*.o" >/dev/null && full=0
  say "building LIGGGHTS $VERSION + surface ellipsoid ($total sources, $JOBS parallel; a full build is ~8 min of CPU, 5-16 min on a shared 2-core machine; log $log)"
  local ccache=""
  command -v ccache >/dev/null && ccache="ccache"
  local start=$SECONDS
  set +o pipefail
  # (a bash loop, not awk: Debian's mawk reads a pipe in blocks, so progress would come late)
  (cd "$SRC" && make -j"$JOBS" ellipsoid_dep CCACHE="$ccache" 2>&1) | tee "$log" | {
    n=0
    while IFS= read -r line; do
      case "$line" in
        "CXX "*) n=$((n + 1))
          if [ "$full" = 1 ]; then printf '  [%3d%%] %s\n' $((100 * n / total)) "${line#CXX }"
          else printf '  [%d] %s\n' "$n" "${line#CXX }"; fi ;;
        LINK*) echo "  linking" ;;
        *error*|*Error*) echo "$line" ;;
      esac
    done; } >&2
  local rc=${PIPESTATUS[0]}
  set -o pipefail
  [ "$rc" = 0 ] && [ -x "$SRC/lmp_ellipsoid_dep" ] ||
    die "LIGGGHTS build failed (make exit $rc; log: $log)"
  mkdir -p "$(dirname "$EXE")"
  if ! cmp -s "$SRC/lmp_ellipsoid_dep" "$EXE"; then cp "$SRC/lmp_ellipsoid_dep" "$EXE"; fi
  ln -sfn "$BUILD" "$CACHE/liggghts-current"
  say "built $EXE in $((SECONDS - start)) s"
}

# what this checkout's binary was built from: the tree's key and the synced sources
sources_stamp() {
  { echo "$KEY"; cat "$ROOT"/src/liggghts/* "$ROOT"/src/kernel/*.h "$ROOT"/src/kernel/*.cpp; } |
    sha256sum | cut -c1-16
}

main() {
  install_packages
  # the binary of these very sources exists: nothing to do (LIGGGHTS's make would still
  # recompile its version stamp and relink, several seconds at every call)
  local stamp
  stamp="$(sources_stamp)"
  if [ -x "$EXE" ] && [ "$(cat "$EXE.stamp" 2>/dev/null)" = "$stamp" ]; then
    echo "$EXE"
    return
  fi
  download
  # one checkout at a time in the shared tree (sync, make and the copy of the binary)
  exec 9>"$LOCK"
  flock 9
  extract_and_patch
  sync_adapter
  build
  echo "$stamp" >"$EXE.stamp"
  echo "$EXE"
}

case "${1:-setup}" in
  setup) main ;;
  source) install_packages; download; extract_and_patch; sync_adapter; echo "$SRC" ;;  # no build
  path) echo "$EXE" ;;          # where the binary is (or will be)
  *) die "usage: setup.sh [setup|source|path]" ;;
esac
