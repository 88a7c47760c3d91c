/* sbfx-play under a service manager (platform/player/outputs/notify.c, docs/kiosk-deploy.md):
 * this test plays systemd's part. It binds a unix datagram socket, starts the player headless
 * (the sbfx-play beside this test's build folder) with NOTIFY_SOCKET naming it, WATCHDOG_USEC
 * set and the test hook SBFX_PLAY_TEST_HANG_AFTER_FRAMES, which stalls the render loop after
 * that many frames, and reads what arrives:
 *   - READY=1 first, and only once the first frame is on the output (its PNG exists);
 *   - WATCHDOG=1 pings while frames are rendered;
 *   - none once the loop hangs (the hook's line on stderr), while no frame is written either;
 *   - without WATCHDOG_USEC, READY=1 and no ping. */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <stdbool.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <time.h>

#include "check.h"

#define WATCHDOG_USEC 20000            /* pings every 10 ms */
#define HANG_AFTER_FRAMES "300"
#define START_TIMEOUT_MS 120000        /* a safety net for a slow (ASan) start, not a limit */
#define SILENCE_MS 1000                /* 100 ping intervals */

struct listener {
    char dir[64], socket_path[96], out_dir[96];
    int sock, err_pipe;
    pid_t pid;
    /* what arrived */
    int ready, pings, pings_after_hang, other;
    bool ready_first, png_at_ready, hung;
    int pngs_at_hang;
};

static int64_t now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

/* The sbfx-play of the build this test belongs to: BUILD/tests/platform/test_x -> BUILD/sbfx-play. */
static bool player_path(char *out, size_t n)
{
    char self[PATH_MAX - 16]; /* room for "/sbfx-play" in out */
    ssize_t len = readlink("/proc/self/exe", self, sizeof(self) - 1);
    if (len <= 0) return false;
    self[len] = '\0';
    for (int up = 0; up < 3; up++) {
        char *slash = strrchr(self, '/');
        if (!slash) return false;
        *slash = '\0';
    }
    snprintf(out, n, "%s/sbfx-play", self);
    return access(out, X_OK) == 0;
}

static int count_pngs(const char *dir)
{
    int count = 0;
    char path[256];
    for (int i = 0; i < 100000; i++) {
        snprintf(path, sizeof(path), "%s/frame-%04d.png", dir, i);
        if (access(path, F_OK) != 0) break;
        count++;
    }
    return count;
}

static void open_socket(struct listener *l)
{
    snprintf(l->dir, sizeof(l->dir), "/tmp/sbfx-notify-XXXXXX");
    CHECK(mkdtemp(l->dir) != NULL, "mkdtemp: %s", strerror(errno));
    snprintf(l->socket_path, sizeof(l->socket_path), "%s/notify", l->dir);
    snprintf(l->out_dir, sizeof(l->out_dir), "%s/out", l->dir);
    l->sock = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    CHECK(l->sock >= 0, "socket: %s", strerror(errno));
    struct sockaddr_un addr = {.sun_family = AF_UNIX};
    snprintf(addr.sun_path, sizeof(addr.sun_path), "%s", l->socket_path);
    CHECK(bind(l->sock, (struct sockaddr *)&addr, sizeof(addr)) == 0, "bind: %s", strerror(errno));
}

static void start_player(struct listener *l, const char *player, bool watchdog)
{
    int fds[2];
    CHECK(pipe(fds) == 0);
    l->pid = fork();
    if (l->pid == 0) {
        dup2(fds[1], 2);
        close(fds[0]);
        setenv("NOTIFY_SOCKET", l->socket_path, 1);
        unsetenv("WATCHDOG_PID");
        if (watchdog) {
            char usec[32];
            snprintf(usec, sizeof(usec), "%d", WATCHDOG_USEC);
            setenv("WATCHDOG_USEC", usec, 1);
        } else {
            unsetenv("WATCHDOG_USEC");
        }
        setenv("SBFX_PLAY_TEST_HANG_AFTER_FRAMES", HANG_AFTER_FRAMES, 1);
        execl(player, player, "--headless", "--quiet", "--size", "64x36", "--frames", "100000", "--out",
              l->out_dir, (char *)NULL);
        _exit(127);
    }
    close(fds[1]);
    l->err_pipe = fds[0];
    CHECK(l->pid > 0, "fork: %s", strerror(errno));
}

static void on_message(struct listener *l, const char *msg)
{
    if (strncmp(msg, "READY=1", 7) == 0) {
        if (l->ready == 0 && l->pings == 0 && l->other == 0) l->ready_first = true;
        if (l->ready == 0) {
            char first[256];
            snprintf(first, sizeof(first), "%s/frame-0000.png", l->out_dir);
            l->png_at_ready = access(first, F_OK) == 0;
        }
        l->ready++;
    } else if (strcmp(msg, "WATCHDOG=1") == 0) {
        if (l->hung) l->pings_after_hang++;
        else l->pings++;
    } else {
        l->other++;
        printf("# unexpected message: %s\n", msg);
    }
}

/* Drains the datagrams waiting in the socket. */
static void read_messages(struct listener *l)
{
    char msg[512];
    ssize_t len;
    while ((len = recv(l->sock, msg, sizeof(msg) - 1, MSG_DONTWAIT)) > 0) {
        msg[len] = '\0';
        on_message(l, msg);
    }
}

/* True once the player's stderr carries the hook's "stalls" line (or it closed). */
static bool read_stderr(struct listener *l, bool *closed)
{
    static char text[8192];
    static size_t used;
    ssize_t len = read(l->err_pipe, text + used, sizeof(text) - 1 - used);
    if (len <= 0) {
        *closed = true;
        return false;
    }
    used += (size_t)len;
    text[used] = '\0';
    if (used >= sizeof(text) - 1) used = 0;
    return strstr(text, "render loop stalls") != NULL;
}

/* Listens until the hook's line (or START_TIMEOUT_MS), then SILENCE_MS more. */
static void listen_until_hang(struct listener *l)
{
    int64_t deadline = now_ms() + START_TIMEOUT_MS;
    bool closed = false;
    while (!l->hung && !closed && now_ms() < deadline) {
        struct pollfd fds[2] = {{.fd = l->sock, .events = POLLIN}, {.fd = l->err_pipe, .events = POLLIN}};
        if (poll(fds, 2, 100) < 0 && errno != EINTR) break;
        if (fds[0].revents) read_messages(l);
        if (fds[1].revents && read_stderr(l, &closed)) {
            read_messages(l); /* what was sent before the line was written */
            l->hung = true;
            l->pngs_at_hang = count_pngs(l->out_dir);
        }
    }
    CHECK(l->hung, "the player never reached the hang hook (%s)", closed ? "it exited" : "timed out");
    int64_t quiet_until = now_ms() + SILENCE_MS;
    while (l->hung && now_ms() < quiet_until) {
        struct pollfd fd = {.fd = l->sock, .events = POLLIN};
        if (poll(&fd, 1, 50) > 0) read_messages(l);
    }
}

static void stop_player(struct listener *l)
{
    if (l->pid > 0) {
        kill(l->pid, SIGKILL);
        waitpid(l->pid, NULL, 0);
    }
    close(l->sock);
    close(l->err_pipe);
    char cmd[160];
    snprintf(cmd, sizeof(cmd), "rm -rf '%s'", l->dir);
    if (system(cmd) != 0) printf("# could not remove %s\n", l->dir);
}

static void run(struct listener *l, bool watchdog)
{
    char player[PATH_MAX];
    if (!player_path(player, sizeof(player))) CHECK_SKIP("no sbfx-play beside this test's build (make all)");
    memset(l, 0, sizeof(*l));
    open_socket(l);
    start_player(l, player, watchdog);
    listen_until_hang(l);
    int pngs_after = count_pngs(l->out_dir);
    printf("# %s: READY=1 x %d, WATCHDOG=1 x %d while rendering (%d frames), %d after the hang\n",
           watchdog ? "watchdog" : "no watchdog", l->ready, l->pings, l->pngs_at_hang, l->pings_after_hang);
    CHECK(pngs_after == l->pngs_at_hang, "frames went on after the hang: %d -> %d", l->pngs_at_hang, pngs_after);
    stop_player(l);
}

CHECK_TEST(ready_after_first_frame_pings_while_rendering_none_when_hung)
{
    static struct listener l;
    run(&l, true);
    CHECK(l.ready == 1, "READY=1 came %d times", l.ready);
    CHECK(l.ready_first, "READY=1 was not the first message");
    CHECK(l.png_at_ready, "READY=1 came before the first frame was written");
    CHECK(l.pings >= 3, "only %d WATCHDOG=1 pings over %d frames", l.pings, l.pngs_at_hang);
    CHECK(l.pings_after_hang == 0, "%d pings after the render loop hung", l.pings_after_hang);
    CHECK(l.other == 0, "%d unexpected messages", l.other);
}

CHECK_TEST(no_watchdog_no_pings)
{
    static struct listener l;
    run(&l, false);
    CHECK(l.ready == 1 && l.ready_first && l.png_at_ready, "READY=1 x %d, first %d, after a frame %d",
          l.ready, l.ready_first, l.png_at_ready);
    CHECK(l.pings == 0 && l.pings_after_hang == 0, "%d pings without WATCHDOG_USEC", l.pings + l.pings_after_hang);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
