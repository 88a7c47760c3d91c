#!/bin/sh
# Makes sure the Debian packages sbfx needs are installed.
# As root: installs what is missing (apt-get, non-interactive). Otherwise: prints the exact
# apt-get line and exits 1. Usage: tools/deps.sh [build|test|vm|cross-arm64|deb|deb-arm64|fresh|mesa-shim]
set -eu
set_of="${1:-test}"

# gcc only recommends libc6-dev, which --no-install-recommends leaves out: named here
host_tools="make gcc libc6-dev pkg-config"
build_pkgs="$host_tools libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri libpng-dev liblcms2-dev libconfig-dev libdrm-dev libgbm-dev libgpiod-dev colord-data libsystemd-dev libavformat-dev libavcodec-dev libswscale-dev libavutil-dev"
# MQTT triggers (platform/net/mqtt/mqtt_client.c, docs/triggers.md): libmosquitto, the player only
build_pkgs="$build_pkgs libmosquitto-dev"
# the Wayland display (display_wayland.c): libwayland-client, wayland-egl, and the protocols'
# XML turned into C by wayland-scanner (libwayland-bin) at build time
build_pkgs="$build_pkgs libwayland-dev wayland-protocols libwayland-bin"
# the GStreamer element, libgstsbfx.so (integrations/gstreamer/): GStreamer's core, base and GL
# libraries (gstreamer-1.0, -base, -video, -gl, -app for its tests)
build_pkgs="$build_pkgs libgstreamer1.0-dev libgstreamer-plugins-base1.0-dev"
# Debian 13 (trixie) names some packages differently: its clang is 19 (libgpiod-dev is 2.x
# there under the same name; the GPIO backend follows pkg-config's version)
clang_rt=libclang-rt-14-dev
if [ -r /etc/os-release ] && grep -qx 'VERSION_CODENAME=trixie' /etc/os-release; then
    clang_rt=libclang-rt-19-dev
fi
test_pkgs="$build_pkgs glslang-tools gnuplot-nox clang $clang_rt groff-base ffmpeg imagemagick libsdl2-dev libopengl-dev"
# make test also builds the hosts (docs/hosts/): the SDL2 example, libOpenGL for desktop OpenGL
# the Qt Quick item, its example and test under Xvfb (integrations/qt/, tests/hosts/qt_quick.sh);
# they are C++, and g++ is not in a minimal Debian root (Debian 13's debootstrap minbase)
test_pkgs="$test_pkgs g++ qt6-base-dev qt6-declarative-dev qml6-module-qtquick qml6-module-qtquick-window qml6-module-qtqml-workerscript qt6-qpa-plugins xvfb xauth"
# systemd-analyze (security --offline, verify) and systemd-sysusers check the kiosk's unit
# procps: /bin/kill, the unit's ExecReload (systemctl reload), which systemd-analyze verify looks for
test_pkgs="$test_pkgs systemd procps"
# tests/wayland.sh: sbfx-play under cage (wlroots, headless) read back by grim (wlr-screencopy),
# and under weston (headless) for presentation-time feedback. Debian 12's cage 0.1.4 does not
# start without Xwayland, which it only recommends (--no-install-recommends leaves it out);
# Debian 13's cage 0.2 starts without it.
test_pkgs="$test_pkgs cage grim weston"
if ! [ -r /etc/os-release ] || ! grep -qx 'VERSION_CODENAME=trixie' /etc/os-release; then
    test_pkgs="$test_pkgs xwayland"
fi
# tests/mqtt.sh: a mosquitto broker of its own and mosquitto_pub / mosquitto_sub as the clients
test_pkgs="$test_pkgs mosquitto mosquitto-clients"
# tests/cigi.sh: Wireshark's CIGI dissector reads what the test host sends and the receiver's
# Start of Frame (tshark; text2pcap from wireshark-common, which tshark depends on)
test_pkgs="$test_pkgs tshark"
# the GStreamer element's tests (tests/gstreamer/): gst-launch-1.0 and gst-inspect-1.0, GstGL's
# elements, videotestsrc and appsink (base), mp4mux and qtdemux (good), x264enc (ugly), kmssink
# and waylandsink (bad), avdec_h264 for decodebin (libav: the MP4 recording's input)
gst_runtime_pkgs="gstreamer1.0-tools gstreamer1.0-gl gstreamer1.0-plugins-base gstreamer1.0-plugins-good gstreamer1.0-plugins-bad"
test_pkgs="$test_pkgs $gst_runtime_pkgs gstreamer1.0-plugins-ugly gstreamer1.0-libav"
# make test-vm: qemu (TCG), the guest's modprobe through the shared root, and what tests/vm/run.sh
# needs to fetch and unpack Debian's kernel packages and build vkms and gpio-sim out of tree
vm_pkgs="$build_pkgs qemu-system-x86 kmod xz-utils patch gcc-12 make libelf1"
# the GStreamer camera kiosk in the VM: v4l2src (good) from vivid through sbfx to kmssink (bad)
vm_pkgs="$vm_pkgs $gst_runtime_pkgs"
# make BOARD=<an arm64 board> and make cross-check: Debian's aarch64 toolchain and the arm64
# multiarch -dev packages, with the host's make, pkg-config and compiler (build/tools/ runs here)
cross_arm64_pkgs="$host_tools liblcms2-dev colord-data gcc-aarch64-linux-gnu libc6-dev:arm64 libegl-dev:arm64 libgles-dev:arm64 libdrm-dev:arm64 libgbm-dev:arm64 libgpiod-dev:arm64 libpng-dev:arm64 libconfig-dev:arm64 libsystemd-dev:arm64 libavformat-dev:arm64 libavcodec-dev:arm64 libswscale-dev:arm64 libavutil-dev:arm64 libwayland-dev:arm64 wayland-protocols libwayland-bin libmosquitto-dev:arm64"

# make web and test-web (docs/web.md): Debian's emscripten (its LLVM, binaryen and node modules),
# dpkg-dev (dpkg-source unpacks libconfig's source package: tools/web-libconfig.sh), Chromium for
# the browser tests (driven over its DevTools pipe by node, which emscripten brings), ImageMagick
# (the browser's frames beside sbfx-play's PNGs: tests/web/same_picture.js)
web_pkgs="$build_pkgs emscripten dpkg-dev chromium imagemagick"
# make test runs one case of the browser tests (tests/web/run.sh --quick)
test_pkgs="$test_pkgs emscripten dpkg-dev chromium"
# make deb (tools/deb.sh, dist/debian/control): dpkg-buildpackage's tools and lintian, and the
# build dependencies debian/control names (the build set and systemd's .pc: systemd-dev on 13,
# systemd on 12); make deb ARCH=arm64 the same for arm64 with the cross toolchain
deb_tools="dpkg-dev debhelper fakeroot lintian"
systemd_pc=systemd
if [ -r /etc/os-release ] && grep -qx 'VERSION_CODENAME=trixie' /etc/os-release; then systemd_pc=systemd-dev; fi
deb_pkgs="$deb_tools $build_pkgs $systemd_pc"
# (not libgstreamer-plugins-base1.0-dev:arm64: on Debian 12 it is not Multi-Arch: same and would
# replace the machine's amd64 one, which make needs; tools/deb.sh says how to build the element)
deb_arm64_pkgs="$deb_tools $cross_arm64_pkgs $systemd_pc libgstreamer1.0-dev:arm64"
# make test's ABI check (tests/abi.sh): libabigail's abidw and abidiff
test_pkgs="$test_pkgs abigail-tools"

# make test-fresh (and test-debian13): bare Debian roots made with debootstrap, checked against
# the archive's key
fresh_pkgs="debootstrap debian-archive-keyring"
# tools/mesa-shim.sh (make bench's Mali columns, make test-gpus): what Mesa 25's meson build of
# the panfrost, v3d, freedreno and etnaviv drivers and their drm-shims needs from Debian 12
mesa_shim_pkgs="$build_pkgs flex bison python3-mako python3-yaml python3-ply python3-pycparser libexpat1-dev libdrm-dev ninja-build xz-utils dpkg-dev patch"

case "$set_of" in
    build) want="$build_pkgs" ;;
    fresh | debian13) want="$fresh_pkgs" ;;
    test) want="$test_pkgs" ;;
    vm) want="$vm_pkgs" ;;
    cross-arm64) want="$cross_arm64_pkgs" ;;
    deb) want="$deb_pkgs" ;;
    deb-arm64) want="$deb_arm64_pkgs" ;;
    mesa-shim) want="$mesa_shim_pkgs" ;;
    web) want="$web_pkgs" ;;
    *) echo "deps.sh: unknown package set '$set_of' (build|test|vm|cross-arm64|deb|deb-arm64|fresh|mesa-shim|web)" >&2; exit 2 ;;
esac

# arm64 packages need the architecture enabled first (dpkg --add-architecture arm64)
add_arch=""
if { [ "$set_of" = cross-arm64 ] || [ "$set_of" = deb-arm64 ]; } && ! dpkg --print-foreign-architectures | grep -qx arm64; then
    add_arch="dpkg --add-architecture arm64 && "
fi

# What is installed, read once (a dpkg-query per package made every build wait some 1.5 s, and
# make test runs this six times): "name:arch" for each installed package; a package of
# architecture "all" counts as the native one's. A name without ":arch" means the native
# architecture. Without dpkg, everything is missing (and apt-get would say so).
native=$(dpkg --print-architecture 2>/dev/null || echo none)
missing=$(dpkg-query -W -f='${Package} ${Architecture} ${Status}\n' 2>/dev/null |
    awk -v native="$native" -v want="$want" '
        $3 == "install" && $4 == "ok" && $5 == "installed" {
            ok[$1 ":" $2] = 1
            if ($2 == "all") ok[$1 ":" native] = 1
        }
        END {
            n = split(want, w, " ")
            for (i = 1; i <= n; i++) {
                key = index(w[i], ":") ? w[i] : w[i] ":" native
                if (!(key in ok)) printf " %s", w[i]
            }
        }')
[ -z "$missing" ] && [ -z "$add_arch" ] && exit 0

line="apt-get install -y --no-install-recommends$missing"
if [ "$(id -u)" -ne 0 ]; then
    echo "sbfx needs Debian packages that are not installed. As root, run:" >&2
    echo "  ${add_arch}apt-get update && $line" >&2
    exit 1
fi
echo "deps.sh: installing:$missing" >&2
export DEBIAN_FRONTEND=noninteractive
[ -n "$add_arch" ] && dpkg --add-architecture arm64
# another apt-get (unattended-upgrades, a second make) may hold dpkg's lock: wait for it rather than fail
apt_wait="-o DPkg::Lock::Timeout=900"
# shellcheck disable=SC2086
apt-get $apt_wait update -qq
# shellcheck disable=SC2086
apt-get $apt_wait install -y -qq --no-install-recommends $missing >&2
