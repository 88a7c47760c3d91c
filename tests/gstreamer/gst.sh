#!/usr/bin/env bash
# The GStreamer element from the command line, as users meet it (issue 34; docs/hosts/gstreamer.md):
#   inspect          gst-inspect-1.0 sbfx lists every property and the trigger signal, at the
#                    Makefile's VERSION
#   inspect-checks   gst-inspect-1.0's own checks: the plugin file loads without the registry's
#                    scanner process and without a warning or critical, is not blacklisted,
#                    names its element for auto-install, passes --exists --atleast-version
#   bad-scene        gst-launch-1.0 with a scene that has an error on line 3: it fails (255),
#                    the error names file:3, the pipeline is set back to NULL and freed
#   installed        make install (PREFIX=/usr/local, DESTDIR) puts libgstsbfx.so into
#                    GStreamer's plugin folder under the prefix, and the issue's pipeline,
#                    videotestsrc num-buffers=48 ! glupload ! sbfx scene=... ! gldownload !
#                    videoconvert ! pngenc ! multifilesink, run from the installed copy alone
#                    (GST_PLUGIN_PATH, LD_LIBRARY_PATH), writes 48 frames with the explosion over
#                    the test pattern that move; PREFIX=/usr
#                    puts it into the system folder; make uninstall removes it
#   record-mp4       examples/gstreamer/record-mp4.sh (the docs' file-to-MP4 pipeline) on a
#                    36-frame H.264 file: the recording decodes (ffmpeg) to 36 frames, the first
#                    as the input's, later ones with the explosion
# Usage: tests/gstreamer/gst.sh [BUILD] (default build). Prints ok / not ok / skip lines.
set -u
cd "$(dirname "$0")/../.." || exit 1
BUILD=${1:-build}
VERSION=$(sed -n 's/^VERSION := //p' Makefile)
SUITE=gstreamer
failures=0
ok() { echo "ok - $SUITE/$1"; }
fail() {
    echo "not ok - $SUITE/$1: $2"
    failures=$((failures + 1))
}
tail_of() { tail -n "${2:-3}" "$1" | tr '\n' ' ' | cut -c1-400; }

plugin=$BUILD/gstreamer/libgstsbfx.so
if [ ! -f "$plugin" ]; then
    fail build "$plugin was not built (make gstreamer; tools/deps.sh build installs GStreamer's -dev packages)"
    exit 1
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
in_tree() { tests/gstreamer/with_plugin.sh "$BUILD" "$@"; }

# ---- gst-inspect-1.0 --------------------------------------------------------------------------
properties="scene scale opacity upsample format tone-map exposure budget-ms seed timeline detail-from-input
background-distance stats"
test_inspect() {
    if ! in_tree gst-inspect-1.0 sbfx >"$tmp/inspect.txt" 2>"$tmp/inspect.err"; then
        fail inspect "gst-inspect-1.0 sbfx: $(tail_of "$tmp/inspect.err")"
        return
    fi
    local missing="" p
    for p in $properties; do grep -q "^  $p  *:" "$tmp/inspect.txt" || missing="$missing $p"; done
    # the action, its return and argument types: GStreamer 1.22 prints `"trigger" :  void
    # user_function (GstElement* object, gchararray arg0, gdouble arg1, ...)`, 1.26 `"trigger" ->
    # void  :  g_signal_emit_by_name (element, "trigger", const gchar * arg0, gdouble arg1, ...)`
    local action
    action=$(sed -n '/^Element Actions:/,$p' "$tmp/inspect.txt" | sed -n '/^  "trigger" /,/);/p')
    if ! echo "$action" | head -n 1 | grep -qE '^  "trigger" (:|-> void ) +(void user_function|:  g_signal_emit_by_name)' ||
        ! echo "$action" | grep -qE '(gchararray|gchar \*) arg0,' ||
        [ "$(echo "$action" | grep -cE 'gdouble arg[123][,)]')" -ne 3 ]; then
        missing="$missing trigger-action"
    fi
    grep -q "^  Version  *$VERSION\$" "$tmp/inspect.txt" || missing="$missing version-$VERSION"
    if [ -z "$missing" ]; then
        ok "inspect (13 properties, the trigger action, version $VERSION)"
    else
        fail inspect "missing from gst-inspect-1.0 sbfx:$missing"
    fi
}

test_inspect_checks() {
    local why=""
    G_DEBUG=fatal-warnings in_tree gst-inspect-1.0 --gst-disable-registry-fork "$plugin" >"$tmp/file.txt" \
        2>"$tmp/file.err" || why="$why; loading the file: exit $? $(tail_of "$tmp/file.err")"
    grep -qiE 'critical|warning' "$tmp/file.err" && why="$why; it warns: $(tail_of "$tmp/file.err")"
    in_tree gst-inspect-1.0 -b 2>&1 | grep -q sbfx && why="$why; it is blacklisted"
    in_tree gst-inspect-1.0 --print-plugin-auto-install-info "$plugin" 2>&1 | grep -qx 'element-sbfx' ||
        why="$why; --print-plugin-auto-install-info does not name element-sbfx"
    in_tree gst-inspect-1.0 --exists --atleast-version="$VERSION" sbfx || why="$why; --exists --atleast-version=$VERSION"
    if [ -z "$why" ]; then ok "inspect-checks"; else fail inspect-checks "${why#; }"; fi
}

# ---- a bad scene --------------------------------------------------------------------------------
test_bad_scene() {
    printf '# a typo on line 3\nrender = { target_scale = 4; };\nmedia = { smoke = { densty = 0.5; }; };\n' \
        >"$tmp/bad.cfg"
    in_tree timeout 60 gst-launch-1.0 videotestsrc num-buffers=10 ! glupload ! sbfx scene="$tmp/bad.cfg" \
        ! gldownload ! fakesink >"$tmp/bad.out" 2>&1
    local rc=$?
    if [ "$rc" -ne 0 ] && grep -q "bad.cfg:3: unknown key 'densty'" "$tmp/bad.out" &&
        grep -q 'Setting pipeline to NULL' "$tmp/bad.out" && grep -q 'Freeing pipeline' "$tmp/bad.out"; then
        ok "bad-scene ($(grep -m1 -o "bad.cfg:3: [^(]*" "$tmp/bad.out"))"
    else
        fail bad-scene "exit $rc: $(tail_of "$tmp/bad.out" 6)"
    fi
}

# ---- the installed copy ------------------------------------------------------------------------
# differing A B FUZZ: pixels of two pictures that differ beyond FUZZ (ImageMagick's compare)
differing() {
    local n
    n=$(compare -metric AE -fuzz "$3" "$1" "$2" null: 2>&1 | cut -d' ' -f1)
    [[ "$n" =~ ^[0-9]+$ ]] && echo "$n" || echo -1
}

# frames DIR PIPELINE-END...: the issue's source, 48 frames of the test pattern, into DIR/f-NN.png
frames() {
    local dir=$1
    shift
    mkdir -p "$dir"
    timeout 120 gst-launch-1.0 videotestsrc num-buffers=48 ! glupload "$@" ! gldownload ! videoconvert ! pngenc \
        ! multifilesink location="$dir/f-%02d.png" >"$dir.log" 2>&1
}

# check_frames NAME DIR: 48 frames, the explosion in frame 12 (against the pattern alone), and
# frames 12 and 24 differ
check_frames() {
    local count covered moved
    count=$(find "$2" -name 'f-*.png' | wc -l)
    covered=$(differing "$tmp/plain/f-12.png" "$2/f-12.png" 5%)
    moved=$(differing "$2/f-12.png" "$2/f-24.png" 5%)
    if [ "$count" -eq 48 ] && [ "$covered" -gt 2000 ] && [ "$moved" -gt 2000 ]; then
        ok "installed/$1 (48 frames; the explosion covers $covered pixels of frame 12, $moved change by frame 24)"
    else
        fail "installed/$1" "$count frames, $covered pixels differ from the pattern, $moved move: $(tail_of "$2.log")"
    fi
}

test_installed() {
    local root=$tmp/root dir
    if ! make --no-print-directory BUILD="$BUILD" PREFIX=/usr/local DESTDIR="$root" install >"$tmp/install.log" 2>&1; then
        fail installed "make install: $(tail_of "$tmp/install.log")"
        return
    fi
    # GStreamer's own folder with its prefix replaced by /usr/local
    dir=$(pkg-config --variable=pluginsdir gstreamer-1.0)
    dir=/usr/local${dir#"$(pkg-config --variable=prefix gstreamer-1.0)"}
    if [ ! -f "$root$dir/libgstsbfx.so" ]; then
        fail installed/plugin-folder "no libgstsbfx.so in $root$dir: $(find "$root" -name 'libgstsbfx*' | head -n 3)"
        return
    fi
    ok "installed/plugin-folder ($dir)"
    (
        export GST_PLUGIN_PATH=$root$dir LD_LIBRARY_PATH=$root/usr/local/lib GST_REGISTRY=$tmp/registry.bin
        export GST_GL_PLATFORM=egl GST_GL_WINDOW=egl-device
        gst-inspect-1.0 sbfx 2>&1 | grep -q "Filename  *$root$dir/libgstsbfx.so" ||
            echo "not ok - $SUITE/installed/found: gst-inspect-1.0 does not find the installed copy"
        frames "$tmp/plain"
        frames "$tmp/fx" ! sbfx scene="$root/usr/local/share/sbfx/scenes/explosion.cfg"
    )
    check_frames done-when "$tmp/fx"
    if make --no-print-directory BUILD="$BUILD" PREFIX=/usr DESTDIR="$tmp/usr-root" install-gstreamer >"$tmp/usr.log" 2>&1 &&
        [ -f "$tmp/usr-root$(pkg-config --variable=pluginsdir gstreamer-1.0)/libgstsbfx.so" ]; then
        ok "installed/system-folder (PREFIX=/usr: $(pkg-config --variable=pluginsdir gstreamer-1.0))"
    else
        fail installed/system-folder "PREFIX=/usr did not install into $(pkg-config --variable=pluginsdir gstreamer-1.0)"
    fi
    make --no-print-directory BUILD="$BUILD" PREFIX=/usr/local DESTDIR="$root" uninstall >/dev/null 2>&1
    if [ ! -e "$root$dir/libgstsbfx.so" ]; then ok installed/uninstall; else fail installed/uninstall "still there"; fi
}

# ---- file to MP4 (the docs' pipeline) -----------------------------------------------------------
test_record_mp4() {
    local d=$tmp/mp4
    mkdir -p "$d"
    in_tree gst-launch-1.0 -q videotestsrc num-buffers=36 pattern=smpte75 ! video/x-raw,width=320,height=180,framerate=24/1 \
        ! x264enc ! mp4mux ! filesink location="$d/in.mp4" >"$d/in.log" 2>&1
    if ! in_tree timeout 120 examples/gstreamer/record-mp4.sh "$d/in.mp4" "$d/out.mp4" scenes/explosion.cfg \
        >"$d/rec.log" 2>&1; then
        fail record-mp4 "examples/gstreamer/record-mp4.sh: $(tail_of "$d/rec.log")"
        return
    fi
    ffmpeg -v error -i "$d/in.mp4" "$d/i-%02d.png" && ffmpeg -v error -i "$d/out.mp4" "$d/o-%02d.png"
    local count first later
    count=$(find "$d" -name 'o-*.png' | wc -l)
    first=$(differing "$d/i-01.png" "$d/o-01.png" 10%)
    later=$(differing "$d/i-18.png" "$d/o-18.png" 10%)
    if [ "$count" -eq 36 ] && [ "$first" -eq 0 ] && [ "$later" -gt 2000 ]; then
        ok "record-mp4 (36 frames decoded; frame 18: $later pixels of the explosion over the input)"
    else
        fail record-mp4 "$count frames decoded, frame 1 differs in $first pixels, frame 18 in $later"
    fi
}

test_inspect
test_inspect_checks
test_bad_scene
test_installed
test_record_mp4
[ "$failures" -eq 0 ]
