/* Where network triggers are configured: --dis, --dis-exercise, --mqtt, --mqtt-topic
 * (player/options/args.c), the board profile's mqtt and dis groups (options/board.c), the scene's dis group
 * (net/dis/dis_config.c). Every error names the flag, or the file, the line and the key. */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "net/dis/dis_config.h"
#include "player/options/board.h"
#include "player/options/options.h"

static const char *write_temp(const char *text)
{
    static char path[64];
    snprintf(path, sizeof(path), "/tmp/sbfx-net-%d.cfg", (int)getpid());
    FILE *f = fopen(path, "w");
    if (!f) return NULL;
    fputs(text, f);
    fclose(f);
    return path;
}

/* ---- flags ---- */

static int parse(struct player_options *opt, char *err, size_t n, const char *a, const char *b)
{
    char *argv[] = {"sbfx-play", (char *)a, (char *)b, NULL};
    player_options_defaults(opt);
    return player_parse_args(opt, 3, argv, err, n);
}

CHECK_TEST(network_flags)
{
    static struct player_options opt;
    char err[512] = "";
    CHECK(parse(&opt, err, sizeof(err), "--dis", "3000") == 0 && strcmp(opt.dis, "3000") == 0, "%s", err);
    CHECK(parse(&opt, err, sizeof(err), "--dis", "239.1.2.3:3000") == 0, "%s", err);
    CHECK(parse(&opt, err, sizeof(err), "--dis-exercise", "12") == 0 && opt.dis_exercise == 12, "%s", err);
    CHECK(parse(&opt, err, sizeof(err), "--mqtt", "broker.local") == 0 && strcmp(opt.mqtt, "broker.local") == 0);
    CHECK(parse(&opt, err, sizeof(err), "--mqtt", "[fd00::2]:8883") == 0, "%s", err);
    CHECK(parse(&opt, err, sizeof(err), "--mqtt-topic", "site/+/trigger") == 0 && strcmp(opt.mqtt_topic, "site/+/trigger") == 0);
    const char *bad[][3] = {{"--dis", "0", "--dis: expected [ADDR:]PORT"},
                            {"--dis", "70000", "--dis: expected [ADDR:]PORT"},
                            {"--dis", "host.local:3000", "--dis: expected [ADDR:]PORT"},
                            {"--dis", "1.2.3.4:", "--dis: expected [ADDR:]PORT"},
                            {"--dis-exercise", "0", "--dis-exercise: expected an exercise ID 1..255"},
                            {"--dis-exercise", "256", "--dis-exercise: expected an exercise ID 1..255"},
                            {"--mqtt", ":1883", "--mqtt: expected HOST[:PORT]"},
                            {"--mqtt", "broker:0", "--mqtt: expected HOST[:PORT]"},
                            {"--mqtt", "[fd00::2", "--mqtt: expected HOST[:PORT]"},
                            {"--mqtt-topic", "", "--mqtt-topic: expected a topic"}};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
        err[0] = '\0';
        CHECK(parse(&opt, err, sizeof(err), bad[i][0], bad[i][1]) == -EINVAL, "%s %s accepted", bad[i][0], bad[i][1]);
        CHECK(strstr(err, bad[i][2]) != NULL, "%s %s: %s", bad[i][0], bad[i][1], err);
    }
}

CHECK_TEST(addresses)
{
    struct udp_endpoint e;
    char err[256], host[256];
    int port = -1;
    CHECK(udp_endpoint_parse("3000", &e, err, sizeof(err)) == 0 && e.port == 3000 && e.addr.s_addr == 0 && !e.multicast);
    CHECK(udp_endpoint_parse("239.1.2.3:3001", &e, err, sizeof(err)) == 0 && e.port == 3001 && e.multicast);
    CHECK(udp_endpoint_parse("192.168.1.255:3000", &e, err, sizeof(err)) == 0 && !e.multicast);
    CHECK(mqtt_endpoint_parse("broker", host, sizeof(host), &port, err, sizeof(err)) == 0 && port == 0 &&
          strcmp(host, "broker") == 0);
    CHECK(mqtt_endpoint_parse("10.0.0.2:1884", host, sizeof(host), &port, err, sizeof(err)) == 0 && port == 1884 &&
          strcmp(host, "10.0.0.2") == 0);
    CHECK(mqtt_endpoint_parse("[::1]:8883", host, sizeof(host), &port, err, sizeof(err)) == 0 && port == 8883 &&
          strcmp(host, "::1") == 0);
    CHECK(mqtt_endpoint_parse("::1", host, sizeof(host), &port, err, sizeof(err)) == 0 && port == 0 &&
          strcmp(host, "::1") == 0, "a bare IPv6 literal");
}

/* ---- the board's mqtt and dis groups ---- */

static const char *load_board(const char *text, struct board_profile *b)
{
    static char err[512];
    err[0] = '\0';
    const char *path = write_temp(text);
    board_load(path, b, err, sizeof(err));
    remove(path);
    return err;
}

CHECK_TEST(board_mqtt_and_dis)
{
    static struct board_profile b;
    const char *err = load_board(
        "mqtt = { host = \"broker.lan\"; port = 8883; topic = \"hall/+/boom\"; status_topic = \"hall/kiosk1\";\n"
        "  username = \"kiosk1\"; password_file = \"/etc/sbfx/mqtt.pass\"; ca_file = \"/etc/sbfx/ca.pem\";\n"
        "  min_interval_ms = 1000; };\n"
        "dis = { listen = \"239.1.2.3:3000\"; interface = \"eth1\"; };\n", &b);
    CHECK(!err[0], "%s", err);
    CHECK(strcmp(b.mqtt.host, "broker.lan") == 0 && b.mqtt.port == 8883 && strcmp(b.mqtt.topic, "hall/+/boom") == 0);
    CHECK(strcmp(b.mqtt.status_topic, "hall/kiosk1") == 0 && strcmp(b.mqtt.username, "kiosk1") == 0);
    CHECK(strcmp(b.mqtt.password_file, "/etc/sbfx/mqtt.pass") == 0 && strcmp(b.mqtt.ca_file, "/etc/sbfx/ca.pem") == 0);
    CHECK(b.mqtt_min_interval_ms == 1000);
    CHECK(strcmp(b.dis_listen, "239.1.2.3:3000") == 0 && strcmp(b.dis_interface, "eth1") == 0);
    err = load_board("board = \"t\";\n", &b);
    CHECK(!err[0] && !b.mqtt.host[0] && !b.dis_listen[0] && b.mqtt_min_interval_ms == 250, "the defaults: %s", err);
    const char *bad[][2] = {{"mqtt = { port = 1883; };\n", ":1: mqtt needs 'host'"},
                            {"mqtt = { host = \"b:1883\"; port = 0; };\n", "'port' = 0 is out of range"},
                            {"mqtt = {\n host = \"b\"; password_file = \"/p\"; };\n", ":2: 'password_file' needs 'username'"},
                            {"mqtt = { host = \"b\"; passwd = \"x\"; };\n", "unknown key 'passwd' in mqtt"},
                            {"dis = {\n listen = \"host:3000\"; };\n", ":2: 'listen': expected [ADDR:]PORT"},
                            {"dis = { port = 3000; };\n", "unknown key 'port' in dis"}};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
        err = load_board(bad[i][0], &b);
        CHECK(strstr(err, bad[i][1]) != NULL, "%s: %s", bad[i][0], err);
    }
}

/* ---- the scene's dis group ---- */

static const char *read_dis(const char *text, struct dis_settings *s, bool *found)
{
    static char err[512];
    err[0] = '\0';
    memset(s, 0, sizeof(*s));
    s->exercise = DIS_ANY;
    s->range_m = 20000.0;
    const char *path = write_temp(text);
    dis_config_read(path, s, found, err, sizeof(err));
    remove(path);
    return err;
}

CHECK_TEST(scene_dis_group)
{
    static struct dis_settings s;
    bool found = false;
    const char *err = read_dis(
        "media = {}; effects = {};\n"
        "dis = { origin = [48.1, 11.0, -20.5]; range = 5000; exercise = 4;\n"
        "  effects = ( { munition = \"2.9.*.2.*.*.*\"; result = 7; effect = \"air\"; },\n"
        "              { munition = \"*\"; effect = \"ground\"; } );\n"
        "  default = \"dust\"; };\n", &s, &found);
    CHECK(!err[0] && found, "%s", err);
    CHECK(s.have_origin && s.origin[0] == 48.1 && s.origin[1] == 11 && s.origin[2] == -20.5);
    CHECK(s.range_m == 5000 && s.exercise == 4 && s.effects.count == 2 && strcmp(s.effects.fallback, "dust") == 0);
    CHECK(s.effects.rules[0].result == 7 && s.effects.rules[0].munition[2] == DIS_ANY && s.effects.rules[0].munition[3] == 2);
    CHECK(s.effects.rules[1].result == DIS_ANY && strcmp(s.effects.rules[1].effect, "ground") == 0);
    err = read_dis("media = {};\n", &s, &found);
    CHECK(!err[0] && !found && !s.have_origin && s.range_m == 20000.0, "no group: %s", err);
    const char *bad[][2] = {
        {"dis = { origin = [91, 0, 0]; };", ":1: dis.origin[0] must be a number in -90..90"},
        {"dis = { origin = [0, 0]; };", "dis.origin must be [latitude, longitude, height]"},
        {"dis = {\n range = 0; };", ":2: dis.range must be a distance"},
        {"dis = { exercise = 0; };", "dis.exercise must be an exercise ID, 1..255"},
        {"dis = { effects = ( { munition = \"2.9\"; effect = \"x\"; } ); };", "seven fields"},
        {"dis = { effects = ( { munition = \"*\"; } ); };", "needs effect = \"NAME\""},
        {"dis = { effects = ( { munition = \"*\"; effect = \"x\"; result = 300; } ); };", "result must be"},
        {"dis = { effects = ( { munitions = \"*\"; effect = \"x\"; } ); };", "unknown key 'munitions'"},
        {"dis = { origen = [0, 0, 0]; };", "unknown key 'origen' in dis"},
        {"dis = { default = 3; };", "dis.default must be an effect's name"},
        {"dis = ( 1 );", "dis must be a group"},
    };
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
        err = read_dis(bad[i][0], &s, &found);
        CHECK(strstr(err, bad[i][1]) != NULL, "%s: %s", bad[i][0], err);
    }
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
