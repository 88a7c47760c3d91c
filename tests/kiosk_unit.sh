#!/usr/bin/env bash
# The kiosk's deployment files (dist/, docs/kiosk-deploy.md) as `make install` writes them
# (PREFIX=/usr into a temporary DESTDIR):
#   - scenes and board profiles under share/sbfx; the unit, udev rule and sysusers.d file;
#   - the unit's paths filled in and pointing at installed files; systemd-analyze verify;
#   - exposure <= 1.0 by `systemd-analyze security --offline=true` (systemd's own scoring);
#   - no network (AF_UNIX only); the network drop-in for DIS and MQTT opens AF_INET only and keeps
#     the exposure <= 1.5;
#   - what the kiosk relies on: Type=notify with a watchdog, restarts that never give up,
#     devices by DevicePolicy=closed + DeviceAllow= (DRM, V4L2, GPIO; no private /dev), a shader
#     cache directory, every Wants= also ordered by After=;
#   - the udev rule's group is the one the sysusers.d file makes (run by systemd-sysusers
#     --root on the staged tree) and the one the unit runs in.
# Usage: tests/kiosk_unit.sh [BUILD] (default build). Prints ok/not ok lines.
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
root=$tmp/root
unit=$root/usr/lib/systemd/system/sbfx-kiosk.service
rule=$root/usr/lib/udev/rules.d/60-sbfx-gpio.rules
sysusers=$root/usr/lib/sysusers.d/sbfx.conf

failed=0
ok() { echo "ok - kiosk-unit/$1"; }
not_ok() { echo "not ok - kiosk-unit/$1: $2"; failed=1; }

if ! make --no-print-directory -s BUILD="$BUILD" DESTDIR="$root" PREFIX=/usr install >"$tmp/log" 2>&1; then
    not_ok install "make install failed: $(tail -n 3 "$tmp/log" | tr '\n' ' ')"
    exit 1
fi
missing=""
for f in "$unit" "$rule" "$sysusers" "$root"/usr/share/sbfx/boards/rk3588.cfg \
    "$root"/usr/share/sbfx/scenes/explosion.cfg "$root"/usr/bin/sbfx-play; do
    [ -f "$f" ] || missing="$missing ${f#"$root"}"
done
n_scenes=$(ls "$root"/usr/share/sbfx/scenes/*.cfg 2>/dev/null | wc -l)
n_boards=$(ls "$root"/usr/share/sbfx/boards/*.cfg 2>/dev/null | wc -l)
if [ -n "$missing" ]; then not_ok installed "missing:$missing"
elif [ "$n_scenes" -ne "$(ls scenes/*.cfg | wc -l)" ] || [ "$n_boards" -ne "$(ls boards/*.cfg | wc -l)" ]; then
    not_ok installed "$n_scenes scenes, $n_boards boards installed"
else ok "installed ($n_scenes scenes, $n_boards board profiles, unit, udev rule, sysusers.d)"; fi
[ -f "$unit" ] || exit 1

# value KEY: the unit's values of KEY, one a line (every assignment, in order)
value() { sed -n "s/^$1=//p" "$unit"; }

# paths: nothing left to substitute; ExecStart and the default board and scene exist
left=$(grep -o '@[A-Z]*@' "$unit" | sort -u | tr '\n' ' ')
exec_bin=$(value ExecStart | awk '{print $1}')
board=$(value Environment | sed -n 's/^SBFX_BOARD=//p')
scene=$(value Environment | sed -n 's/^SBFX_SCENE=//p')
if [ -n "$left" ]; then not_ok paths "placeholders left: $left"
elif [ "$exec_bin" != /usr/bin/sbfx-play ] || [ ! -x "$root$exec_bin" ]; then not_ok paths "ExecStart runs '$exec_bin'"
elif [ ! -f "$root$board" ] || [ ! -f "$root$scene" ]; then not_ok paths "board '$board' or scene '$scene' not installed"
else ok "paths (ExecStart=$exec_bin, board $board, scene $scene)"; fi

if ! command -v systemd-analyze >/dev/null 2>&1; then
    not_ok verify "systemd-analyze not found (tools/deps.sh test installs systemd)"
    not_ok exposure "systemd-analyze not found (tools/deps.sh test installs systemd)"
else
    # verify with the staged binary in place of /usr/bin (systemd checks that it exists)
    mkdir -p "$tmp/verify"
    sed "s|=/usr/bin/sbfx-play|=$root/usr/bin/sbfx-play|" "$unit" >"$tmp/verify/sbfx-kiosk.service"
    if systemd-analyze verify --man=no "$tmp/verify/sbfx-kiosk.service" >"$tmp/verify.log" 2>&1 &&
        [ ! -s "$tmp/verify.log" ]; then ok verify
    else not_ok verify "$(head -n 3 "$tmp/verify.log" | tr '\n' ' ')"; fi

    systemd-analyze security --offline=true "$unit" >"$tmp/security.log" 2>&1
    level=$(sed -n 's/.*Overall exposure level for sbfx-kiosk.service: \([0-9.]*\).*/\1/p' "$tmp/security.log")
    if [ -z "$level" ]; then not_ok exposure "no exposure level: $(tail -n 2 "$tmp/security.log" | tr '\n' ' ')"
    elif awk -v l="$level" 'BEGIN { exit !(l <= 1.0) }'; then ok "exposure ($level <= 1.0, systemd-analyze security --offline=true)"
    else not_ok exposure "$level > 1.0: $(grep '✗' "$tmp/security.log" | awk '{print $2}' | tr '\n' ' ')"; fi
fi

# Triggers from the network (docs/triggers.md): the unit has none (AF_UNIX only, PrivateNetwork=yes);
# the drop-in make install puts in share/sbfx/systemd/ opens IPv4 only (AF_INET, no AF_INET6,
# AF_PACKET or AF_NETLINK) to the networks it names, and the unit with it still rates 1.5 or less.
dropin=$root/usr/share/sbfx/systemd/network.conf
families() { sed -n 's/^RestrictAddressFamilies=//p' "$@" | tr ' ' '\n' | sort -u | tr '\n' ' '; }
if [ "$(families "$unit")" != "AF_UNIX " ] || [ "$(value PrivateNetwork)" != yes ]; then
    not_ok network "the unit allows '$(families "$unit")', PrivateNetwork=$(value PrivateNetwork): want AF_UNIX and yes"
elif [ ! -f "$dropin" ] || grep -q '@[A-Z]*@' "$dropin"; then
    not_ok network "$dropin not installed, or placeholders left in it"
elif [ "$(families "$unit" "$dropin")" != "AF_INET AF_UNIX " ]; then
    not_ok network "with the drop-in the families are '$(families "$unit" "$dropin")': want AF_UNIX and AF_INET only"
elif ! command -v systemd-analyze >/dev/null 2>&1; then
    not_ok network "systemd-analyze not found (tools/deps.sh test installs systemd)"
else
    mkdir -p "$root/etc/systemd/system/sbfx-kiosk.service.d" "$tmp/verify/sbfx-kiosk.service.d"
    cp "$dropin" "$root/etc/systemd/system/sbfx-kiosk.service.d/"
    cp "$dropin" "$tmp/verify/sbfx-kiosk.service.d/"
    systemd-analyze security --offline=true --root="$root" sbfx-kiosk.service >"$tmp/netsec.log" 2>&1
    level=$(sed -n 's/.*Overall exposure level for sbfx-kiosk.service: \([0-9.]*\).*/\1/p' "$tmp/netsec.log")
    if ! systemd-analyze verify --man=no "$tmp/verify/sbfx-kiosk.service" >"$tmp/netverify.log" 2>&1 ||
        [ -s "$tmp/netverify.log" ]; then
        not_ok network "verify with the drop-in: $(head -n 3 "$tmp/netverify.log" | tr '\n' ' ')"
    elif [ -n "$level" ] && awk -v l="$level" 'BEGIN { exit !(l <= 1.5) }'; then
        ok "network (the unit: AF_UNIX, no network; with share/sbfx/systemd/network.conf: AF_INET to the networks named, exposure $level <= 1.5)"
    else
        not_ok network "with the drop-in: exposure '$level' > 1.5: $(grep '✗' "$tmp/netsec.log" | awk '{print $2}' | tr '\n' ' ')"
    fi
fi

# what the kiosk relies on
[ "$(value Type)" = notify ] && [ -n "$(value WatchdogSec)" ] && [ "$(value NotifyAccess)" = main ] &&
    ok "watchdog (Type=notify, WatchdogSec=$(value WatchdogSec))" ||
    not_ok watchdog "Type=$(value Type) WatchdogSec=$(value WatchdogSec) NotifyAccess=$(value NotifyAccess)"
# systemctl reload: SIGHUP to the player, which reloads its scene (platform/player/inputs/signals.c)
if [ "$(value ExecReload)" = '/bin/kill -HUP $MAINPID' ] && grep -q 'catch_signal(SIGHUP' platform/player/inputs/signals.c; then
    ok "reload (ExecReload=$(value ExecReload))"
else not_ok reload "ExecReload='$(value ExecReload)': want '/bin/kill -HUP \$MAINPID' (sbfx-play reloads on SIGHUP)"; fi
restart_sec=$(value RestartSec | sed 's/s$//')
if [ "$(value StartLimitIntervalSec)" = 0 ] && [ "$(value Restart)" = always ] &&
    awk -v r="$restart_sec" 'BEGIN { exit !(r >= 1 && r <= 30) }'; then
    ok "restarts (Restart=always, RestartSec=$(value RestartSec), StartLimitIntervalSec=0)"
else
    not_ok restarts "Restart=$(value Restart) RestartSec=$(value RestartSec) StartLimitIntervalSec=$(value StartLimitIntervalSec)"
fi
devices=$(value DeviceAllow | tr '\n' ',')
if [ "$(value DevicePolicy)" = closed ] && [ "$devices" = "char-drm rw,char-video4linux rw,char-gpiochip rw," ] &&
    [ -z "$(value PrivateDevices)" ]; then ok "devices (DevicePolicy=closed; $devices no PrivateDevices=)"
else not_ok devices "DevicePolicy=$(value DevicePolicy) DeviceAllow=$devices PrivateDevices=$(value PrivateDevices)"; fi
cache=$(value CacheDirectory)
if [ -n "$cache" ] && value Environment | tr ' ' '\n' | grep -qx "MESA_SHADER_CACHE_DIR=%C/$cache"; then
    ok "shader-cache (CacheDirectory=$cache, MESA_SHADER_CACHE_DIR=%C/$cache)"
else not_ok shader-cache "CacheDirectory=$cache; $(value Environment | tr '\n' ' ')"; fi
wants=$(value Wants | tr ' ' '\n' | grep -v '^$')
after=$(value After | tr ' ' '\n')
unordered=$(for w in $wants; do printf '%s\n' "$after" | grep -qx "$w" || echo "$w"; done | tr '\n' ' ')
if [ -z "$wants" ]; then not_ok wants-after "no Wants="
elif [ -n "$unordered" ]; then not_ok wants-after "wanted but not ordered: $unordered"
else ok "wants-after ($(echo $wants) also in After=)"; fi

# the group: udev rule = sysusers.d = SupplementaryGroups, and systemd-sysusers makes it
rule_group=$(sed -n 's/.*GROUP="\([^"]*\)".*/\1/p' "$rule")
made=$(awk '$1 == "g" {print $2}' "$sysusers")
mkdir -p "$root/etc"
if [ -z "$rule_group" ] || [ "$rule_group" != "$made" ]; then not_ok gpio-group "udev rule's group '$rule_group', sysusers.d's '$made'"
elif ! value SupplementaryGroups | tr ' ' '\n' | grep -qx "$rule_group"; then not_ok gpio-group "the unit does not run in group $rule_group"
elif command -v systemd-sysusers >/dev/null 2>&1 && ! { systemd-sysusers --root="$root" sbfx.conf >/dev/null 2>&1 &&
    grep -q "^$rule_group:" "$root/etc/group"; }; then not_ok gpio-group "systemd-sysusers did not make group $rule_group"
else ok "gpio-group ($rule_group: udev rule, sysusers.d, SupplementaryGroups)"; fi

# The Wayland kiosk's units (docs/kiosk-deploy.md "Wayland"): cage on tty1 (system) and a client of
# the session's compositor (user): installed with their paths, verified, restarted on the
# compositor going away (sbfx-play exits 69), the cage unit hardened as far as a compositor on a
# seat allows (its seat's devices through logind: no DevicePolicy=), its user made by sysusers.
cage_unit=$root/usr/lib/systemd/system/sbfx-kiosk-cage.service
user_unit=$root/usr/lib/systemd/user/sbfx-kiosk-wayland.service
uvalue() { sed -n "s/^$2=//p" "$1"; }
if [ ! -f "$cage_unit" ] || [ ! -f "$user_unit" ]; then
    not_ok wayland-units "not installed: $cage_unit $user_unit"
elif grep -q '@[A-Z]*@' "$cage_unit" "$user_unit"; then
    not_ok wayland-units "placeholders left: $(grep -ho '@[A-Z]*@' "$cage_unit" "$user_unit" | sort -u | tr '\n' ' ')"
elif ! uvalue "$cage_unit" ExecStart | grep -q -- "-- /usr/bin/sbfx-play --display wayland" ||
    ! uvalue "$user_unit" ExecStart | grep -q -- "^/usr/bin/sbfx-play --display wayland"; then
    not_ok wayland-units "ExecStart: $(uvalue "$cage_unit" ExecStart) / $(uvalue "$user_unit" ExecStart)"
elif [ "$(uvalue "$cage_unit" Restart)" != always ] || [ "$(uvalue "$user_unit" Restart)" != on-failure ] ||
    uvalue "$user_unit" RestartPreventExitStatus | grep -qw 69; then
    not_ok wayland-units "restarts: cage Restart=$(uvalue "$cage_unit" Restart), user Restart=$(uvalue "$user_unit" Restart)"
else
    ok "wayland-units (sbfx-kiosk-cage.service: cage -- sbfx-play, Restart=always; user sbfx-kiosk-wayland.service: Restart=on-failure restarts on 69)"
fi
if command -v systemd-analyze >/dev/null 2>&1 && [ -f "$cage_unit" ] && [ -f "$user_unit" ]; then
    mkdir -p "$tmp/wverify"
    for u in "$cage_unit" "$user_unit"; do
        sed "s|/usr/bin/sbfx-play|$root/usr/bin/sbfx-play|" "$u" >"$tmp/wverify/$(basename "$u")"
    done
    if systemd-analyze verify --man=no "$tmp/wverify/"*.service >"$tmp/wverify.log" 2>&1 && [ ! -s "$tmp/wverify.log" ]; then
        ok wayland-verify
    else not_ok wayland-verify "$(head -n 3 "$tmp/wverify.log" | tr '\n' ' ')"; fi
    systemd-analyze security --offline=true "$cage_unit" >"$tmp/wsecurity.log" 2>&1
    level=$(sed -n 's/.*Overall exposure level for sbfx-kiosk-cage.service: \([0-9.]*\).*/\1/p' "$tmp/wsecurity.log")
    if [ -n "$level" ] && awk -v l="$level" 'BEGIN { exit !(l <= 1.5) }'; then ok "wayland-exposure ($level <= 1.5)"
    else not_ok wayland-exposure "'$level' > 1.5: $(grep '✗' "$tmp/wsecurity.log" | awk '{print $2}' | tr '\n' ' ')"; fi
    # the user unit, hardened as far as a user manager allows (tests/wayland.sh starts it in one)
    systemd-analyze security --offline=true "$user_unit" >"$tmp/usecurity.log" 2>&1
    level=$(sed -n 's/.*Overall exposure level for sbfx-kiosk-wayland.service: \([0-9.]*\).*/\1/p' "$tmp/usecurity.log")
    if [ -n "$level" ] && awk -v l="$level" 'BEGIN { exit !(l <= 2.5) }'; then ok "user-unit-exposure ($level <= 2.5)"
    else not_ok user-unit-exposure "'$level' > 2.5: $(grep '✗' "$tmp/usecurity.log" | awk '{print $2}' | tr '\n' ' ')"; fi
fi
if [ "$(uvalue "$cage_unit" User)" = sbfx ] && grep -q '^u sbfx ' "$sysusers" && { ! command -v systemd-sysusers >/dev/null 2>&1 ||
    grep -q '^sbfx:' "$root/etc/passwd"; }; then ok "wayland-user (sbfx, made by sysusers.d)"
else not_ok wayland-user "User=$(uvalue "$cage_unit" User); sysusers.d: $(grep '^u' "$sysusers")"; fi
exit "$failed"
