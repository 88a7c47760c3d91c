#!/usr/bin/env bash
# make test-fresh: the README's quick start, verbatim, on a bare Debian machine
# (docs/testing.md "A fresh machine"). As root (debootstrap, chroot, mount).
#
#   DIST=bookworm (Debian 12, the default) or DIST=trixie (Debian 13).
#
#   1. The bare root: `debootstrap --variant=minbase DIST` from the archive this machine's apt
#      uses (its URI read from the apt sources at run time), plus what the README's
#      Requirements ask a reader to have before the two commands: git and make. Nothing else.
#      Made once per DIST and kept in $FRESH_DIR/DIST/base (base.stamp: the suite and that
#      package list); each run works in a fresh copy of it, $FRESH_DIR/DIST/root.
#   2. The commit under test (HEAD, or the ref FRESH_REF), not the working tree: a git bundle of it,
#      cloned inside the root with `git clone`, as a reader clones the project.
#   3. As a plain user (scenario "user"): `make demo` must stop and print the one apt-get line;
#      that line is run as root; then `make demo` as the user must render.
#   4. Then as root in the same root (scenario "root"): `make demo` and `make test` in a clone of
#      its own, as the README shows them; they install what is still missing (make test: the
#      test packages). The run fails when any step fails. FRESH_AS="root" skips the user.
#   Downloaded packages are shared (debootstrap's and apt's cache: $FRESH_DIR/DIST/apt, which
#   starts with the machine's own downloads when DIST is the machine's release), so a second
#   run downloads nothing again. The root is removed after a run that passes (FRESH_KEEP=1 keeps
#   it) and kept for a look when it fails.
#   5. FRESH_AS="deb" (make test-deb) or "user root deb": the Debian packages built in a fresh
#      copy of the bare root from debian/control's build dependencies, installed with apt into
#      another, checked and purged there (scenario_deb below; DEB_ARCH=arm64 cross builds).
# Environment: DIST, FRESH_DIR (build/fresh), FRESH_AS ("user root"), FRESH_REF (HEAD; a branch or tag),
# DEB_ARCH (this machine's; arm64).
# The whole script is one brace group: bash reads it all before running it, so editing this file
# while a run (half an hour) goes on does not change what that run does.
{
set -euo pipefail
cd "$(dirname "$0")/../.."
DIST=${DIST:-bookworm}
case $DIST in bookworm | trixie) ;; *)
    echo "test-fresh: DIST=$DIST: bookworm (Debian 12) or trixie (Debian 13)" >&2
    exit 2
    ;;
esac
TOP=${FRESH_DIR:-build/fresh}
case $TOP in /*) ;; *) TOP=$PWD/$TOP ;; esac
DIR=$TOP/$DIST
BASE=$DIR/base
SCENARIOS=${FRESH_AS:-user root}
REF=${FRESH_REF:-HEAD}
COMMIT=$(git rev-parse --verify "$REF^{commit}")
# What the README's Requirements tell a reader to install on a bare Debian before the two
# commands (README.md "Requirements"; tests/docs.sh checks that the README names them).
REQUIREMENTS="git make"
USER_NAME=reader

# what the run says goes to fd 3, the run's stderr, also from inside commands whose output goes
# to a log
exec 3>&2
say() { printf 'fresh %s: %s\n' "$DIST" "$*" >&3; }
[ "$(id -u)" -eq 0 ] || { say "needs root (debootstrap, chroot, mount)"; exit 1; }
command -v debootstrap >/dev/null || { say "debootstrap is missing (tools/deps.sh fresh)"; exit 1; }
[ -z "$(git status --porcelain --untracked-files=no)" ] ||
    say "note: uncommitted changes are not tested; the commit is $(git log -1 --format='%h %s' "$COMMIT")"

# The archive's URI: the first "URIs:" of a deb822 stanza that serves a main suite (not
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

# The package cache the roots share, $DIR/apt. For the machine's own release it starts with
# hard links to what the machine's apt has downloaded, and gives back what it downloaded at the
# end: not the folder itself, whose lock the machine's own apt may hold meanwhile.
CACHE=$DIR/apt
mkdir -p "$CACHE/partial"
host_codename=$(. /etc/os-release 2>/dev/null && echo "${VERSION_CODENAME:-}")
if [ "$host_codename" = "$DIST" ]; then
    find /var/cache/apt/archives -maxdepth 1 -name '*.deb' -exec cp -l -n -t "$CACHE" {} + 2>/dev/null || true
fi

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
mount_in() { # mount_in ROOT TARGET MOUNT-ARGS...
    local target=$1$2
    shift 2
    mkdir -p "$target"
    mount "$@" "$target"
    MOUNTED+=("$target")
}
mount_all() { # mount_all ROOT
    # the root bound onto itself: / in the chroot is then a mount point, which `unshare -m`
    # (tests/no_data_files.sh) needs to make its mounts private
    mount_in "$1" / --bind "$1"
    mount_in "$1" /proc -t proc proc
    mount_in "$1" /sys -t sysfs sysfs
    mount_in "$1" /dev --bind /dev
    mount_in "$1" /dev/pts --bind /dev/pts
    # POSIX shared memory of its own (the bind above does not carry the host's /dev/shm): cage 0.2's
    # wlroots 0.18 allocates its headless output's buffers there (tests/wayland.sh)
    mount_in "$1" /dev/shm -t tmpfs -o mode=1777 tmpfs
    # the unified cgroup hierarchy, as a Debian machine mounts it (tests/wayland.sh delegates a
    # subtree of it to a user manager)
    mount_in "$1" /sys/fs/cgroup -t cgroup2 cgroup2
    mount_in "$1" /var/cache/apt/archives --bind "$CACHE"
}

# Mounts a killed run (SIGKILL: no trap) left behind, deepest first: removing or remaking a
# root over a bound /dev would remove the machine's device nodes.
unmount_leftovers() {
    local m
    awk -v dir="$DIR" 'index($2, dir "/") == 1 { print length($2), $2 }' /proc/mounts |
        sort -rn | cut -d' ' -f2- | while read -r m; do
        umount "$m" 2>/dev/null || umount -l "$m" || say "could not unmount $m (left by an earlier run)"
    done
}

# in_root ROOT [--userspec=U:G] COMMAND...: COMMAND in the root, in a clean environment as a
# login would give. The root is entered as a container would be, not with chroot alone: a mount
# namespace of its own whose root is ROOT (pivot_root; the machine's own tree unmounted in it).
# The kernel refuses user namespaces to a chrooted process, and the tests start a user manager
# whose services use one (tests/wayland.sh), as they would on a machine of their own.
in_root() {
    local root=$1 home=/root spec=()
    shift
    case $1 in --userspec=*) spec=("$1") home=/home/$USER_NAME; shift ;; esac
    unshare --mount --propagation private /bin/sh -c '
        cd "$1" && pivot_root . .fresh-host && cd / && umount -l /.fresh-host || exit 125
        shift
        exec "$@"' sh "$root" chroot "${spec[@]}" / /usr/bin/env -i PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
        HOME="$home" USER="${spec:+$USER_NAME}" LANG=C.UTF-8 "$@" 3>&- 9>&-
}
as_reader() { in_root "$1" --userspec="$USER_NAME:$USER_NAME" "${@:2}"; }

base_stamp() { printf '%s\n%s\n' "$DIST" "$REQUIREMENTS"; }
make_base() {
    local uri
    uri=$(archive_uri | head -n 1)
    [ -n "$uri" ] || { say "no Debian archive in the machine's apt sources"; exit 1; }
    say "debootstrap --variant=minbase --include=${REQUIREMENTS// /,} $DIST (a minute or two)"
    rm -rf --one-file-system "$BASE" "$DIR/base.stamp"
    mkdir -p "$DIR"
    debootstrap --variant=minbase --include="${REQUIREMENTS// /,}" --cache-dir="$CACHE" \
        "$DIST" "$BASE" "$uri" >"$DIR/debootstrap.log" 2>&1 || {
        tail -n 5 "$DIR/debootstrap.log" >&3
        exit 1
    }
    chroot "$BASE" useradd --create-home --shell /bin/sh "$USER_NAME"
    base_stamp >"$DIR/base.stamp"
}

# new_root [PATH]: a fresh copy of the bare root ($ROOT, or PATH) with the commit's bundle in
# /tmp, mounted.
ROOT=$DIR/root
new_root() {
    local root=${1:-$ROOT}
    rm -rf --one-file-system "$root"
    cp -a "$BASE" "$root"
    mkdir "$root/.fresh-host" # where in_root's pivot_root puts the machine's tree, unmounted at once
    git bundle create -q "$root/tmp/sbfx.bundle" "$REF"
    chmod 644 "$root/tmp/sbfx.bundle"
    mount_all "$root"
}

# timed LABEL COMMAND...: runs COMMAND, says how long it took; its status is COMMAND's.
timed() {
    local label=$1 t=$SECONDS rc=0
    shift
    "$@" || rc=$?
    say "$label: $((SECONDS - t)) s (exit status $rc)"
    return "$rc"
}

clone_cmd="git clone -q /tmp/sbfx.bundle sbfx && cd sbfx && git checkout -q $COMMIT"

# As a plain user: make demo names the packages and stops; the line as root; make demo renders.
scenario_user() {
    local out=$DIR/user-demo-1.log line
    if timed "user: make demo (no packages yet)" as_reader "$ROOT" sh -c "cd && $clone_cmd && make demo" >"$out" 2>&1; then
        say "user: make demo succeeded without the packages installed: it should have printed the apt-get line"
        tail -n 5 "$out" >&3
        return 1
    fi
    line=$(grep -A1 -m1 'As root, run:' "$out" | tail -n 1 | sed 's/^ *//')
    case $line in
    "apt-get update && apt-get install -y --no-install-recommends "*) say "user: make demo printed: $line" ;;
    *)
        say "user: make demo did not print the one apt-get line; its last lines:"
        tail -n 5 "$out" >&3
        return 1
        ;;
    esac
    timed "user: that line as root" in_root "$ROOT" env DEBIAN_FRONTEND=noninteractive sh -c "$line" \
        >"$DIR/user-apt.log" 2>&1 || { tail -n 8 "$DIR/user-apt.log" >&3; return 1; }
    timed "user: make demo" as_reader "$ROOT" sh -c 'cd ~/sbfx && make demo' >"$DIR/user-demo-2.log" 2>&1 || {
        tail -n 8 "$DIR/user-demo-2.log" >&3
        return 1
    }
    [ -s "$ROOT/home/$USER_NAME/sbfx/build/demo/contact-sheet.png" ] || {
        say "user: make demo left no build/demo/contact-sheet.png"
        return 1
    }
    tail -n 2 "$DIR/user-demo-2.log" | sed "s/^/fresh $DIST: user: /" >&3
}

# As root, the README's two commands.
scenario_root() {
    timed "root: make demo" in_root "$ROOT" sh -c "cd && $clone_cmd && make demo" >"$DIR/root-demo.log" 2>&1 || {
        tail -n 20 "$DIR/root-demo.log" >&3
        return 1
    }
    tail -n 2 "$DIR/root-demo.log" | sed "s/^/fresh $DIST: root: /" >&3
    timed "root: make test" in_root "$ROOT" sh -c 'cd ~/sbfx && make test' 2>&1 | tee "$DIR/root-test.log" || return 1
}

# The Debian packages (issue 46, make test-deb; docs/packaging.md), from the same bare root and
# package cache: built in a fresh copy of the root with what debian/control's Build-Depends name
# (apt-get build-dep) and nothing else, lintian there (this release's); installed with apt into a
# second fresh copy, where tests/fresh/deb-checks.sh runs the player, a host built with
# pkg-config, gst-inspect-1.0 and systemd-analyze verify, then purges them and looks for what is
# left. DEB_ARCH=arm64: the same packages cross built (apt-get build-dep -a arm64, multiarch) and
# checked as aarch64 objects in the multiarch folders (tools/deb.sh); not installed in an arm64
# root, but the player run under qemu-user in the build root (deb_under_qemu).
DEB_ARCH=${DEB_ARCH:-$(dpkg --print-architecture)}
scenario_deb() {
    local build=$DIR/deb-build install=$DIR/deb-install native version arch_opt="" add_arch="" cross=""
    native=$(dpkg --print-architecture)
    version=$(git show "$COMMIT:Makefile" | sed -n 's/^VERSION := //p')
    if [ "$DEB_ARCH" != "$native" ]; then
        # a cross build: DEB_ARCH's build dependencies through multiarch, and Debian's cross
        # toolchain (crossbuild-essential, as sbuild installs it; build-dep brings build-essential)
        arch_opt="-a $DEB_ARCH"
        add_arch="dpkg --add-architecture $DEB_ARCH && "
        cross="crossbuild-essential-$DEB_ARCH"
    fi
    new_root "$build"
    timed "deb: build-dep, dpkg-buildpackage $arch_opt, lintian" in_root "$build" env DEBIAN_FRONTEND=noninteractive sh -c "
        set -e; cd && $clone_cmd
        mkdir -p /tmp/control/debian && cp dist/debian/control /tmp/control/debian/
        ${add_arch}apt-get update -qq
        apt-get build-dep -y -qq --no-install-recommends $arch_opt /tmp/control
        apt-get install -y -qq --no-install-recommends lintian $cross
        tools/deb.sh $DEB_ARCH build/deb" >"$DIR/deb-build.log" 2>&1 || {
        tail -n 25 "$DIR/deb-build.log" >&3
        return 1
    }
    grep '^deb ' "$DIR/deb-build.log" | sed "s/^/fresh $DIST: /" >&3
    local debs=$build/root/sbfx/build/deb/$DEB_ARCH
    if [ "$DEB_ARCH" != "$native" ]; then
        deb_under_qemu
        return
    fi
    new_root "$install"
    mkdir -p "$install/tmp/debs"
    cp "$debs"/*.deb "$install/tmp/debs/"
    rm -f "$install"/tmp/debs/*-dbgsym_*.deb
    git show "$COMMIT:examples/bare-egl/host.c" >"$install/tmp/host.c"
    git show "$COMMIT:tests/fresh/deb-checks.sh" >"$install/tmp/deb-checks.sh"
    # the packages with apt (their Depends resolved from the archive), and what the checks use:
    # a compiler and pkg-config for the host, EGL's headers and Mesa (the GL driver a board
    # brings), gst-inspect-1.0, systemd-analyze, /bin/kill and cage (the units' commands)
    timed "deb: apt-get install the packages" in_root "$install" env DEBIAN_FRONTEND=noninteractive sh -c "
        apt-get update -qq && apt-get install -y -qq --no-install-recommends /tmp/debs/*.deb \
            gcc libc6-dev pkg-config libegl-dev libegl-mesa0 libgl1-mesa-dri gstreamer1.0-tools systemd procps cage" \
        >"$DIR/deb-install.log" 2>&1 || {
        tail -n 15 "$DIR/deb-install.log" >&3
        return 1
    }
    timed "deb: checks" in_root "$install" sh /tmp/deb-checks.sh "$version" 2>&1 | tee "$DIR/deb-checks.log" |
        sed "s/^/fresh $DIST: /" >&3
    ! grep -q '^not ok' "$DIR/deb-checks.log" && grep -q '^ok - deb/purge' "$DIR/deb-checks.log"
}

# The cross built player under qemu-user in the build root, whose DEB_ARCH libraries are there as
# the build dependencies' (with DEB_ARCH's Mesa added): --version and one headless frame of an
# installed scene, from the unpacked sbfx-player package. DEB_QEMU=0 skips it, saying so.
deb_under_qemu() {
    if [ "${DEB_QEMU:-1}" = 0 ]; then
        say "deb: DEB_QEMU=0: the $DEB_ARCH player is not run under qemu-user (its files were checked as $DEB_ARCH code above)"
        return 0
    fi
    timed "deb: the $DEB_ARCH player under qemu-user" in_root "$DIR/deb-build" env DEBIAN_FRONTEND=noninteractive sh -c "
        set -e
        apt-get install -y -qq --no-install-recommends qemu-user-static libegl-mesa0:$DEB_ARCH libgl1-mesa-dri:$DEB_ARCH
        rm -rf /tmp/player /tmp/qemu-frame && dpkg-deb -x /root/sbfx/build/deb/$DEB_ARCH/sbfx-player_*_$DEB_ARCH.deb /tmp/player
        q=qemu-\$(dpkg-architecture -a$DEB_ARCH -qDEB_HOST_GNU_CPU)-static
        \$q /tmp/player/usr/bin/sbfx-play --version
        \$q /tmp/player/usr/bin/sbfx-play --headless --quiet --scene /tmp/player/usr/share/sbfx/scenes/explosion.cfg \
            --size 160x90 --frames 1 --out /tmp/qemu-frame
        test -s /tmp/qemu-frame/frame-0000.png" >"$DIR/deb-qemu.log" 2>&1 || {
        tail -n 12 "$DIR/deb-qemu.log" >&3
        return 1
    }
    say "deb: under qemu-user: $(grep -m1 '^sbfx-play ' "$DIR/deb-qemu.log"), one headless frame: $(stat -c %s "$DIR/deb-build/tmp/qemu-frame/frame-0000.png") bytes"
}

start=$SECONDS
# one run at a time in a DIST's folder: a second would unmount the first one's roots
mkdir -p "$DIR"
exec 9>"$DIR/.lock"
flock -n 9 || { say "another make test-fresh DIST=$DIST runs in $DIR"; exit 1; }
unmount_leftovers
if [ "$(cat "$DIR/base.stamp" 2>/dev/null)" != "$(base_stamp)" ] || ! [ -x "$BASE/usr/bin/git" ]; then
    timed "bare root" make_base
fi
say "bare root: $(. "$BASE/etc/os-release" && echo "$PRETTY_NAME"), $(du -sm "$BASE" | cut -f1) MB, commit $(git log -1 --format=%h "$COMMIT")"
# One root: the plain user first (the packages are not there yet), then root; the packages'
# scenario makes roots of its own.
rc=0
case " $SCENARIOS " in *" user "* | *" root "*) new_root ;; esac
for s in user root deb; do
    case " $SCENARIOS " in *" $s "*) ;; *) continue ;; esac
    timed "scenario $s" "scenario_$s" || { rc=1; say "scenario $s FAILED"; break; }
done
unmount_all
roots=$(for r in "$ROOT" "$DIR/deb-build" "$DIR/deb-install"; do if [ -d "$r" ]; then echo "$r"; fi; done)
if [ $rc -eq 0 ] && [ -z "${FRESH_KEEP:-}" ]; then
    for r in $roots; do rm -rf --one-file-system "$r"; done
else
    say "the roots are kept: $(echo $roots)"
fi
# and what the roots downloaded serves the machine's own apt next (CI installs the same packages)
if [ "$host_codename" = "$DIST" ]; then
    find "$CACHE" -maxdepth 1 -name '*.deb' -exec cp -l -n -t /var/cache/apt/archives {} + 2>/dev/null || true
fi
say "$([ $rc -eq 0 ] && echo passed || echo FAILED) after $((SECONDS - start)) s"
exit "$rc"
}
