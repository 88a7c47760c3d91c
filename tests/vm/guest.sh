#!/bin/bash
# Runs inside the test VM (tests/vm/run.sh boots it; tests/vm/init starts this as root with the
# host's / as the root filesystem): loads vkms, vivid and gpio-sim and runs sbfx-play against
# them. Prints "ok - vm/NAME", "not ok - vm/NAME: why", "skip - vm/NAME: why" and "# ..." notes,
# and writes the result lines to /vmout/results.txt for the host.
#
# Each test group runs under its own time limit (run_test): a group that hangs fails with the
# step it was at (step) and the tail of the newest player log, its processes are killed, and the
# next group runs (harness-limit checks that with a group that hangs on purpose). Everything that tells what happened is written as it happens into the host's
# writable share (/vmout = build/vm/out on the host), so it is there even when the whole VM has
# to be killed: the player logs (logs/NAME.out, .err, .json), the kernel log (logs/dmesg.txt,
# followed), the steps with their uptime (steps.txt) and the kernel's code symbols (kallsyms.txt,
# for run.sh's backtrace of a wedged VM).
set -u
SRC=${SBFX_SRC:?}
B=${SBFX_BUILD:?}
cd "$SRC" || exit 1
OUT=/vmout
RESULTS=$OUT/results.txt
L=$OUT/logs
T=/tmp/vm
PLAYER=$B/sbfx-play
# the same player built against libgpiod 2.x (Debian 13's, tools/libgpiod2.sh): the GPIO groups
# run with each (with_gpiod2; their results and logs end in -gpiod2)
PLAYER_GPIOD2=$B/gpiod2/sbfx-play
SFX=""
PNGDIFF=$B/tests/vm/pngdiff
DRM_STATE=$B/tests/vm/drm_state
V4L2_CTRL=$B/tests/vm/v4l2_ctrl
VBLANK_STRESS=$B/tests/vm/vblank_stress
CARD=/dev/dri/card0
MODE=640x480
GPIO_LABEL=sbfx-vm # the gpio-sim bank's label: how a chip that comes back is found again
: >"$RESULTS"
mkdir -p "$T" "$L"
: >"$OUT/steps.txt"
# llvmpipe's shader cache (tmpfs, this boot only): only the first player run pays for compiling
# the shaders under TCG (~7 s)
export HOME=/tmp MESA_SHADER_CACHE_DIR=/tmp/mesa-cache
# an ASan+UBSan build (BUILD=build/asan) also runs here: Mesa keeps allocations until exit that
# LeakSanitizer would report as ours
export ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

result() { printf '%s\n' "$1" | tee -a "$RESULTS"; }
ok() { result "ok - vm/$1"; }
fail() { result "not ok - vm/$1: $2"; }
skip() { result "skip - vm/$1: $2"; }
note() { printf '# %s\n' "$*"; }

# ---- one test at a time, each under its own limit --------------------------------------------

uptime_s() { local u; read -r u _ </proc/uptime; printf '%s' "$u"; }

# step TEXT: what the running test is doing now (named in its failure if it hangs).
step() {
    printf '%s\n' "$*" >"$T/step"
    printf '%s %s: %s\n' "$(uptime_s)" "$CURRENT_TEST" "$*" >>"$OUT/steps.txt"
}

# pause SECONDS: sleeps without starting a process (a FIFO nobody writes; under TCG every sleep
# process costs tens of ms).
mkfifo "$T/idle" && exec 6<>"$T/idle"
pause() { read -r -t "$1" -u 6; }

# newest_log: the player log written last (the one a hung test was running).
newest_log() { ls -t "$L"/*.err 2>/dev/null | head -n 1; }

# kill_tree SIGNAL PID: PID and every process under it, the children first (a subshell, its
# players, their helpers), found through their parent ids.
kill_tree() {
    local child
    for child in $(ps -o pid= --ppid "$2" 2>/dev/null); do kill_tree "$1" "$child"; done
    kill "-$1" "$2" 2>/dev/null
}

# run_test NAME SECONDS FUNCTION [ARGS...]: FUNCTION in a child shell; past SECONDS it and what it
# started are killed and NAME fails with its step and the tail of the newest player log; blocked
# tasks' kernel backtraces go to the kernel log first (sysrq w: a player stuck in a driver shows
# where).
CURRENT_TEST=setup
run_test() {
    local name=$1 limit=$2 t0=$SECONDS
    shift 2
    CURRENT_TEST=$name
    printf '%s\n' "$name" >"$OUT/current-test.txt"
    step "start (limit $limit s)"
    "$@" &
    local pid=$! i
    for ((i = 0; i < limit * 5; i++)); do
        kill -0 "$pid" 2>/dev/null || break
        pause 0.2
    done
    if kill -0 "$pid" 2>/dev/null; then
        local at log
        at=$(cat "$T/step" 2>/dev/null)
        log=$(newest_log)
        echo w >/proc/sysrq-trigger 2>/dev/null
        kill_tree TERM "$pid"
        for ((i = 0; i < 25; i++)); do kill -0 "$pid" 2>/dev/null || break; pause 0.2; done
        kill_tree KILL "$pid"
        fail "$name" "timed out after $limit s at step '$at'; ${log:-no player log}: $(tail -n 3 "$log" 2>/dev/null | grep -v -e vkms -e kmsro | tr '\n' ' ' | cut -c 1-300)"
        ps -eo pid,stat,wchan:32,args 2>/dev/null | grep -e sbfx -e vblank_stress | grep -v grep | sed 's/^/# still there: /'
    fi
    wait "$pid" 2>/dev/null
    step "end after $((SECONDS - t0)) s"
    CURRENT_TEST=none
}

# The kernel's side, kept as it happens: dmesg followed into the share; hung tasks reported after
# 20 s (Debian: 120); the kernel's code symbols, modules included (run.sh names a wedged VM's CPUs
# with them: Debian's System.map is a stub).
watch_kernel() {
    sysctl -q -w kernel.hung_task_timeout_secs=20 kernel.sysrq=1 kernel.kptr_restrict=0 2>/dev/null
    dmesg --follow >"$L/dmesg.txt" 2>&1 &
    DMESG_PID=$!
}

kernel_symbols() {
    grep -i ' t ' /proc/kallsyms >"$OUT/kallsyms.txt" 2>/dev/null
}

# json_number FILE KEY: the value of "KEY": N in a --stats file.
json_number() { sed -n "s/.*\"$2\"[[:space:]]*:[[:space:]]*\([0-9][0-9]*\).*/\1/p" "$1" 2>/dev/null; }

# wait_for FILE TEXT SECONDS: until TEXT shows up in FILE.
wait_for() {
    local i
    for ((i = 0; i < $3 * 10; i++)); do
        grep -qF -- "$2" "$1" 2>/dev/null && return 0
        sleep 0.1
    done
    return 1
}

# kiosk NAME ARGS...: starts sbfx-play --display drm in the background (pid in $kiosk_pid,
# output in $T/NAME.out and $T/NAME.err) and waits for its banner.
kiosk() {
    local name=$1
    shift
    "$PLAYER" --display drm --device "$CARD" --mode "$MODE" "$@" >"$L/$name.out" 2>"$L/$name.err" &
    kiosk_pid=$!
    wait_for "$L/$name.out" "until stopped" 90
}

# stop_kiosk: SIGTERM, and the exit status in $kiosk_rc (137 and a note if it had to be
# killed after 20 s).
stop_kiosk() {
    kill -TERM "$kiosk_pid" 2>/dev/null
    local i
    for ((i = 0; i < 200; i++)); do
        kill -0 "$kiosk_pid" 2>/dev/null || break
        sleep 0.1
    done
    if kill -0 "$kiosk_pid" 2>/dev/null; then
        note "sbfx-play ignored SIGTERM for 20 s: killed"
        kill -KILL "$kiosk_pid"
    fi
    wait "$kiosk_pid"
    kiosk_rc=$?
}

# play ARGS...: sbfx-play in the foreground, killed if it runs past 120 s.
play() { timeout -k 5 120 "$PLAYER" "$@"; }

first_line() { head -n 1 "$1" 2>/dev/null | cut -c 1-200; }

# ---- setup -----------------------------------------------------------------------------------

setup_modules() {
    local t0=$SECONDS why=""
    modprobe vkms 2>>"$L/modprobe.err" || why="$why vkms"
    modprobe vivid node_types=0x1 2>>"$L/modprobe.err" || why="$why vivid"
    modprobe gpio-sim 2>>"$L/modprobe.err" || why="$why gpio-sim"
    mountpoint -q /sys/kernel/config || mount -t configfs configfs /sys/kernel/config
    udevadm settle 2>/dev/null
    for ((i = 0; i < 50; i++)); do [ -e "$CARD" ] && [ -e /dev/video0 ] && break; sleep 0.1; done
    if [ -n "$why" ]; then
        fail modules "modprobe failed:$why: $(head -c 300 "$L/modprobe.err")"
    elif [ ! -e "$CARD" ] || [ ! -e /dev/video0 ]; then
        fail modules "no $CARD or /dev/video0 after loading vkms and vivid"
    else
        ok modules
    fi
    note "modules loaded in $((SECONDS - t0)) s"
}

# A gpio-sim chip with 8 lines; sets GPIO_CHIP (gpiochipN) and GPIO_PULL (line 0's pull file).
setup_gpio_sim() {
    local cfg=/sys/kernel/config/gpio-sim/sbfx
    mkdir -p "$cfg/bank0" && echo 8 >"$cfg/bank0/num_lines" && echo "$GPIO_LABEL" >"$cfg/bank0/label" &&
        echo 1 >"$cfg/live" || {
        fail gpio-sim "configuring gpio-sim through configfs failed"
        return 1
    }
    GPIO_CHIP=$(cat "$cfg/bank0/chip_name")
    GPIO_DEV=$(cat "$cfg/dev_name")
    GPIO_SYS=/sys/devices/platform/$GPIO_DEV/$GPIO_CHIP
    GPIO_PULL=$GPIO_SYS/sim_gpio0/pull
    [ -w "$GPIO_PULL" ] || {
        fail gpio-sim "no $GPIO_PULL"
        return 1
    }
    note "gpio-sim: $GPIO_CHIP ($GPIO_DEV)"
    # run_test runs this in a child: the names go back to the tier through a file
    declare -p GPIO_CHIP GPIO_DEV GPIO_SYS GPIO_PULL >"$T/gpio.env"
}

# ---- DRM/KMS on vkms -------------------------------------------------------------------------

# The explosion on vkms with page flips; the last frame read back through the writeback
# connector; the CRTC restored afterwards (a second open fd keeps the kernel's fbdev restore out
# of the way, so what is checked is the player's own restore).
test_drm_atomic() {
    local t0=$SECONDS
    "$DRM_STATE" "$CARD" >"$T/crtc-before.txt" 2>&1
    mkfifo "$T/hold"
    "$DRM_STATE" "$CARD" --hold <"$T/hold" >"$T/crtc-after.txt" 2>&1 &
    local holder=$!
    exec 8>"$T/hold"
    play --display drm --device "$CARD" --mode "$MODE" --fps 12 --frames 8 \
        --screenshot "$T/shot.png" --stats "$L/atomic.json" >"$L/atomic.out" 2>"$L/atomic.err"
    local rc=$?
    exec 8>&-
    wait "$holder"
    local flips
    flips=$(json_number "$L/atomic.json" flips)
    if [ "$rc" -ne 0 ]; then
        fail drm-atomic-flips "sbfx-play --display drm exited with $rc: $(grep -v -e vkms -e kmsro "$L/atomic.err" | head -n 2 | tr '\n' ' ')"
    elif [ "${flips:-0}" -ne 7 ]; then
        fail drm-atomic-flips "8 frames (1 modeset + 7 flips) gave flips=$flips"
    else
        ok drm-atomic-flips
    fi
    note "$(grep -m1 'frames in' "$L/atomic.out")"
    if cmp -s "$T/crtc-before.txt" "$T/crtc-after.txt"; then
        ok drm-restore-crtc
    else
        fail drm-restore-crtc "before: $(tr '\n' ' ' <"$T/crtc-before.txt") after: $(tr '\n' ' ' <"$T/crtc-after.txt")"
    fi
    note "drm atomic run: $((SECONDS - t0)) s"
}

# The scanned-out frame equals the headless render of the same frame (same Mesa, same CPU).
test_screenshot_matches_headless() {
    local t0=$SECONDS
    if [ ! -s "$T/shot.png" ]; then
        fail drm-writeback-matches-headless "no writeback screenshot: $(grep -m1 -i writeback "$L/atomic.err")"
        return
    fi
    play --headless --size "$MODE" --fps 12 --frames 8 --out "$T/headless" --quiet \
        >"$L/headless.out" 2>"$L/headless.err" || {
        fail drm-writeback-matches-headless "the headless run failed: $(first_line "$L/headless.err")"
        return
    }
    local diff max
    diff=$("$PNGDIFF" "$T/shot.png" "$T/headless/frame-0007.png" 2>&1)
    max=$(printf '%s' "$diff" | sed -n 's/^max \([0-9]*\).*/\1/p')
    cp "$T/shot.png" "$OUT/drm-writeback-frame7.png"
    cp "$T/headless/frame-0007.png" "$OUT/headless-frame7.png"
    if [ -n "$max" ] && [ "$max" -le 2 ]; then
        ok drm-writeback-matches-headless
    else
        fail drm-writeback-matches-headless "$diff"
    fi
    note "writeback vs headless frame 7: $diff ($((SECONDS - t0)) s)"
}

# A GPU reset injected before frame 3 on the DRM display (SBFX_PLAY_INJECT_GPU_RESET: no GPU
# here can be made to hang): the player makes a new context on the same GBM surface, its GL
# objects and sbfx, the page flips go on, and the frame scanned out at the end (writeback) equals
# the headless run with the same injected reset.
test_drm_gpu_reset() {
    step "sbfx-play --display drm, reset injected before frame 3"
    SBFX_PLAY_INJECT_GPU_RESET=3 play --display drm --device "$CARD" --mode "$MODE" --fps 12 --frames 8 \
        --screenshot "$T/reset-shot.png" --stats "$L/drmreset.json" >"$L/drmreset.out" 2>"$L/drmreset.err"
    local rc=$? flips resets
    flips=$(json_number "$L/drmreset.json" flips)
    resets=$(json_number "$L/drmreset.json" gpu_resets)
    step "the same headless"
    SBFX_PLAY_INJECT_GPU_RESET=3 play --headless --size "$MODE" --fps 12 --frames 8 --out "$T/reset-headless" \
        --quiet >"$L/headlessreset.out" 2>"$L/headlessreset.err"
    local diff max
    diff=$("$PNGDIFF" "$T/reset-shot.png" "$T/reset-headless/frame-0007.png" 2>&1)
    max=$(printf '%s' "$diff" | sed -n 's/^max \([0-9]*\).*/\1/p')
    note "drm gpu reset: $(grep -h -e 'GPU reset' -e recovered "$L/drmreset.err" | tr '\n' ' ')"
    if [ "$rc" -ne 0 ]; then
        fail drm-gpu-reset "exit $rc: $(grep -v -e vkms -e kmsro "$L/drmreset.err" | tail -n 1)"
    elif [ "${resets:-0}" -ne 1 ] || [ "${flips:-0}" -ne 7 ] || ! grep -q "recovered at" "$L/drmreset.err"; then
        fail drm-gpu-reset "gpu_resets=$resets flips=$flips (8 frames: 1 modeset + 7 flips)"
    elif [ -z "$max" ] || [ "$max" -gt 2 ]; then
        fail drm-gpu-reset "the frame scanned out after the reset differs from the headless run's: $diff"
    else
        ok drm-gpu-reset
    fi
}

test_drm_legacy() {
    local t0=$SECONDS
    play --display drm --device "$CARD" --mode "$MODE" --modeset legacy --fps 12 --frames 6 \
        --scale 8 --stats "$L/legacy.json" --quiet >"$L/legacy.out" 2>"$L/legacy.err"
    local rc=$? flips
    flips=$(json_number "$L/legacy.json" flips)
    if [ "$rc" -ne 0 ]; then
        fail drm-legacy-flips "--modeset legacy exited with $rc: $(grep -v -e vkms -e kmsro "$L/legacy.err" | head -n 1)"
    elif [ "${flips:-0}" -ne 5 ]; then
        fail drm-legacy-flips "6 frames gave flips=$flips"
    else
        ok drm-legacy-flips
    fi
    note "drm legacy run: $((SECONDS - t0)) s"
}

# A kiosk runs until SIGTERM; a second player on the same card is refused naming it; the
# flips of the kiosk are paced by vblank (no more than the refresh rate).
test_kiosk_and_busy() {
    local t0=$SECONDS
    if ! kiosk kiosk --scale 8 --stats "$L/kiosk.json"; then
        fail drm-kiosk "no banner within 90 s: $(first_line "$L/kiosk.err")"
        stop_kiosk
        return
    fi
    play --display drm --device "$CARD" --frames 1 >"$L/busy.out" 2>"$L/busy.err"
    local rc=$?
    if [ "$rc" -eq 1 ] && grep -qF "$CARD" "$L/busy.err" && grep -qF "in use" "$L/busy.err"; then
        ok drm-busy-master
    else
        fail drm-busy-master "second player exited $rc: $(grep -v -e vkms -e kmsro "$L/busy.err" | head -n 1)"
    fi
    wait_stats kiosk 2 40 # two frames at least (under TCG the first takes 5 to 12 s)
    stop_kiosk
    local frames flips missed
    frames=$(json_number "$L/kiosk.json" frames)
    flips=$(json_number "$L/kiosk.json" flips)
    if [ "$kiosk_rc" -eq 0 ] && [ "${frames:-0}" -ge 2 ] && grep -q "fps, frame" "$L/kiosk.out"; then
        ok drm-kiosk-sigterm
    else
        fail drm-kiosk-sigterm "exit $kiosk_rc, frames=$frames, stats lines: $(grep -c 'fps, frame' "$L/kiosk.out")"
    fi
    note "kiosk: $(grep -m1 'frames in' "$L/kiosk.out") ($((SECONDS - t0)) s)"
}

# The kiosk loop allocates nothing per frame: the player's own malloc/calloc/realloc calls
# (tests/vm/alloc_count.so) are the same for 4 and for 16 frames, with the camera and a GPIO
# line in use. Mesa's own allocations are not counted (not ours to control).
test_no_allocations_per_frame() {
    local preload=$B/tests/vm/alloc_count.so n counts=""
    if [ ! -f "$preload" ]; then
        skip "drm-no-allocations-per-frame$SFX" "$preload is not built (make test-vm builds it)"
        return
    elif ldd "$PLAYER" | grep -q libasan; then
        skip "drm-no-allocations-per-frame$SFX" "an ASan build replaces malloc itself"
        return
    fi
    gpio_sim_paths
    for n in 4 16; do
        timeout -k 5 120 env LD_PRELOAD="$preload" "$PLAYER" --display drm --device "$CARD" --mode "$MODE" --scale 8 \
            --fps 30 --frames $n --scene "$T/camera.cfg" --video /dev/video0 \
            --gpio "$GPIO_CHIP:2=explosion" --quiet >"$L/alloc$n$SFX.out" 2>"$L/alloc$n$SFX.err"
        counts="$counts $(sed -n 's/^alloc-count: program \([0-9]*\),.*/\1/p' "$L/alloc$n$SFX.err")"
    done
    read -r a b <<<"$counts"
    if [ -n "${a:-}" ] && [ "$a" = "${b:-}" ]; then
        ok "drm-no-allocations-per-frame$SFX"
    else
        fail "drm-no-allocations-per-frame$SFX" "allocations from the player: '$a' after 4 frames, '$b' after 16"
    fi
    note "allocations from the player's code: $a (4 frames), $b (16 frames); all, Mesa included: $(grep -h alloc-count "$L"/alloc[0-9]*"$SFX".err | sed 's/.*all //' | tr '\n' ' ')"
}

# ---- V4L2 detail from vivid ------------------------------------------------------------------

make_scenes() {
    sed 's/source = "procedural"/source = "v4l2"/' scenes/explosion.cfg >"$T/camera.cfg"
}

# The explosion scene with its timeline replaced by a GPIO trigger on line 1 of the chip.
make_gpio_scene() {
    sed '/^triggers = {/,$d' scenes/explosion.cfg >"$T/gpio-scene.cfg"
    printf 'triggers = {\n  gpio = ( { chip = "%s"; line = 1; edge = "rising"; debounce_ms = 30;\n            effect = "explosion"; position = [1.0, 0.0, 0.0]; } );\n};\n' \
        "$GPIO_CHIP" >>"$T/gpio-scene.cfg"
}

# video_frames_so_far NAME: the camera frames the kiosk NAME counted in its stats lines so far.
video_frames_so_far() { sed -n 's/.*, video \([0-9]*\) frames.*/\1/p' "$L/$1.out" | awk '{s += $1} END {print s + 0}'; }

# The camera's frames reach the detail volume, and they differ. The kiosk runs until its stats
# lines counted 4 camera frames (a frame takes up to seconds under TCG: a fixed time proves
# nothing there), 35 s at most; the summary's counts are then checked.
test_video_frames() {
    local t0=$SECONDS i
    if ! kiosk video --scene "$T/camera.cfg" --video /dev/video0 --scale 8 --stats "$L/video.json"; then
        fail video-frames "no banner: $(first_line "$L/video.err")"
        stop_kiosk
        return
    fi
    for ((i = 0; i < 350; i++)); do
        [ "$(video_frames_so_far video)" -ge 4 ] && break
        sleep 0.1
    done
    stop_kiosk
    local frames distinct
    frames=$(json_number "$L/video.json" video_frames)
    distinct=$(json_number "$L/video.json" video_distinct)
    if [ "$kiosk_rc" -ne 0 ]; then
        fail video-frames "exit $kiosk_rc: $(grep -v -e vkms -e kmsro "$L/video.err" | head -n 1)"
    elif [ "${frames:-0}" -lt 3 ] || [ "${distinct:-0}" -lt 2 ]; then
        fail video-frames "video_frames=$frames video_distinct=$distinct"
    else
        ok video-frames
    fi
    note "$(grep -m1 'feeds the detail volume' "$L/video.err"); frames $frames, distinct $distinct ($((SECONDS - t0)) s)"
}

# The GStreamer camera kiosk (examples/gstreamer/camera-kms.sh, docs/hosts/gstreamer.md): vivid's
# frames through v4l2src, the element sbfx with the video as its detail (detail-from-input), the
# frames to vkms through kmssink, which sets a 640x480 mode (vkms's planes do not scale). The
# scene is the explosion every second (64, a timeline's most): under TCG the element's start
# (its shaders) holds the first frame some 20 s, which the camera's running time counts. While it plays the CRTC scans
# kmssink's framebuffer out (another than the console's, at 640x480); at the end the element's
# summary (GST_DEBUG=sbfx:4) says it rendered explosions and pushed the camera's slices.
gst_scene() {
    # the particle target at 1/8 of the frame: under TCG a 1/4 target costs a second a frame
    sed -e '/^triggers = {/,$d' -e 's/^\( *target_scale *= *\)4;/\18;/' scenes/explosion.cfg >"$T/gst-again.cfg"
    {
        echo 'triggers = { timeline = ('
        local t
        for ((t = 1; t < 64; t++)); do
            printf '  { effect = "explosion"; time = %d.0; position = [0.0, 0.0, 0.0]; },\n' "$t"
        done
        echo '  { effect = "explosion"; time = 64.0; position = [0.0, 0.0, 0.0]; } ); };'
    } >>"$T/gst-again.cfg"
}

test_gst_camera() {
    local t0=$SECONDS
    if ! command -v gst-launch-1.0 >/dev/null; then
        skip gst-camera "gst-launch-1.0 is not installed (tools/deps.sh vm)"
        return
    fi
    if [ ! -f "$B/gstreamer/libgstsbfx.so" ]; then
        fail gst-camera "$B/gstreamer/libgstsbfx.so was not built (make gstreamer)"
        return
    fi
    gst_scene
    local console
    console=$("$DRM_STATE" "$CARD" 2>&1 | grep -m1 ' mode ' | awk '{print $4}')
    step "camera-kms.sh: vivid -> sbfx -> kmssink"
    env GST_PLUGIN_PATH="$B/gstreamer" LD_LIBRARY_PATH="$B" GST_REGISTRY="$T/gst-registry.bin" GST_DEBUG=sbfx:4 \
        GST_DEBUG_NO_COLOR=1 SCENE="$T/gst-again.cfg" KMSSINK="driver-name=vkms force-modesetting=true" \
        CAMERA="v4l2src device=/dev/video0 num-buffers=30 ! video/x-raw,width=640,height=480" \
        timeout -k 5 200 examples/gstreamer/camera-kms.sh >"$L/gst-camera.out" 2>"$L/gst-camera.err" &
    local pid=$! crtc="" i
    # until the CRTC shows kmssink's framebuffer, or the run ends
    for ((i = 0; i < 1200; i++)); do
        [ -z "$crtc" ] && kill -0 "$pid" 2>/dev/null || break
        crtc=$("$DRM_STATE" "$CARD" 2>&1 | awk -v c="$console" '$4 != 0 && $4 != c && $6 == "640x480"' | head -n 1)
        pause 0.1
    done
    wait "$pid"
    local rc=$? summary rendered slices
    summary=$(grep -o 'stopped after.*' "$L/gst-camera.err" | tail -n 1)
    rendered=$(printf '%s' "$summary" | sed -n 's/.* \([0-9]*\) rendered.*/\1/p')
    slices=$(printf '%s' "$summary" | sed -n 's/.* \([0-9]*\) detail slices.*/\1/p')
    if [ "$rc" -ne 0 ]; then
        fail gst-camera "exit $rc: $(grep -m1 -e ERROR -e CRITICAL "$L/gst-camera.out" "$L/gst-camera.err" | cut -c 1-200)"
    elif [ -z "$crtc" ]; then
        fail gst-camera "the CRTC never showed a 640x480 framebuffer other than the console's ($console) while kmssink played"
    elif grep -q CRITICAL "$L/gst-camera.err"; then
        fail gst-camera "$(grep -m1 CRITICAL "$L/gst-camera.err" | cut -c 1-200)"
    elif [ "${rendered:-0}" -lt 10 ] || [ "${slices:-0}" -lt 25 ]; then
        fail gst-camera "the element: '$summary'"
    else
        ok gst-camera
    fi
    note "gst-camera: $crtc (console fb $console); $summary ($((SECONDS - t0)) s)"
}

# stats_lines NAME: how many once-a-second stats lines the kiosk NAME printed so far.
stats_lines() { grep -c 'fps, frame' "$L/$1.out"; }

# wait_stats NAME COUNT SECONDS: until the kiosk printed COUNT stats lines.
wait_stats() {
    local i
    for ((i = 0; i < $3 * 10; i++)); do
        [ "$(stats_lines "$1")" -ge "$2" ] && return 0
        sleep 0.1
    done
    return 1
}

# One kiosk with the camera through two outages: vivid stops delivering frames (its "Percentage
# of Dropped Buffers" control at 100: the player's 2 s no-frame timeout), then delivers again;
# then its device is unbound (what a USB disconnect does; the module cannot be unloaded while a
# program holds the device open), the module unloaded once the player let go, and loaded again
# as a multi-planar device (the path SoC ISPs take). Each outage is logged once, rendering goes
# on with procedural detail (the stats lines keep coming), the camera is picked up again.
test_video_outages() {
    local t0=$SECONDS
    if ! kiosk unplug --scene "$T/camera.cfg" --video /dev/video0 --scale 8 --stats "$L/unplug.json"; then
        fail video-timeout "no banner: $(first_line "$L/unplug.err")"
        stop_kiosk
        return
    fi
    wait_for "$L/unplug.err" "feeds the detail volume" 30
    "$V4L2_CTRL" /dev/video0 "Percentage of Dropped Buffers" 100 2>>"$L/unplug.ctl"
    local lost=no back=no
    wait_for "$L/unplug.err" "no frame for 2000 ms" 30 && lost=yes
    local at_loss
    at_loss=$(stats_lines unplug)
    wait_stats unplug $((at_loss + 3)) 30
    "$V4L2_CTRL" /dev/video0 "Percentage of Dropped Buffers" 0 2>>"$L/unplug.ctl"
    wait_for "$L/unplug.err" "is back" 30 && back=yes
    if [ "$lost" = yes ] && [ "$back" = yes ] && [ "$(grep -c 'takes over' "$L/unplug.err")" -eq 1 ] &&
        [ "$(stats_lines unplug)" -ge $((at_loss + 3)) ]; then
        ok video-timeout
    else
        fail video-timeout "lost=$lost back=$back, 'takes over' logged $(grep -c 'takes over' "$L/unplug.err") times, stats lines $at_loss -> $(stats_lines unplug) $(head -c 200 "$L/unplug.ctl" 2>/dev/null)"
    fi
    echo vivid.0 >/sys/bus/platform/drivers/vivid/unbind
    wait_for "$L/unplug.err" "No such device" 15
    local unloaded=yes
    rmmod vivid 2>"$L/rmmod.err" || unloaded="no ($(cat "$L/rmmod.err"))"
    note "vivid unbound; module unloaded: $unloaded"
    at_loss=$(stats_lines unplug)
    wait_stats unplug $((at_loss + 3)) 30
    local after
    after=$(stats_lines unplug)
    modprobe vivid node_types=0x1 multiplanar=2 2>/dev/null
    [ -e /dev/video0 ] || echo vivid.0 >/sys/bus/platform/drivers/vivid/bind 2>/dev/null
    wait_for "$L/unplug.err" "mplane" 30
    sleep 1
    stop_kiosk
    local losses reopens takeovers said frames
    losses=$(json_number "$L/unplug.json" video_losses)
    reopens=$(json_number "$L/unplug.json" video_reopens)
    takeovers=$(json_number "$L/unplug.json" video_takeovers)
    frames=$(json_number "$L/unplug.json" video_frames)
    said=$(grep -c "procedural detail takes over" "$L/unplug.err")
    if [ "$kiosk_rc" -ne 0 ]; then
        fail video-unplug "exit $kiosk_rc: $(grep -v -e vkms -e kmsro "$L/unplug.err" | tail -n 1)"
    elif [ "$said" -ne 2 ] || [ "${losses:-0}" -ne 2 ] || [ "${takeovers:-0}" -ne 2 ]; then
        fail video-unplug "2 outages: loss logged $said times, video_losses=$losses video_takeovers=$takeovers"
    elif [ "$after" -lt $((at_loss + 3)) ]; then
        fail video-unplug "rendering stopped after the camera went away ($at_loss stats lines, then $after)"
    else
        ok video-unplug
    fi
    if [ "${reopens:-0}" -eq 2 ] && grep -q "is back: .* mplane" "$L/unplug.err"; then
        ok video-reopen-multiplanar
    else
        fail video-reopen-multiplanar "video_reopens=$reopens; $(grep 'is back' "$L/unplug.err" | tail -n 1)"
    fi
    grep -e "takes over" -e "is back" "$L/unplug.err" | sed 's/^/# /'
    note "camera frames $frames ($((SECONDS - t0)) s)"
}

# ---- GPIO triggers from gpio-sim -------------------------------------------------------------

# press LINE: one clean press of a simulated button (rising edge, 100 ms, falling edge).
press() {
    echo pull-up >"$GPIO_SYS/sim_gpio$1/pull"
    sleep 0.1
    echo pull-down >"$GPIO_SYS/sim_gpio$1/pull"
}

# press_read NAME LINE: a press, then until the kiosk NAME printed two more stats lines.
press_read() {
    local lines
    lines=$(stats_lines "$1")
    press "$2"
    wait_stats "$1" $((lines + 2)) 30
}

# storm: 1000 edges on line 0 spread over one second: bursts of 20 edges every 20 ms, paced
# with bash builtins only ($EPOCHREALTIME, read -t on a FIFO; no sleep processes, which cost
# tens of ms each under TCG).
storm() {
    local i now due wait
    [ -p "$T/pace" ] || mkfifo "$T/pace"
    exec 9<>"$T/pace"
    local start=${EPOCHREALTIME/./}
    for ((i = 0; i < 500; i++)); do
        echo pull-up >"$GPIO_PULL"
        echo pull-down >"$GPIO_PULL"
        ((i % 10 == 9)) || continue
        due=$((start + (i + 1) * 2000))
        now=${EPOCHREALTIME/./}
        ((due > now)) || continue
        printf -v wait '%d.%06d' $(((due - now) / 1000000)) $(((due - now) % 1000000))
        read -r -t "$wait" -u 9
    done
    exec 9>&-
}

# Line 0 from --gpio, line 1 from the scene's triggers.gpio, debounce and rate limit from a
# board profile: 4 clean presses on line 0 fire 4 explosions, a storm of 1000 edges in about a
# second fires 1, a press on line 1 fires 1. The board's rate limit (1.5 s) is longer than the
# storm: under TCG the shell writing the edges can stall for more than the 30 ms debounce, which
# would be a real quiet gap; tests/platform/test_trigger_filter.c checks the debounce itself
# (and the kernel FIFO overflow) with exact timelines.
test_gpio() {
    local t0=$SECONDS
    gpio_sim_paths
    make_gpio_scene
    printf 'board = "vm";\ngpio = { debounce_ms = 30; min_interval_ms = 1500; };\n' >"$T/vm-board.cfg"
    if ! kiosk "gpio$SFX" --board "$T/vm-board.cfg" --scene "$T/gpio-scene.cfg" --scale 8 \
        --gpio "$GPIO_CHIP:0=explosion@0,0,0" --stats "$L/gpio$SFX.json"; then
        fail "gpio-presses$SFX" "no banner: $(first_line "$L/gpio$SFX.err")"
        stop_kiosk
        return
    fi
    # Each step waits until the kiosk has finished two more stats lines (a whole frame, whose GPIO
    # service read the edges): under TCG on a loaded host a frame can take seconds (the first one,
    # compiling shaders, ten), and edges left in the kernel's 16-event FIFO until the storm, or
    # read more than 10 s late (they then carry the read's time), would be lost or merged.
    step "first frames"
    wait_stats "gpio$SFX" 2 60
    local i
    for i in 1 2 3 4; do
        step "press $i on line 0"
        press_read "gpio$SFX" 0
        sleep 1.6
    done
    local storm_ms
    step "storm of 1000 edges on line 0"
    storm_ms=$(date +%s%N)
    storm
    storm_ms=$((($(date +%s%N) - storm_ms) / 1000000))
    wait_stats "gpio$SFX" $(($(stats_lines "gpio$SFX") + 2)) 30
    sleep 1.6
    step "press on line 1 (the scene's)"
    press_read "gpio$SFX" 1
    step "stopping the kiosk"
    stop_kiosk
    local fired edges filtered
    fired=$(json_number "$L/gpio$SFX.json" gpio_fired)
    edges=$(json_number "$L/gpio$SFX.json" gpio_edges)
    filtered=$(json_number "$L/gpio$SFX.json" gpio_filtered)
    note "gpio$SFX: 4 presses, 1000 edges in $storm_ms ms, 1 press on the scene's line: gpio_edges=$edges (the kernel FIFO drops the rest) gpio_filtered=$filtered gpio_fired=$fired"
    if [ "$kiosk_rc" -ne 0 ]; then
        fail "gpio-presses$SFX" "exit $kiosk_rc: $(grep -v -e vkms -e kmsro "$L/gpio$SFX.err" | head -n 1)"
    elif [ "${fired:-0}" -ne 6 ]; then
        fail "gpio-presses$SFX" "4 clean presses, a storm and a press on the scene's line fired $fired effects (expected 6)"
    else
        ok "gpio-presses$SFX"
    fi
    local triggers
    triggers=$(json_number "$L/gpio$SFX.json" triggers_fired)
    if [ "${triggers:-0}" -eq "${fired:-x}" ]; then ok "gpio-effects-started$SFX"; else
        fail "gpio-effects-started$SFX" "sbfx triggers_fired=$triggers, gpio_fired=$fired"; fi
    note "gpio$SFX test: $((SECONDS - t0)) s"
}

# gpio_sim_paths: the chip's sysfs folder again (GPIO_SYS, GPIO_CHIP, GPIO_PULL) after it was
# re-created (each GPIO group starts with it: an earlier group may have re-created the chip).
gpio_sim_paths() {
    local cfg=/sys/kernel/config/gpio-sim/sbfx
    GPIO_CHIP=$(cat "$cfg/bank0/chip_name")
    GPIO_SYS=/sys/devices/platform/$(cat "$cfg/dev_name")/$GPIO_CHIP
    GPIO_PULL=$GPIO_SYS/sim_gpio0/pull
}

# The kiosk's GPIO chip removed while it runs (gpio-sim's device taken down through configfs, as
# an I/O board unplugged), then created again: the loss is logged once, the frames go on (the
# stats lines keep coming), the line is requested again (found by its chip's label) and a press
# on it fires an effect again.
test_gpio_loss() {
    local cfg=/sys/kernel/config/gpio-sim/sbfx
    gpio_sim_paths
    step "kiosk with --gpio $GPIO_LABEL:3"
    if ! kiosk gpioloss$SFX --scale 8 --gpio "$GPIO_LABEL:3=explosion" --stats "$L/gpioloss$SFX.json"; then
        fail "gpio-loss$SFX" "no banner: $(first_line "$L/gpioloss$SFX.err")"
        stop_kiosk
        return
    fi
    step "press on line 3 before the loss"
    local lines
    lines=$(stats_lines gpioloss$SFX)
    press 3
    # an edge still in the kernel's FIFO when the chip goes is lost with it: let the kiosk read
    # it first (two stats lines: at least one whole frame, whose GPIO service reads it)
    wait_stats gpioloss$SFX $((lines + 2)) 30
    step "gpio-sim device removed (live = 0)"
    echo 0 >"$cfg/live"
    local lost=no back=no at_loss after
    wait_for "$L/gpioloss$SFX.err" "the chip went away" 15 && lost=yes
    at_loss=$(stats_lines gpioloss$SFX)
    step "frames without the chip"
    wait_stats gpioloss$SFX $((at_loss + 3)) 30
    after=$(stats_lines gpioloss$SFX)
    step "gpio-sim device created again (live = 1)"
    echo 1 >"$cfg/live"
    gpio_sim_paths
    wait_for "$L/gpioloss$SFX.err" "is back" 20 && back=yes
    step "press on line 3 after the return ($GPIO_CHIP)"
    lines=$(stats_lines gpioloss$SFX)
    press 3
    wait_stats gpioloss$SFX $((lines + 2)) 30
    step "stopping the kiosk"
    stop_kiosk
    local losses returns fired said
    losses=$(json_number "$L/gpioloss$SFX.json" gpio_losses)
    returns=$(json_number "$L/gpioloss$SFX.json" gpio_returns)
    fired=$(json_number "$L/gpioloss$SFX.json" gpio_fired)
    said=$(grep -c "went away" "$L/gpioloss$SFX.err")
    note "gpio loss$SFX: lost=$lost back=$back, stats lines $at_loss -> $after without the chip," \
        "gpio_losses=$losses gpio_returns=$returns gpio_retries=$(json_number "$L/gpioloss$SFX.json" gpio_retries) gpio_fired=$fired"
    grep -e "went away" -e "is back" "$L/gpioloss$SFX.err" | sed 's/^/# /'
    if [ "$kiosk_rc" -ne 0 ]; then
        fail "gpio-loss$SFX" "exit $kiosk_rc: $(grep -v -e vkms -e kmsro "$L/gpioloss$SFX.err" | tail -n 1)"
    elif [ "$lost" != yes ] || [ "$said" -ne 1 ] || [ "${losses:-0}" -ne 1 ]; then
        fail "gpio-loss$SFX" "chip removed: loss logged $said times, gpio_losses=$losses"
    elif [ "$after" -lt $((at_loss + 3)) ]; then
        fail "gpio-loss$SFX" "rendering stopped without the chip ($at_loss stats lines, then $after)"
    else
        ok "gpio-loss$SFX"
    fi
    if [ "$back" = yes ] && [ "${returns:-0}" -eq 1 ] && [ "${fired:-0}" -eq 2 ]; then
        ok "gpio-return$SFX"
    else
        fail "gpio-return$SFX" "back=$back gpio_returns=$returns; a press before and one after fired $fired (expected 2)"
    fi
}

# flips_so_far NAME: the flips the kiosk NAME counted in its stats lines so far.
flips_so_far() { sed -n 's/.*, flips \([0-9]*\),.*/\1/p' "$L/$1.out" | awk '{s += $1} END {print s + 0}'; }

# The display unplugged and plugged back while the kiosk runs. vkms (6.1) cannot hot-unplug its
# one connector and its device cannot be unbound (no driver to unbind; the module is in use), so
# this is the DRM core's forced connector state on the real driver: "off" written to the
# connector's sysfs status makes the kernel report it disconnected (what a cable pulled does to
# a real connector's state), "detect" gives it back. The player pauses scan-out (logged once,
# no flips, frames still rendered at 10 Hz, stats lines keep coming), then sets the mode again
# and flips resume.
test_display_unplug() {
    local status
    status=$(ls -d /sys/class/drm/card0-Virtual-*/status 2>/dev/null | head -n 1)
    if [ ! -w "$status" ]; then
        skip display-unplug "no writable connector status in /sys/class/drm"
        return
    fi
    step "kiosk on $CARD"
    if ! kiosk unplugdisp --scale 8 --stats "$L/unplugdisp.json"; then
        fail display-unplug "no banner: $(first_line "$L/unplugdisp.err")"
        stop_kiosk
        return
    fi
    wait_stats unplugdisp 2 30
    step "connector forced off ($status)"
    echo off >"$status"
    local paused=no resumed=no at_pause flips_at_pause lines_after flips_paused
    wait_for "$L/unplugdisp.err" "disconnected; scan-out paused" 15 && paused=yes
    pause 1.5 # the stats line of the second the pause began may still count flips
    at_pause=$(stats_lines unplugdisp)
    flips_at_pause=$(flips_so_far unplugdisp)
    step "frames while disconnected"
    wait_stats unplugdisp $((at_pause + 3)) 30
    lines_after=$(stats_lines unplugdisp)
    flips_paused=$(($(flips_so_far unplugdisp) - flips_at_pause))
    step "connector back (detect)"
    echo detect >"$status"
    wait_for "$L/unplugdisp.err" "connected again" 15 && resumed=yes
    local at_resume
    at_resume=$(flips_so_far unplugdisp)
    wait_stats unplugdisp $((lines_after + 3)) 30
    step "stopping the kiosk"
    stop_kiosk
    local unplugs replugs flips_after
    unplugs=$(json_number "$L/unplugdisp.json" display_unplugs)
    replugs=$(json_number "$L/unplugdisp.json" display_replugs)
    flips_after=$(($(flips_so_far unplugdisp) - at_resume))
    note "display unplug: paused=$paused resumed=$resumed; stats lines $at_pause -> $lines_after while" \
        "disconnected with $flips_paused flips; $flips_after flips after; display_unplugs=$unplugs" \
        "display_replugs=$replugs display_paused_frames=$(json_number "$L/unplugdisp.json" display_paused_frames)"
    if [ "$kiosk_rc" -ne 0 ]; then
        fail display-unplug "exit $kiosk_rc: $(grep -v -e vkms -e kmsro "$L/unplugdisp.err" | tail -n 1)"
    elif [ "$paused" != yes ] || [ "$(grep -c 'scan-out paused' "$L/unplugdisp.err")" -ne 1 ] ||
        [ "${unplugs:-0}" -ne 1 ]; then
        fail display-unplug "forced off: paused=$paused, display_unplugs=$unplugs"
    elif [ "$lines_after" -lt $((at_pause + 3)) ] || [ "$flips_paused" -ne 0 ]; then
        fail display-unplug "while disconnected: stats lines $at_pause -> $lines_after, flips $flips_paused (expected none)"
    else
        ok display-unplug
    fi
    if [ "$resumed" = yes ] && [ "${replugs:-0}" -eq 1 ] && [ "$flips_after" -gt 0 ]; then
        ok display-replug
    else
        fail display-replug "resumed=$resumed display_replugs=$replugs, $flips_after flips after"
    fi
}

# The CRTC switched on and off 1000 times (VBLANK_CYCLES on the host) with a page flip in between
# (tests/vm/vblank_stress.c):
# every cycle disables the vblank timer while it may be firing, which deadlocks Debian 6.1's
# vkms without tests/vm/patches/vkms-vblank-cancel-deadlock.patch (the VM then stops dead: no
# process can run, and run.sh reports the wedged CPUs).
VBLANK_CYCLES=${SBFX_VBLANK_CYCLES:-1000}
test_vblank_off_stress() {
    step "vblank_stress $CARD $VBLANK_CYCLES: CRTC on, a page flip, CRTC off"
    local t0=$SECONDS
    "$VBLANK_STRESS" "$CARD" "$VBLANK_CYCLES" >"$L/vblank-stress.out" 2>"$L/vblank-stress.err"
    local rc=$?
    if [ "$rc" -eq 0 ] && grep -q "cycles $VBLANK_CYCLES, flips $VBLANK_CYCLES" "$L/vblank-stress.out"; then
        ok drm-vblank-off-stress
    else
        fail drm-vblank-off-stress "exit $rc: $(cat "$L/vblank-stress.out" "$L/vblank-stress.err" | tr '\n' ' ')"
    fi
    note "vblank stress: $(cat "$L/vblank-stress.out") in $((SECONDS - t0)) s"
}

test_drm_errors() {
    play --display drm --device "$CARD" --connector HDMI-A-1 --frames 1 >"$L/conn.out" 2>"$L/conn.err"
    local rc=$?
    if [ "$rc" -eq 1 ] && grep -qF "$CARD" "$L/conn.err" && grep -qF "no connector 'HDMI-A-1'" "$L/conn.err"; then
        ok drm-missing-connector
    else
        fail drm-missing-connector "exit $rc: $(first_line "$L/conn.err")"
    fi
    play --display drm --device "$CARD" --mode 123x45 --frames 1 >"$L/mode.out" 2>"$L/mode.err"
    rc=$?
    if [ "$rc" -eq 1 ] && grep -qF "offers no such mode" "$L/mode.err"; then
        ok drm-missing-mode
    else
        fail drm-missing-mode "exit $rc: $(first_line "$L/mode.err")"
    fi
}

test_gpio_errors() {
    gpio_sim_paths
    play --display drm --device "$CARD" --frames 1 --gpio "$GPIO_CHIP:99=explosion" \
        >"$L/gl$SFX.out" 2>"$L/gl$SFX.err"
    local rc=$?
    # a line the chip does not have is not fatal (it may come with another board): logged, retried
    if [ "$rc" -eq 0 ] && grep -qF "$GPIO_CHIP" "$L/gl$SFX.err" && grep -qF "no line 99" "$L/gl$SFX.err" &&
        grep -qF "until it appears" "$L/gl$SFX.err"; then
        ok "gpio-missing-line$SFX"
    else
        fail "gpio-missing-line$SFX" "exit $rc: $(grep -v -e vkms -e kmsro "$L/gl$SFX.err" | head -n 1)"
    fi
    # a line held by a kiosk (its chip by path) is in use for a second player (its chip by number),
    # which names the holder's consumer label
    step "kiosk holding /dev/$GPIO_CHIP line 5"
    if ! kiosk "gpiobusy$SFX" --scale 8 --gpio "/dev/$GPIO_CHIP:5=explosion"; then
        fail "gpio-busy-line$SFX" "no banner: $(first_line "$L/gpiobusy$SFX.err")"
        stop_kiosk
        return
    fi
    step "second player on line 5 of chip ${GPIO_CHIP#gpiochip}"
    play --headless --size 64x64 --frames 1 --out "$T/busy$SFX" --gpio "${GPIO_CHIP#gpiochip}:5=explosion" \
        >"$L/gpiobusy2$SFX.out" 2>"$L/gpiobusy2$SFX.err"
    rc=$?
    stop_kiosk
    if [ "$rc" -eq 1 ] && grep -qF "$GPIO_CHIP line 5 is in use by 'sbfx-play'" "$L/gpiobusy2$SFX.err"; then
        ok "gpio-busy-line$SFX"
    else
        fail "gpio-busy-line$SFX" "exit $rc: $(head -n 1 "$L/gpiobusy2$SFX.err")"
    fi
}

# The kiosk started while its GPIO chip is not there (gpio-sim's device down: an I/O board late at
# boot): the absence is logged once, the frames go on, the chip is created, the line is requested
# (found by its label) and a press on it fires an effect.
test_gpio_late() {
    local cfg=/sys/kernel/config/gpio-sim/sbfx name=gpiolate$SFX
    gpio_sim_paths
    step "gpio-sim device removed before the kiosk starts (live = 0)"
    echo 0 >"$cfg/live"
    step "kiosk with --gpio $GPIO_LABEL:4, no such chip"
    if ! kiosk "$name" --scale 8 --gpio "$GPIO_LABEL:4=explosion" --stats "$L/$name.json"; then
        fail "gpio-late-chip$SFX" "no banner: $(first_line "$L/$name.err")"
        echo 1 >"$cfg/live"
        stop_kiosk
        return
    fi
    local absent=no appeared=no at_start after
    wait_for "$L/$name.err" "until it appears" 15 && absent=yes
    at_start=$(stats_lines "$name")
    step "frames without the chip"
    wait_stats "$name" $((at_start + 3)) 30
    after=$(stats_lines "$name")
    step "gpio-sim device created (live = 1)"
    echo 1 >"$cfg/live"
    gpio_sim_paths
    local t_live=$SECONDS
    wait_for "$L/$name.err" "appeared" 20 && appeared=yes
    local took=$((SECONDS - t_live))
    step "press on line 4 ($GPIO_CHIP)"
    local lines
    lines=$(stats_lines "$name")
    press 4
    wait_stats "$name" $((lines + 2)) 30
    step "stopping the kiosk"
    stop_kiosk
    local fired absent_n appeared_n
    fired=$(json_number "$L/$name.json" gpio_fired)
    absent_n=$(json_number "$L/$name.json" gpio_absent)
    appeared_n=$(json_number "$L/$name.json" gpio_appeared)
    note "gpio late$SFX: absent=$absent appeared=$appeared (${took} s after the chip was created)," \
        "stats lines $at_start -> $after without the chip, gpio_absent=$absent_n gpio_appeared=$appeared_n" \
        "gpio_retries=$(json_number "$L/$name.json" gpio_retries) gpio_fired=$fired"
    grep -e "until it appears" -e "appeared" "$L/$name.err" | sed 's/^/# /'
    if [ "$kiosk_rc" -ne 0 ]; then
        fail "gpio-late-chip$SFX" "exit $kiosk_rc: $(grep -v -e vkms -e kmsro "$L/$name.err" | tail -n 1)"
    elif [ "$absent" != yes ] || [ "$(grep -c 'until it appears' "$L/$name.err")" -ne 1 ] || [ "${absent_n:-0}" -ne 1 ]; then
        fail "gpio-late-chip$SFX" "chip absent at start: logged $(grep -c 'until it appears' "$L/$name.err") times, gpio_absent=$absent_n"
    elif [ "$after" -lt $((at_start + 3)) ]; then
        fail "gpio-late-chip$SFX" "rendering stopped without the chip ($at_start stats lines, then $after)"
    elif [ "$appeared" != yes ] || [ "${appeared_n:-0}" -ne 1 ] || [ "${fired:-0}" -ne 1 ]; then
        fail "gpio-late-chip$SFX" "appeared=$appeared gpio_appeared=$appeared_n; a press once it appeared fired $fired (expected 1)"
    else
        ok "gpio-late-chip$SFX"
    fi
}

# The backend itself (tests/vm/gpio_backend.c, built against this libgpiod): lookups, errors,
# edges, the kernel FIFO, the chip taken away and created again.
test_gpio_backend() {
    gpio_sim_paths
    local tool=$B/tests/vm/gpio_backend
    [ -n "$SFX" ] && tool=$B/gpiod2/tests/vm/gpio_backend
    step "$tool on $GPIO_CHIP"
    timeout -k 5 50 "$tool" "gpio-backend$SFX" "$GPIO_CHIP" "$GPIO_LABEL" "$GPIO_SYS" \
        /sys/kernel/config/gpio-sim/sbfx >"$L/gpio-backend$SFX.out" 2>"$L/gpio-backend$SFX.err"
    local rc=$?
    grep -e '^ok - ' -e '^not ok - ' "$L/gpio-backend$SFX.out" | while IFS= read -r line; do result "$line"; done
    grep '^#' "$L/gpio-backend$SFX.err" | head -n 5
    [ "$rc" -le 1 ] || fail "gpio-backend$SFX" "$tool exited with $rc: $(head -n 2 "$L/gpio-backend$SFX.err" | tr '\n' ' ')"
    # make test's backend checks too (tests/platform/test_gpio_backend.c), here with chips to list
    local unit=$B/tests/platform/test_gpio_backend
    [ -n "$SFX" ] && unit=$B/gpiod2/tests/platform/test_gpio_backend
    step "$unit"
    timeout -k 5 30 "$unit" >"$L/gpio-backend-unit$SFX.out" 2>&1
    rc=$?
    sed -nE "s#^(ok|not ok|skip) - test_gpio_backend/#\1 - vm/gpio-backend$SFX/unit-#p" "$L/gpio-backend-unit$SFX.out" |
        while IFS= read -r line; do result "$line"; done
    grep -q '^ok - ' "$L/gpio-backend-unit$SFX.out" && [ "$rc" -le 1 ] ||
        fail "gpio-backend$SFX/unit" "$unit exited with $rc: $(head -n 2 "$L/gpio-backend-unit$SFX.out" | tr '\n' ' ')"
}

# with_gpiod2 FUNCTION: a GPIO test group with the player built against libgpiod 2.x.
with_gpiod2() {
    if [ ! -x "$PLAYER_GPIOD2" ]; then
        fail "$CURRENT_TEST" "$PLAYER_GPIOD2 is not built (make test-vm builds it)"
        return
    fi
    PLAYER=$PLAYER_GPIOD2
    SFX=-gpiod2
    "$@"
}

# The per-test limit itself: a group that hangs (blocked on a FIFO nobody writes, with a child
# process in its group, like a kiosk) must fail with its step and its log's tail, its processes
# killed, within its limit; the tier then goes on.
hang_forever() {
    step "blocked on a FIFO nobody writes"
    echo "selftest: about to block" >"$L/selftest.err"
    sleep 1000 &
    echo "$!" >"$T/selftest-child"
    mkfifo "$T/selftest-fifo"
    read -r <"$T/selftest-fifo"
}

test_harness_limit() {
    local t0=$SECONDS line child
    RESULTS=$T/selftest.txt run_test selftest-hang 3 hang_forever >/dev/null
    CURRENT_TEST=harness-limit
    line=$(cat "$T/selftest.txt" 2>/dev/null)
    child=$(cat "$T/selftest-child" 2>/dev/null)
    if [[ "$line" != "not ok - vm/selftest-hang: timed out after 3 s at step 'blocked on a FIFO nobody writes'"* ]] ||
        [[ "$line" != *"selftest: about to block"* ]]; then
        fail harness-limit "a hung group gave: '$line'"
    elif [ -n "$child" ] && [ -e "/proc/$child" ] && [ "$(ps -o stat= -p "$child")" != Z ]; then
        fail harness-limit "the hung group's child $child is still running"
    elif [ $((SECONDS - t0)) -gt 15 ]; then
        fail harness-limit "the hung group took $((SECONDS - t0)) s to be stopped (limit 3 s)"
    else
        ok harness-limit
    fi
}

# Qt Quick on the DRM display (docs/hosts/qt-quick.md): the item's test on Qt's eglfs platform
# (eglfs_kms: GBM and EGL on vkms), the item smaller than the screen, drawn through its own target.
test_qt_eglfs() {
    local bin=$B/tests/qt/test_qt_quick t0=$SECONDS rc
    if [ ! -x "$bin" ]; then
        skip qt-eglfs "$bin was not built (make test-qt-quick: Qt 6, tools/deps.sh test)"
        return
    fi
    step "the Qt Quick item's test on eglfs"
    printf '{ "device": "%s", "hwcursor": false }\n' "$CARD" >"$T/eglfs.json"
    QT_QPA_PLATFORM=eglfs QT_QPA_EGLFS_INTEGRATION=eglfs_kms QT_QPA_EGLFS_KMS_CONFIG=$T/eglfs.json \
        XDG_RUNTIME_DIR=$T "$bin" item_smaller_than_the_window >"$L/qt-eglfs.out" 2>&1
    rc=$?
    if [ "$rc" -eq 0 ] && grep -q '^ok - test_qt_quick/item_smaller_than_the_window' "$L/qt-eglfs.out"; then
        ok "qt-eglfs ($(grep -m1 '^# explosion' "$L/qt-eglfs.out" | cut -c3-))"
    else
        fail qt-eglfs "exit status $rc: $(grep -m1 -e '^#   ' -e '^not ok' -e '^skip' "$L/qt-eglfs.out" ||
            tail -n 1 "$L/qt-eglfs.out")"
    fi
    note "qt-eglfs: $((SECONDS - t0)) s"
}

# ---- the tier --------------------------------------------------------------------------------

# SBFX_VM_TESTS (VM_TESTS on the host): only the groups named there (space separated); setup
# always runs.
selected() { [ -z "${SBFX_VM_TESTS:-}" ] || [[ " $SBFX_VM_TESTS " == *" $1 "* ]]; }
group() {
    selected "$1" || return 0
    run_test "$@"
}

note "guest up after $(uptime_s) s"
watch_kernel
group harness-limit 30 test_harness_limit
run_test modules 60 setup_modules
kernel_symbols
make_scenes
group drm-atomic 120 test_drm_atomic
group drm-writeback 90 test_screenshot_matches_headless
group drm-gpu-reset 90 test_drm_gpu_reset
group drm-legacy 60 test_drm_legacy
group drm-errors 60 test_drm_errors
group drm-kiosk 120 test_kiosk_and_busy
group video-frames 90 test_video_frames
group video-outages 150 test_video_outages
group gst-camera 240 test_gst_camera
run_test gpio-sim 30 setup_gpio_sim
if [ -s "$T/gpio.env" ]; then
    . "$T/gpio.env"
    group gpio-backend 60 test_gpio_backend
    group gpio-backend-gpiod2 60 with_gpiod2 test_gpio_backend
    group gpio 150 test_gpio
    group gpio-gpiod2 150 with_gpiod2 test_gpio
    group gpio-errors 90 test_gpio_errors
    group gpio-errors-gpiod2 90 with_gpiod2 test_gpio_errors
    group drm-no-allocations 120 test_no_allocations_per_frame
    group drm-no-allocations-gpiod2 120 with_gpiod2 test_no_allocations_per_frame
    group gpio-loss 120 test_gpio_loss
    group gpio-loss-gpiod2 120 with_gpiod2 test_gpio_loss
    group gpio-late 120 test_gpio_late
    group gpio-late-gpiod2 120 with_gpiod2 test_gpio_late
fi
group qt-eglfs 240 test_qt_eglfs
group display-unplug 120 test_display_unplug
group drm-vblank-off-stress $((90 + VBLANK_CYCLES / 10)) test_vblank_off_stress
kill "$DMESG_PID" 2>/dev/null
note "guest done after $(uptime_s) s (logs: build/vm/out/logs/, steps: build/vm/out/steps.txt)"
