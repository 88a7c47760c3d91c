#!/usr/bin/env bash
# MQTT triggers into sbfx-play (issue 35, docs/triggers.md): a real mosquitto broker started here
# on a free port (not 1883: other sessions may test at the same time), mosquitto_pub and
# mosquitto_sub as the clients, `sbfx-play --mqtt 127.0.0.1:PORT` headless on tests/net/range.cfg:
#   - "online" is retained on the status topic once the player is connected;
#   - a message EFFECT@X,Y,Z sets off its effect there (trigger_log, source "mqtt");
#   - the same effect again within the rate limit is refused (triggers_refused);
#   - a payload that is not EFFECT[@X,Y,Z], and one naming an effect the scene lacks, are counted
#     (mqtt_malformed) and logged;
#   - the broker killed and started again on the same port: the player logs the loss and the
#     reconnect, counts it (mqtt_reconnects), renders on meanwhile, and the next message works;
#   - SIGTERM: "offline" published, exit status 0; SIGKILL: "offline" as the last will.
# Skipped, saying why, without mosquitto and its clients. Every wait is bounded.
# Usage: tests/mqtt.sh [BUILD] (default build). Prints ok/not ok/skip lines.
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
PLAYER=$BUILD/sbfx-play
SUITE=mqtt
WAIT_S=${MQTT_WAIT_S:-30}
. tests/net/common.sh

for tool in mosquitto mosquitto_pub mosquitto_sub; do
    if ! command -v "$tool" >/dev/null 2>&1 && [ ! -x "/usr/sbin/$tool" ]; then
        echo "skip - $SUITE/all: $tool is not installed (tools/deps.sh test installs mosquitto and mosquitto-clients)"
        exit 0
    fi
done
MOSQUITTO=$(command -v mosquitto || echo /usr/sbin/mosquitto)
[ -x "$PLAYER" ] || { fail built "$PLAYER was not built"; exit 1; }

# start_broker [again]: mosquitto on 127.0.0.1, on a free port (again: on $port once more).
start_broker() {
    local tries
    for tries in 1 2 3 4 5 6 7 8 9 10; do
        [ "${1:-}" = again ] || port=$(free_port tcp)
        printf 'listener %d 127.0.0.1\nallow_anonymous true\npersistence false\n' "$port" >"$tmp/broker.conf"
        "$MOSQUITTO" -c "$tmp/broker.conf" >>"$tmp/broker.log" 2>&1 &
        broker=$!
        local deadline=$(($(now_ms) + 5000))
        while kill -0 "$broker" 2>/dev/null && [ "$(now_ms)" -lt "$deadline" ]; do
            mosquitto_pub -h 127.0.0.1 -p "$port" -t sbfx/probe -n 2>/dev/null && return 0
            sleep 0.1
        done
        kill -KILL "$broker" 2>/dev/null
        wait "$broker" 2>/dev/null
        broker=""
        [ "${1:-}" = again ] && sleep 0.5 # the same port: the old socket may linger
    done
    return 1
}

stop_broker() {
    kill -TERM "$broker"
    wait "$broker" 2>/dev/null
    broker=""
}

pub() { mosquitto_pub -h 127.0.0.1 -p "$port" -q 1 "$@"; }
# status: the retained message on the status topic (empty when none comes within 3 s).
status() { mosquitto_sub -h 127.0.0.1 -p "$port" -t sbfx/status -C 1 -W 3 2>/dev/null; }

# start_player NAME: sbfx-play --mqtt in the background, until it says it is connected.
start_player() {
    out=$tmp/$1
    mkdir -p "$out"
    "$PLAYER" --scene tests/net/range.cfg --no-timeline --size 64x36 --fps 10 --frames 100000 --out "$out" \
        --stats "$out/stats.json" --mqtt "127.0.0.1:$port" >"$out/log" 2>"$out/err" &
    pid=$!
    if ! until_log "$out/err" 'mqtt: connected to'; then
        fail "$1" "the player did not connect: $(head -c 300 "$out/err")"
        return 1
    fi
}

frames() { ls "$out" | grep -c '^frame-'; }
json() { json_number "$out/stats.json" "$1"; }

if ! start_broker; then
    fail broker "mosquitto did not start: $(tail -n 3 "$tmp/broker.log" | tr '\n' ' ')"
    exit 1
fi

test_triggers() {
    start_player triggers || return
    local s
    s=$(status)
    [ "$s" = online ] && ok "online (retained on sbfx/status)" || fail online "the status topic holds '$s'"
    pub -t sbfx/trigger -m 'blast@1,2,3'
    printf 'airburst@5,0,0\nairburst@6,0,0\n' | pub -t sbfx/trigger -l # back to back: the second within 250 ms
    pub -t sbfx/trigger -m 'boom boom'
    pub -t sbfx/trigger -m 'nosuch@0,0,0'
    until_log "$out/err" "a bad payload 'nosuch@0,0,0'"
    # the broker goes away and comes back on the same port
    local before
    before=$(frames)
    stop_broker
    until_log "$out/err" 'mqtt: lost the broker at' || fail reconnect "no loss logged: $(tail -n 2 "$out/err")"
    sleep 1
    local during
    during=$(frames)
    start_broker again || fail reconnect "mosquitto did not start again on port $port"
    if until_log "$out/err" 'mqtt: reconnected to'; then
        pub -t sbfx/trigger -m 'dust@0,0,-3'
        sleep 0.6
    fi
    kill -TERM "$pid"
    local rc=0
    wait "$pid" || rc=$?
    pid=""
    s=$(status)
    [ $rc -eq 0 ] && [ "$s" = offline ] && ok "stopped (SIGTERM: exit 0, 'offline' published)" ||
        fail stopped "exit status $rc, the status topic holds '$s'"

    local log
    log=$(grep -o '"trigger_log": \[.*\]' "$out/stats.json")
    if echo "$log" | grep -q '{"source": "mqtt", "effect": "blast", "at": \[1, 2, 3\]' &&
        echo "$log" | grep -q '{"source": "mqtt", "effect": "airburst", "at": \[5, 0, 0\]'; then
        ok "message (blast@1,2,3 and airburst@5,0,0 set off there, source mqtt)"
    else
        fail message "trigger_log: $log"
    fi
    if ! echo "$log" | grep -q '"at": \[6, 0, 0\]' && [ "$(json triggers_refused)" -ge 1 ]; then
        ok "rate-limit (airburst again within 250 ms: refused, triggers_refused $(json triggers_refused))"
    else
        fail rate-limit "triggers_refused $(json triggers_refused); trigger_log: $log"
    fi
    if [ "$(json mqtt_malformed)" = 2 ] && grep -q "a bad payload 'boom boom': the effect name must be" "$out/err" &&
        grep -q "a bad payload 'nosuch@0,0,0': the scene has no effect 'nosuch' (its effects: blast, airburst, dust)" "$out/err"; then
        ok "bad-payloads (mqtt_malformed 2, each logged with why)"
    else
        fail bad-payloads "mqtt_malformed $(json mqtt_malformed): $(grep 'bad payload' "$out/err" | tr '\n' ';')"
    fi
    if [ "$(json mqtt_reconnects)" = 1 ] && grep -q 'mqtt: reconnected to 127.0.0.1:'"$port"' after' "$out/err" &&
        echo "$log" | grep -q '{"source": "mqtt", "effect": "dust", "at": \[0, 0, -3\]' && [ "$during" -gt "$before" ]; then
        ok "reconnect (broker restarted: logged, mqtt_reconnects 1, frames $before to $during meanwhile, the next message set off)"
    else
        fail reconnect "mqtt_reconnects $(json mqtt_reconnects), frames $before -> $during, log: $(grep 'mqtt:' "$out/err" | tr '\n' ';' | cut -c 1-300)"
    fi
    [ "$(json mqtt_messages)" = 6 ] && ok "counted (mqtt_messages 6)" || fail counted "mqtt_messages $(json mqtt_messages), want 6"
}

test_last_will() {
    start_player will || return
    local s
    s=$(status)
    kill -KILL "$pid"
    wait "$pid" 2>/dev/null
    pid=""
    local deadline=$(($(now_ms) + 5000)) after=""
    while [ "$(now_ms)" -lt "$deadline" ]; do
        after=$(status)
        [ "$after" = offline ] && break
    done
    [ "$s" = online ] && [ "$after" = offline ] && ok "last-will (killed: the broker published 'offline')" ||
        fail last-will "before the kill '$s', after '$after'"
}

test_triggers
test_last_will
stop_broker
exit $((failures > 0))
