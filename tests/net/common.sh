# Sourced by tests/dis.sh, cigi.sh, cigi_play.sh, load.sh and mqtt.sh (with SUITE set): result
# lines, a temporary folder cleaned up with the processes the test started ($pid, $broker), bounded
# waits, free ports, stopping the player, positions within 1 cm.

failures=0
tmp=$(mktemp -d)
pid="" broker=""
cleanup() {
    [ -n "$pid" ] && kill -KILL "$pid" 2>/dev/null
    [ -n "$broker" ] && kill -KILL "$broker" 2>/dev/null
    rm -rf "$tmp"
}
trap cleanup EXIT

ok() { echo "ok - $SUITE/$1"; }
fail() {
    echo "not ok - $SUITE/$1: $2"
    failures=$((failures + 1))
}

now_ms() { date +%s%3N; }

# until_log FILE PATTERN: until FILE holds a line matching PATTERN (0), or WAIT_S pass or the
# player ($pid) exits first (1).
until_log() {
    local deadline=$(($(now_ms) + WAIT_S * 1000))
    until grep -q -- "$2" "$1" 2>/dev/null; do
        [ "$(now_ms)" -gt "$deadline" ] && return 1
        [ -n "$pid" ] && ! kill -0 "$pid" 2>/dev/null && ! grep -q -- "$2" "$1" 2>/dev/null && return 1
        sleep 0.05
    done
}

# free_port udp|tcp: a port no socket on this machine holds (other sessions test at the same time).
free_port() {
    local port
    while :; do
        port=$((20000 + RANDOM % 40000))
        grep -qi ":$(printf '%04X' "$port") " "/proc/net/$1" "/proc/net/${1}6" 2>/dev/null || break
    done
    echo "$port"
}

# json FILE KEY: a number of a --stats file.
json_number() { grep -o "\"$2\": [0-9]*" "$1" | grep -o '[0-9]*$'; }

# stop: SIGTERM to the player ($pid: the run ends after its frame and writes its stats); its exit
# status.
stop() {
    kill -TERM "$pid"
    local rc=0
    wait "$pid" || rc=$?
    pid=""
    return $rc
}

# near3 X Y Z WANT_X WANT_Y WANT_Z: within 1 cm (an effect placed where its message said).
near3() {
    awk -v x="$1" -v y="$2" -v z="$3" -v a="$4" -v b="$5" -v c="$6" \
        'BEGIN { d = sqrt((x-a)^2 + (y-b)^2 + (z-c)^2); exit !(d <= 0.01) }'
}
