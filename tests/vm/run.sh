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
#   initrd.gz, kernel.log (ttyS0), guest.log (ttyS1), out/ (the guest's writable share)
#
# Environment: BUILD (build), VM_DIR (build/vm), VM_TIMEOUT (seconds for the VM, 420: a guard
# against hangs; the tests take about two minutes on two cores),
# VM_SMP (2), VM_MEM (1536M), KERNEL_ABI (e.g. 6.1.0-56-amd64; default: what linux-image-amd64
# depends on, remembered in $VM_DIR/kernel-abi).
set -u
cd "$(dirname "$0")/../.." || exit 1
ROOT=$PWD
BUILD=${BUILD:-build}
case $BUILD in /*) ;; *) BUILD=$ROOT/$BUILD ;; esac
VM_DIR=${VM_DIR:-$ROOT/build/vm}
VM_TIMEOUT=${VM_TIMEOUT:-420}
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
    for tool in sbfx-play tests/vm/pngdiff tests/vm/drm_state tests/vm/v4l2_ctrl tests/vm/alloc_count.so; do
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

boot() {
    local out=$VM_DIR/out
    rm -rf "$out" && mkdir -p "$out"
    say "booting $ABI (TCG, $VM_SMP CPUs) for tests/vm/guest.sh"
    timeout -k 10 "$VM_TIMEOUT" qemu-system-x86_64 -machine q35 -accel tcg,thread=multi,tb-size=256 \
        -cpu qemu64 -m "$VM_MEM" -smp "$VM_SMP" -nodefaults -display none -no-reboot \
        -kernel "$KERNEL" -initrd "$VM_DIR/initrd.gz" \
        -append "console=ttyS0 quiet loglevel=4 panic=-1 SBFX_GUEST=$ROOT/tests/vm/guest.sh SBFX_SRC=$ROOT SBFX_BUILD=$BUILD" \
        -serial "file:$VM_DIR/kernel.log" -serial stdio \
        -virtfs local,path=/,mount_tag=hostroot,security_model=none,readonly=on,multidevs=remap \
        -virtfs "local,path=$VM_DIR/modules,mount_tag=modules,security_model=none,readonly=on" \
        -virtfs "local,path=$out,mount_tag=vmout,security_model=none" </dev/null | tee "$VM_DIR/guest.log"
    VM_STATUS=${PIPESTATUS[0]}
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
        echo "not ok - vm/timeout: the VM ran past $VM_TIMEOUT s (kernel log: $VM_DIR/kernel.log)"
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
