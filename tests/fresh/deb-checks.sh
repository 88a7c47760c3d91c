#!/bin/sh
# Run by tests/fresh/run.sh's scenario "deb" (make test-deb) as root inside a bare Debian root
# where apt has just installed sbfx's four packages from /tmp/debs (docs/packaging.md):
#   sbfx-play --version; a headless render of an installed scene; the host example
#   (/tmp/host.c, examples/bare-egl/host.c) built with `pkg-config --cflags --libs sbfx` against
#   libsbfx-dev and run; `gst-inspect-1.0 sbfx`; `systemd-analyze verify` of the installed units,
#   which are not enabled, and the kiosk's user made by sysusers.d; then `apt-get purge` of the
#   four and no file of theirs left (their file lists, dpkg's database, any *sbfx* path).
# Usage: deb-checks.sh VERSION. Prints ok/not ok lines; exits 1 when one fails.
set -u
VERSION=$1
PACKAGES="libsbfx1 libsbfx-dev sbfx-player gstreamer1.0-sbfx"
failed=0
ok() { echo "ok - deb/$1"; }
not_ok() { echo "not ok - deb/$1: $2"; failed=1; }
tail_of() { tail -n "${2:-4}" "$1" | tr '\n' ' '; }
triplet=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || gcc -print-multiarch)
w=/tmp/deb-checks
rm -rf "$w" && mkdir -p "$w"

# what dpkg says is installed, and each package's files (for after the purge)
for p in $PACKAGES; do
    if dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
        dpkg -L "$p" | while read -r f; do [ -d "$f" ] || echo "$f"; done >>"$w/files"
    else
        not_ok "installed/$p" "dpkg does not list it as installed"
    fi
done
[ "$failed" -eq 0 ] && ok "installed ($PACKAGES: $(wc -l <"$w/files") files)"

if sbfx-play --version >"$w/version" 2>&1 && grep -q "$VERSION" "$w/version"; then
    ok "version ($(head -n 1 "$w/version"))"
else
    not_ok version "sbfx-play --version: $(tail_of "$w/version")"
fi

scene=/usr/share/sbfx/scenes/explosion.cfg
if sbfx-play --headless --quiet --scene "$scene" --size 320x180 --frames 3 --out "$w/render" >"$w/render.log" 2>&1 &&
    [ "$(stat -c %s "$w/render/frame-0002.png" 2>/dev/null || echo 0)" -gt 1000 ]; then
    ok "render ($scene, 3 frames 320x180: frame-0002.png $(stat -c %s "$w/render/frame-0002.png") bytes)"
else
    not_ok render "sbfx-play --headless --scene $scene: $(tail_of "$w/render.log")"
fi

# shellcheck disable=SC2046 # pkg-config's words are meant to split
if cc -Wall -Werror -o "$w/host" /tmp/host.c $(pkg-config --cflags --libs sbfx egl glesv2) >"$w/host.log" 2>&1; then
    # (the same file by its real path: with a merged /usr, ld.so may name it under /lib)
    loaded=$(ldd "$w/host" | awk '/libsbfx/ {print $3}')
    if [ -z "$loaded" ] || [ "$(readlink -f "$loaded")" != "$(readlink -f "/usr/lib/$triplet/libsbfx.so.1")" ]; then
        not_ok host "it loads '$loaded', not /usr/lib/$triplet/libsbfx.so.1"
    elif "$w/host" >"$w/host.run" 2>&1; then
        ok "host (examples/bare-egl/host.c, pkg-config --cflags --libs sbfx: $(pkg-config --cflags --libs sbfx | tr -s ' '); $(tail_of "$w/host.run" 1))"
    else
        not_ok host "the host built with pkg-config's flags failed: $(tail_of "$w/host.run")"
    fi
else
    not_ok host "cc host.c \$(pkg-config --cflags --libs sbfx egl glesv2): $(tail_of "$w/host.log")"
fi

plugin=/usr/lib/$triplet/gstreamer-1.0/libgstsbfx.so
if gst-inspect-1.0 sbfx >"$w/gst.log" 2>&1 &&
    [ "$(readlink -f "$(awk '$1 == "Filename" {print $2}' "$w/gst.log")")" = "$(readlink -f "$plugin")" ]; then
    ok "gst-inspect (the element sbfx from $plugin, version $(awk '$1 == "Version" {print $2}' "$w/gst.log"))"
else
    not_ok gst-inspect "gst-inspect-1.0 sbfx: $(tail_of "$w/gst.log")"
fi

# the units: verified, none enabled; the system user made
units=$(grep '\.service$' "$w/files")
verify_failed=""
for u in $units; do
    case $u in
        */systemd/user/*) XDG_RUNTIME_DIR=$(mktemp -d) systemd-analyze --user verify --man=no "$u" >"$w/verify.log" 2>&1 ;;
        *) systemd-analyze verify --man=no "$u" >"$w/verify.log" 2>&1 ;;
    esac
    rc=$?
    if [ $rc -ne 0 ] || [ -s "$w/verify.log" ]; then verify_failed="$verify_failed $u: $(tail_of "$w/verify.log")"; fi
done
if [ -z "$units" ]; then
    not_ok verify "sbfx-player installed no unit"
elif [ -z "$verify_failed" ]; then
    ok "verify ($(echo "$units" | wc -l) units: systemd-analyze verify)"
else
    not_ok verify "$verify_failed"
fi
enabled=""
for u in $units; do
    case $u in */systemd/user/*) state=$(systemctl --global is-enabled "${u##*/}" 2>/dev/null) ;;
        *) state=$(systemctl is-enabled "${u##*/}" 2>/dev/null) ;; esac
    [ "$state" = disabled ] || enabled="$enabled ${u##*/}:$state"
done
if [ -z "$enabled" ]; then ok "units-not-enabled"; else not_ok units-not-enabled "$enabled"; fi
if getent passwd sbfx >/dev/null && getent group gpio >/dev/null; then
    ok "sysusers (user sbfx in $(id -Gn sbfx | tr ' ' ','), group gpio)"
else
    not_ok sysusers "no user sbfx or no group gpio after the install"
fi

# purge: nothing of theirs left
if apt-get purge -y -qq $PACKAGES >"$w/purge.log" 2>&1; then
    left=$(while read -r f; do [ -e "$f" ] || [ -L "$f" ] && echo "$f"; done <"$w/files")
    known=$(dpkg -l | awk '$2 ~ /sbfx/ {print $1, $2}')
    stray=$(find / -xdev \( -path /tmp -o -path /.fresh-host \) -prune -o -name '*sbfx*' -print 2>/dev/null)
    if [ -z "$left$known$stray" ]; then
        ok "purge (apt-get purge $PACKAGES: none of their $(wc -l <"$w/files") files, no dpkg entry, no *sbfx* path left)"
    else
        not_ok purge "left: ${left:+files: $left; }${known:+dpkg: $known; }${stray:+paths: $stray}"
    fi
else
    not_ok purge "apt-get purge: $(tail_of "$w/purge.log")"
fi
exit "$failed"
