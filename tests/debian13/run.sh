#!/usr/bin/env bash
# make test-debian13: the non-VM test suite (make test) built and run in a Debian 13 (trixie)
# root beside this Debian 12 machine, so GCC 14, Mesa 25 and libgpiod 2 are exercised
# (docs/distributions.md). As root.
#
#   1. The root: debootstrap --variant=minbase trixie from the archive this machine's apt uses
#      (its URI read from /etc/apt/sources.list.d/debian.sources or /etc/apt/sources.list at
#      run time), then tools/deps.sh test inside it, which knows Debian 13's package names.
#      Cached in $DEBIAN13_DIR (build/debian13): root.stamp records the package sets it was
#      made with; when tools/deps.sh changes, the packages are brought up to date in place.
#   2. The source tree (what git tracks and what it does not ignore, not build/) is copied to
#      /sbfx in the root; its build/ there is kept between runs, so a second run rebuilds only
#      what changed.
#   3. The root bound onto itself, proc, sysfs, /dev and a /dev/shm of its own are mounted for the run and unmounted on
#      every exit path (the trap), then `make -j$(nproc) test` runs in it; its exit status is
#      the run's.
# Environment: DEBIAN13_DIR (build/debian13), MAKE_TARGET (test).
set -euo pipefail
cd "$(dirname "$0")/../.."
DIR=${DEBIAN13_DIR:-build/debian13}
case $DIR in /*) ;; *) DIR=$PWD/$DIR ;; esac
ROOT=$DIR/root
STAMP=$DIR/root.stamp
TARGET=${MAKE_TARGET:-test}
SUITE=trixie

say() { printf 'debian13: %s\n' "$*" >&2; }
[ "$(id -u)" -eq 0 ] || { say "needs root (debootstrap, chroot, mount)"; exit 1; }
command -v debootstrap >/dev/null || { say "debootstrap is missing (tools/deps.sh debian13)"; exit 1; }

# The archive's URI: the first "URIs:" of a deb822 source that serves the main suite (not
# security), else the first plain "deb" line.
archive_uri() {
    local f=/etc/apt/sources.list.d/debian.sources
    if [ -r "$f" ]; then
        awk '/^URIs:/ { uri = $2 } /^Suites:/ && uri != "" && $0 !~ /-security/ { print uri; exit }
             /^$/ { uri = "" }' "$f"
    fi
    if [ -r /etc/apt/sources.list ]; then
        awk '$1 == "deb" && $0 !~ /security/ { for (i = 2; i <= NF; i++) if ($i ~ /^[a-z]+:\/\//) { print $i; exit } }' \
            /etc/apt/sources.list
    fi
}

# Mounts, undone in reverse order on every exit path.
MOUNTED=()
unmount_all() {
    local i
    for ((i = ${#MOUNTED[@]} - 1; i >= 0; i--)); do
        umount "${MOUNTED[i]}" 2>/dev/null || umount -l "${MOUNTED[i]}" 2>/dev/null ||
            say "could not unmount ${MOUNTED[i]}"
    done
    MOUNTED=()
}
trap unmount_all EXIT
trap 'exit 130' INT TERM
mount_in() { # mount_in TARGET MOUNT-ARGS...
    local target=$ROOT$1
    shift
    mkdir -p "$target"
    mount "$@" "$target"
    MOUNTED+=("$target")
}
mount_all() {
    # the root bound onto itself: / in the chroot is then a mount point, which `unshare -m`
    # (tests/no_data_files.sh) needs to make its mounts private
    mount_in / --bind "$ROOT"
    mount_in /proc -t proc proc
    mount_in /sys -t sysfs sysfs
    mount_in /dev --bind /dev
    mount_in /dev/pts --bind /dev/pts
    # POSIX shared memory of its own (the bind above does not carry the host's /dev/shm): cage 0.2's
    # wlroots 0.18 allocates its headless output's buffers there (tests/wayland.sh)
    mount_in /dev/shm -t tmpfs -o mode=1777 tmpfs
}
in_root() { chroot "$ROOT" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 "$@"; }

# What the root was made with: the suite and tools/deps.sh's text (its package sets).
wanted_stamp() { printf '%s\n' "$SUITE"; sha256sum tools/deps.sh | cut -d' ' -f1; }

make_root() {
    local uri
    uri=$(archive_uri | head -n 1)
    [ -n "$uri" ] || { say "no Debian archive in the machine's apt sources"; exit 1; }
    say "debootstrap --variant=minbase $SUITE into $ROOT (a minute or two)"
    rm -rf --one-file-system "$ROOT" "$STAMP"
    mkdir -p "$DIR"
    debootstrap --variant=minbase "$SUITE" "$ROOT" "$uri" >"$DIR/debootstrap.log" 2>&1 || {
        tail -n 5 "$DIR/debootstrap.log" >&2
        exit 1
    }
}

# The test package set, named as Debian 13 names it (tools/deps.sh reads /etc/os-release).
install_packages() {
    mkdir -p "$ROOT/tmp/sbfx-deps"
    cp tools/deps.sh "$ROOT/tmp/sbfx-deps/deps.sh"
    say "tools/deps.sh test in the root"
    in_root sh -c 'apt-get update -qq && sh /tmp/sbfx-deps/deps.sh test' >"$DIR/deps.log" 2>&1 || {
        tail -n 8 "$DIR/deps.log" >&2
        exit 1
    }
    rm -rf "$ROOT/tmp/sbfx-deps"
}

# The working tree as git sees it (tracked and untracked-not-ignored files), mtimes kept.
copy_tree() {
    mkdir -p "$ROOT/sbfx"
    # files removed from the tree since the last copy go too (build/ stays)
    find "$ROOT/sbfx" -mindepth 1 -maxdepth 1 ! -name build -exec rm -rf {} +
    git ls-files -z --cached --others --exclude-standard |
        while IFS= read -r -d '' f; do [ -e "$f" ] && printf '%s\0' "$f"; done |
        tar --null -T - -cf - | tar -xf - -C "$ROOT/sbfx"
}

# Mounts a killed run (SIGKILL: no trap) left behind, deepest first: removing or remaking the
# root over a bound /dev would remove the machine's device nodes.
unmount_leftovers() {
    local m
    awk -v root="$ROOT" '$2 == root || index($2, root "/") == 1 { print length($2), $2 }' /proc/mounts |
        sort -rn | cut -d' ' -f2- | while read -r m; do
        umount "$m" 2>/dev/null || umount -l "$m" || say "could not unmount $m (left by an earlier run)"
    done
}

start=$SECONDS
unmount_leftovers
if [ ! -f "$STAMP" ] || ! [ -x "$ROOT/usr/bin/apt-get" ]; then
    make_root
fi
mount_all
if [ "$(cat "$STAMP" 2>/dev/null)" != "$(wanted_stamp)" ]; then
    install_packages
    wanted_stamp >"$STAMP"
fi
say "root ready in $((SECONDS - start)) s: $(in_root sh -c '. /etc/os-release; echo "$PRETTY_NAME"'), $(in_root gcc --version | head -n 1), libgpiod $(in_root pkg-config --modversion libgpiod)"
copy_tree
say "make -j$(nproc) $TARGET in the root"
rc=0
in_root sh -c "cd /sbfx && make -j$(nproc) $TARGET" || rc=$?
say "make $TARGET exited with $rc after $((SECONDS - start)) s in all"
exit "$rc"
