#!/usr/bin/env bash
# The real-kernel test tier (make test-vm): boots Debian's own kernel under qemu (TCG) with the
# host's / shared read-only over 9p, loads vkms, vivid and gpio-sim, and runs sbfx-play and
# tests/vm/guest.sh against them. Prints the guest's "ok - vm/..." lines as they come and ends
# with "N passed, M failed[, K skipped]"; exits 1 if M > 0.
#
# Everything comes from Debian's archive (apt-get download; nothing is installed, nothing goes
# to /boot) and is cached in $VM_DIR (build/vm): a second run fetches and builds nothing.
#   debs/    linux-image, linux-headers (+ -common), linux-kbuild, linux-source, busybox-static
#   x/       those packages unpacked (dpkg -x)
#   src/     the few source files of vkms, gpio-sim and irq_sim, patched (tests/vm/patches/)
#   mods/    vkms.ko and gpio-sim.ko built out of tree (Debian's kernel has neither)
#   modules/ the guest's /lib/modules/VERSION: Debian's tree + updates/ (the two above)
#   initrd.gz, kernel.log (ttyS0), guest.log (ttyS1), monitor.log (qemu's monitor),
#   out/ (the guest's writable share: results.txt, steps.txt, logs/ with the player logs and
#   dmesg.txt, written while the guest runs, so they survive a VM that has to be killed)
#
# Environment: BUILD (build), VM_DIR (build/vm), VM_TIMEOUT (seconds for the VM, 1500: the outer
# guard; each test group has its own limit inside the guest, see guest.sh; the tests take about
# three minutes on two cores, more with the GPIO groups run twice (libgpiod 1.6 and 2) and
# under load), VM_TESTS (only these test groups, e.g. "gpio gpio-loss"),
# VBLANK_CYCLES (drm-vblank-off-stress's CRTC on/off cycles, 1000),
# VM_SMP (2), VM_MEM (1536M), KERNEL_ABI (e.g. 6.1.0-56-amd64; default: what linux-image-amd64
# depends on, remembered in $VM_DIR/kernel-abi).
set -u
cd "$(dirname "$0")/../.." || exit 1
ROOT=$PWD
BUILD=${BUILD:-build}
case $BUILD in /*) ;; *) BUILD=$ROOT/$BUILD ;; esac
VM_DIR=${VM_DIR:-$ROOT/build/vm}
VM_TIMEOUT=${VM_TIMEOUT:-1500}
VM_SMP=${VM_SMP:-2}
VM_MEM=${VM_MEM:-1536M}
INITRD_MODULES="virtio_ring virtio virtio_pci_modern_dev virtio_pci_legacy_dev virtio_pci netfs fscache 9pnet 9pnet_virtio 9p overlay"
start=$SECONDS

say() { printf '# vm: %s\n' "$*"; }
# Setup failures are one failed test line and the summary, never a hang or a silent exit.
die() {
    printf 'not ok - vm/setup: %s\n0 passed, 1 failed\n' "$*"
    exit 1
}

# ---- kernel packages ---------------------------------------------------------------------------

kernel_abi() {
    if [ -n "${KERNEL_ABI:-}" ]; then
        echo "$KERNEL_ABI"
    elif [ -s "$VM_DIR/kernel-abi" ]; then
        cat "$VM_DIR/kernel-abi"
    else
        apt-cache depends linux-image-amd64 2>/dev/null |
            sed -n 's/.*Depends: linux-image-\([0-9].*-amd64\)$/\1/p' | head -n 1
    fi
}

# fetch PACKAGE...: apt-get download of what is not in debs/ yet (same version for all).
fetch() {
    mkdir -p "$VM_DIR/debs"
    local missing="" p
    for p in "$@"; do
        ls "$VM_DIR/debs/${p}_"*.deb >/dev/null 2>&1 || missing="$missing $p"
    done
    [ -z "$missing" ] && return 0
    say "downloading from Debian's archive:$missing"
    # shellcheck disable=SC2086
    (cd "$VM_DIR/debs" && apt-get download $missing >/dev/null 2>"$VM_DIR/apt.log") ||
        die "apt-get download$missing failed: $(tail -n 1 "$VM_DIR/apt.log")"
}

unpack() {
    local abi=$1 stamp=$VM_DIR/x/.unpacked-$1
    [ -f "$stamp" ] && return 0
    rm -rf "$VM_DIR/x" && mkdir -p "$VM_DIR/x"
    local deb
    for deb in "$VM_DIR"/debs/linux-image-"$abi"_*.deb "$VM_DIR"/debs/linux-headers-"$abi"_*.deb \
        "$VM_DIR"/debs/linux-headers-"${abi%-amd64}"-common_*.deb "$VM_DIR"/debs/linux-kbuild-6.1_*.deb \
        "$VM_DIR"/debs/busybox-static_*.deb; do
        dpkg -x "$deb" "$VM_DIR/x" || die "dpkg -x $deb failed"
    done
    # the headers' Makefile includes the -common tree by its absolute /usr/src path
    local mk=$VM_DIR/x/usr/src/linux-headers-$abi/Makefile
    sed -i "s|^include /usr/src/|include $VM_DIR/x/usr/src/|" "$mk" || die "cannot edit $mk"
    touch "$stamp"
}

# The sources of vkms, gpio-sim and irq_sim from linux-source-6.1, patched.
extract_sources() {
    local src=$VM_DIR/src stamp=$VM_DIR/src/.extracted sum
    sum=$(cat tests/vm/patches/*.patch | md5sum)
    [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$sum" ] && return 0
    rm -rf "$src" && mkdir -p "$src"
    say "extracting vkms, gpio-sim and irq_sim from linux-source-6.1"
    dpkg --fsys-tarfile "$VM_DIR"/debs/linux-source-6.1_*.deb |
        tar -xO --wildcards './usr/src/linux-source-6.1.tar.xz' |
        tar -xJ -C "$src" --strip-components=1 --wildcards 'linux-source-6.1/drivers/gpu/drm/vkms/*' \
            'linux-source-6.1/drivers/gpio/gpio-sim.c' 'linux-source-6.1/drivers/gpio/gpiolib*.h' \
            'linux-source-6.1/kernel/irq/irq_sim.c' || die "extracting linux-source-6.1 failed"
    local p
    for p in tests/vm/patches/*.patch; do
        patch -s -d "$src" -p1 <"$p" || die "$p does not apply"
    done
    echo "$sum" >"$stamp"
}

# vkms.ko and gpio-sim.ko against the unpacked headers (kbuild, gcc-12).
build_modules() {
    local abi=$1 headers=$VM_DIR/x/usr/src/linux-headers-$1 mods=$VM_DIR/mods
    if [ -f "$mods/vkms/vkms.ko" ] && [ -f "$mods/gpio-sim/gpio-sim.ko" ] &&
        [ "$mods/vkms/vkms.ko" -nt "$VM_DIR/src/.extracted" ]; then
        return 0
    fi
    say "building vkms and gpio-sim for $abi"
    rm -rf "$mods" && mkdir -p "$mods/vkms" "$mods/gpio-sim"
    cp "$VM_DIR"/src/drivers/gpu/drm/vkms/*.[ch] "$mods/vkms/"
    printf 'obj-m += vkms.o\nvkms-y := vkms_drv.o vkms_plane.o vkms_output.o vkms_formats.o vkms_crtc.o vkms_composer.o vkms_writeback.o\n' \
        >"$mods/vkms/Kbuild"
    # gpio-sim needs irq_sim, which Debian's kernel does not build: link it into the module
    cp "$VM_DIR/src/drivers/gpio/gpio-sim.c" "$mods/gpio-sim/gpio-sim-main.c"
    cp "$VM_DIR"/src/drivers/gpio/gpiolib*.h "$VM_DIR/src/kernel/irq/irq_sim.c" "$mods/gpio-sim/"
    printf 'obj-m += gpio-sim.o\ngpio-sim-y := gpio-sim-main.o irq_sim.o\n' >"$mods/gpio-sim/Kbuild"
    local m
    for m in vkms gpio-sim; do
        make -C "$headers" M="$mods/$m" -j"$(nproc)" modules >"$mods/$m.log" 2>&1 ||
            die "building $m.ko failed: $(grep -m1 -i error "$mods/$m.log")"
    done
}

# The guest's module tree: Debian's (hard links) plus updates/.
module_tree() {
    local abi=$1 tree=$VM_DIR/modules
    if [ ! -d "$tree/kernel" ] || [ "$VM_DIR/mods/vkms/vkms.ko" -nt "$tree/modules.dep" ]; then
        rm -rf "$tree"
        cp -al "$VM_DIR/x/lib/modules/$abi" "$tree" 2>/dev/null || cp -a "$VM_DIR/x/lib/modules/$abi" "$tree"
        mkdir -p "$tree/updates"
        cp "$VM_DIR/mods/vkms/vkms.ko" "$VM_DIR/mods/gpio-sim/gpio-sim.ko" "$tree/updates/"
        # depmod wants BASE/lib/modules/VERSION: a symlink farm pointing at the tree
        local base=$VM_DIR/depmod-base
        rm -rf "$base" && mkdir -p "$base/lib/modules" && ln -s "$tree" "$base/lib/modules/$abi"
        /sbin/depmod -b "$base" "$abi" || die "depmod failed"
    fi
}

initramfs() {
    local abi=$1 dir=$VM_DIR/initrd
    [ -f "$VM_DIR/initrd.gz" ] && [ "$VM_DIR/initrd.gz" -nt tests/vm/init ] &&
        [ "$VM_DIR/initrd.gz" -nt "$VM_DIR/x/.unpacked-$abi" ] && return 0
    rm -rf "$dir" && mkdir -p "$dir/bin" "$dir/modules"
    cp "$VM_DIR/x/bin/busybox" "$dir/bin/" && cp tests/vm/init "$dir/init" && chmod +x "$dir/init"
    local m f
    for m in $INITRD_MODULES; do
        f=$(find "$VM_DIR/x/lib/modules/$abi/kernel" -name "$m.ko" | head -n 1)
        [ -n "$f" ] || die "module $m.ko not in linux-image-$abi"
        cp "$f" "$dir/modules/"
    done
    printf '%s\n' $INITRD_MODULES >"$dir/modules.order"
    (cd "$dir" && find . | "$VM_DIR/x/bin/busybox" cpio -o -H newc 2>/dev/null | gzip -1 >"$VM_DIR/initrd.gz") ||
        die "making the initramfs failed"
}

prepare() {
    command -v qemu-system-x86_64 >/dev/null || die "qemu-system-x86_64 missing (tools/deps.sh vm)"
    local tool
    for tool in sbfx-play tests/vm/pngdiff tests/vm/drm_state tests/vm/v4l2_ctrl tests/vm/alloc_count.so tests/vm/vblank_stress; do
        [ -f "$BUILD/$tool" ] || die "$BUILD/$tool is not built (make test-vm builds it)"
    done
    local abi
    abi=$(kernel_abi)
    [ -n "$abi" ] || die "cannot tell the kernel ABI (apt-cache depends linux-image-amd64; set KERNEL_ABI)"
    mkdir -p "$VM_DIR"
    echo "$abi" >"$VM_DIR/kernel-abi"
    if [ ! -f "$VM_DIR/x/.unpacked-$abi" ] || [ ! -f "$VM_DIR/src/.extracted" ]; then
        local version
        version=$(apt-cache show "linux-image-$abi" 2>/dev/null | sed -n 's/^Version: //p' | head -n 1)
        [ -n "$version" ] || die "linux-image-$abi is not in the apt lists (apt-get update?)"
        fetch "linux-image-$abi" "linux-headers-$abi" "linux-headers-${abi%-amd64}-common" \
            "linux-kbuild-6.1" "linux-source-6.1" busybox-static
    fi
    unpack "$abi"
    extract_sources
    build_modules "$abi"
    module_tree "$abi"
    initramfs "$abi"
    KERNEL=$VM_DIR/x/boot/vmlinuz-$abi
    ABI=$abi
}

# ---- the VM ------------------------------------------------------------------------------

# The monitor of a VM that ran past its time: every CPU's registers and the kernel addresses on
# its stack, named from the guest's /proc/kallsyms (kallsyms.txt, written by guest.sh after
# loading the modules; Debian's System.map is a stub). A VM where no
# process runs any more (a deadlock in a driver with interrupts off) tells nothing itself: this
# is the only way to see where its CPUs are.
monitor_dump() {
    local cpu off log=$VM_DIR/monitor.log
    : >"$VM_DIR/wedged.txt"
    for ((cpu = 0; cpu < VM_SMP; cpu++)); do
        off=$(($(stat -c %s "$log") + 1))
        printf 'cpu %d\ninfo registers\nx /96gx $sp\n' "$cpu" >&7
        sleep 2
        tail -c "+$off" "$log" >"$VM_DIR/monitor-cpu$cpu.txt"
        {
            printf 'CPU %d: %s\n' "$cpu" "$(grep -m1 -oE 'RFL=[0-9a-f]+' "$VM_DIR/monitor-cpu$cpu.txt" |
                awk '{v = substr($0, 5); printf "%s (interrupts %s)", $0, (index("2367abef", substr(v, length(v) - 2, 1)) ? "on" : "off")}')"
            grep -oE '(RIP=|0x)ffffffff[89a-f][0-9a-f]{7}' "$VM_DIR/monitor-cpu$cpu.txt" |
                sed 's/^RIP=//; s/^0x//' | symbolize | awk '$2 !~ /^\?/ && !seen[$2]++ {print "  " $2}' | head -n 24
        } >>"$VM_DIR/wedged.txt"
    done
}

# symbolize: kernel text addresses (16 hex digits) on stdin -> "address symbol+offset" in the
# same order, the symbols and the addresses sorted together as strings (same width: the same
# order as numbers).
symbolize() {
    { awk '{print $1, $2, $3 $4}' "$VM_DIR/out/kallsyms.txt" 2>/dev/null; awk '{print $1, "Q", NR}'; } |
        sort -s -k1,1 | awk '
        $2 == "Q" { if (sym != "") printf "%d %s %s %s\n", $3, $1, sym, base; next }
        { sym = $3; base = $1 }' | sort -n |
        while read -r _ addr sym base; do
            printf '%s %s+0x%x\n' "$addr" "$sym" $((0x$addr - 0x$base))
        done
}

wedged_report() {
    echo "# vm: the guest's CPUs when it was stopped (qemu's monitor: the instruction pointer, then"
    echo "# the kernel code addresses on the stack, innermost first; $VM_DIR/monitor-cpu*.txt):"
    sed 's/^/#   /' "$VM_DIR/wedged.txt"
}

# The logs the guest wrote into the share while it ran: what it was doing, the newest player
# log, the kernel's messages.
log_tails() {
    local out=$VM_DIR/out
    echo "# vm: last steps ($out/steps.txt):"
    tail -n 6 "$out/steps.txt" 2>/dev/null | sed 's/^/#   /'
    local newest
    newest=$(ls -t "$out"/logs/*.err 2>/dev/null | head -n 1)
    if [ -n "$newest" ]; then
        echo "# vm: newest player log ($newest):"
        grep -v -e 'failed to open vkms' -e 'failed to load driver' -e kmsro "$newest" | tail -n 8 | sed 's/^/#   /'
    fi
    echo "# vm: kernel log ($out/logs/dmesg.txt, $VM_DIR/kernel.log):"
    tail -n 12 "$out/logs/dmesg.txt" 2>/dev/null | sed 's/^/#   /'
}

boot() {
    local out=$VM_DIR/out mon=$VM_DIR/monitor
    rm -rf "$out" && mkdir -p "$out"
    rm -f "$mon.in" "$mon.out" "$VM_DIR/qemu.pid" "$VM_DIR/guest.log" "$VM_DIR"/monitor-cpu*.txt &&
        mkfifo "$mon.in" "$mon.out" && : >"$VM_DIR/guest.log"
    say "booting $ABI (TCG, $VM_SMP CPUs) for tests/vm/guest.sh${VM_TESTS:+ (only: $VM_TESTS)}"
    local tests=${VM_TESTS:-}
    qemu-system-x86_64 -machine q35 -accel tcg,thread=multi,tb-size=256 \
        -cpu qemu64 -m "$VM_MEM" -smp "$VM_SMP" -nodefaults -display none -no-reboot \
        -kernel "$KERNEL" -initrd "$VM_DIR/initrd.gz" -pidfile "$VM_DIR/qemu.pid" \
        -append "console=ttyS0 quiet loglevel=4 panic=-1 SBFX_GUEST=$ROOT/tests/vm/guest.sh SBFX_SRC=$ROOT SBFX_BUILD=$BUILD${tests:+ SBFX_VM_TESTS=${tests// /,}}${VBLANK_CYCLES:+ SBFX_VBLANK_CYCLES=$VBLANK_CYCLES}" \
        -serial "file:$VM_DIR/kernel.log" -serial stdio -monitor "pipe:$mon" \
        -virtfs local,path=/,mount_tag=hostroot,security_model=none,readonly=on,multidevs=remap \
        -virtfs "local,path=$VM_DIR/modules,mount_tag=modules,security_model=none,readonly=on" \
        -virtfs "local,path=$out,mount_tag=vmout,security_model=none" </dev/null >"$VM_DIR/guest.log" 2>&1 &
    local qemu=$!
    exec 7<>"$mon.in"
    cat "$mon.out" >"$VM_DIR/monitor.log" &
    local reader=$!
    tail -n +1 -f --pid="$qemu" "$VM_DIR/guest.log" &
    local tailer=$! deadline=$((SECONDS + VM_TIMEOUT))
    while kill -0 "$qemu" 2>/dev/null && [ "$SECONDS" -lt "$deadline" ]; do sleep 1; done
    VM_STATUS=0
    if kill -0 "$qemu" 2>/dev/null; then
        VM_STATUS=124
        monitor_dump
        kill "$qemu" 2>/dev/null
        sleep 2
        kill -KILL "$qemu" 2>/dev/null
    fi
    wait "$qemu" 2>/dev/null
    local rc=$?
    [ "$VM_STATUS" -eq 124 ] || VM_STATUS=$rc
    exec 7>&-
    kill "$reader" 2>/dev/null
    wait "$tailer" "$reader" 2>/dev/null
}

summarize() {
    local results=$VM_DIR/out/results.txt
    local passed=0 failed=0 skipped=0
    if [ -f "$results" ]; then
        passed=$(grep -c '^ok - ' "$results")
        failed=$(grep -c '^not ok - ' "$results")
        skipped=$(grep -c '^skip - ' "$results")
    fi
    if [ "$VM_STATUS" -eq 124 ] || [ "$VM_STATUS" -eq 137 ]; then
        echo "not ok - vm/timeout: the VM ran past $VM_TIMEOUT s in test '$(cat "$VM_DIR/out/current-test.txt" 2>/dev/null)' (logs: $VM_DIR/out/)"
        log_tails
        wedged_report
        failed=$((failed + 1))
    elif [ ! -f "$VM_DIR/out/exit-status" ]; then
        echo "not ok - vm/boot: the guest did not finish (exit $VM_STATUS); kernel log tail:"
        tail -n 15 "$VM_DIR/kernel.log" | sed 's/^/#   /'
        failed=$((failed + 1))
    elif [ "$(cat "$VM_DIR/out/exit-status")" != 0 ] || [ $((passed + failed + skipped)) -eq 0 ]; then
        # the guest script could not run (not found, crashed early): never a silent pass
        echo "not ok - vm/guest: the guest script exited $(cat "$VM_DIR/out/exit-status") after" \
             "$((passed + failed + skipped)) results; its output: $VM_DIR/guest.log"
        tail -n 5 "$VM_DIR/guest.log" | sed 's/^/#   /'
        failed=$((failed + 1))
    fi
    say "$((SECONDS - start)) s in all"
    if [ "$skipped" -gt 0 ]; then
        echo "$passed passed, $failed failed, $skipped skipped"
    else
        echo "$passed passed, $failed failed"
    fi
    [ "$failed" -eq 0 ]
}

prepare
say "ready after $((SECONDS - start)) s"
boot
summarize
