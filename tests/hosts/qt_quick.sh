#!/bin/sh
# The Qt Quick integration (integrations/qt/, docs/hosts/qt-quick.md) under Xvfb with Qt's xcb
# platform: its test (tests/hosts/test_qt_quick.cpp: item filling the window and smaller than
# it), then the example program as a user runs it, 60 frames with the timer every 20 ms (Qt's
# default render loop), which must start explosions and exit 0. Each run is bounded (timeout), so
# a hung X server cannot hang make test. Skipped, with the reason, where Qt 6's -dev packages
# or xvfb-run are missing. Usage: tests/hosts/qt_quick.sh BUILD
build=${1:-build}
test_bin="$build/tests/qt/test_qt_quick"
example="$build/examples/sbfx-qt-quick"
pkg=${PKG_CONFIG:-pkg-config}
if ! $pkg --exists Qt6Quick Qt6Qml Qt6Gui; then
    echo "skip - qt-quick: Qt 6 Quick's -dev packages are not installed (tools/deps.sh test installs them)"
    exit 0
fi
if ! command -v xvfb-run >/dev/null 2>&1; then
    echo "skip - qt-quick: xvfb-run is not installed (xvfb, xauth: tools/deps.sh test)"
    exit 0
fi
runtime=$(mktemp -d)
trap 'rm -rf "$runtime"' EXIT
export QT_QPA_PLATFORM=xcb XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$runtime}"

if [ -x "$test_bin" ]; then
    out=$(timeout -k 5 120 xvfb-run -a -s "-screen 0 1024x768x24 -nolisten tcp" "$test_bin" 2>&1)
    rc=$?
    printf '%s\n' "$out"
    if [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then
        echo "not ok - qt-quick/test_qt_quick: timed out after 120 s"
    elif [ "$rc" -ne 0 ] && ! printf '%s\n' "$out" | grep -q '^not ok - '; then
        echo "not ok - qt-quick/test_qt_quick: exit status $rc without a failed test (Xvfb did not start?)"
    fi
else
    echo "not ok - qt-quick/test_qt_quick: $test_bin was not built (make test-qt-quick)"
fi

if [ ! -x "$example" ]; then
    echo "not ok - qt-quick/example-runs: $example was not built (make test-qt-quick)"
    exit 0
fi
if out=$(timeout -k 5 120 xvfb-run -a -s "-screen 0 1024x768x24 -nolisten tcp" "$example" --frames 60 --every 20 2>&1); then
    last=$(printf '%s\n' "$out" | tail -n 1)
    case "$last" in
        *"sbfx-qt-quick: 0 explosions"*) echo "not ok - qt-quick/example-runs: the timer started no explosion ($last)" ;;
        *"explosions"*) echo "ok - qt-quick/example-runs ($last)" ;;
        *) echo "not ok - qt-quick/example-runs: $(printf '%s' "$out" | tail -n 3 | tr '\n' ' ')" ;;
    esac
else
    echo "not ok - qt-quick/example-runs: exit status $?: $(printf '%s' "$out" | tail -n 3 | tr '\n' ' ')"
fi
