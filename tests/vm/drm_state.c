/* tests/vm helper: prints what every CRTC of a DRM device shows, one line each:
 *   crtc ID fb FB mode NAME|off
 * With --hold it opens the device first (and gives up DRM master, so a player can take it),
 * waits until stdin reaches EOF, then prints: holding an fd keeps the kernel from restoring the
 * fbdev console when the player closes the device, so the state printed is the one the player
 * left behind. Exit status 0, or 1 with a message. */
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

static int print_state(int fd)
{
    drmModeRes *res = drmModeGetResources(fd);
    if (!res) {
        perror("drm_state: drmModeGetResources");
        return 1;
    }
    for (int i = 0; i < res->count_crtcs; i++) {
        drmModeCrtc *c = drmModeGetCrtc(fd, res->crtcs[i]);
        if (!c) continue;
        printf("crtc %u fb %u mode %s\n", c->crtc_id, c->buffer_id, c->mode_valid ? c->mode.name : "off");
        drmModeFreeCrtc(c);
    }
    drmModeFreeResources(res);
    return 0;
}

int main(int argc, char **argv)
{
    int hold = argc == 3 && strcmp(argv[2], "--hold") == 0;
    if (argc != 2 && !hold) {
        fprintf(stderr, "usage: drm_state DEVICE [--hold]\n");
        return 1;
    }
    int fd = open(argv[1], O_RDWR | O_CLOEXEC);
    if (fd < 0) {
        perror(argv[1]);
        return 1;
    }
    if (drmIsMaster(fd)) drmDropMaster(fd);
    if (hold) {
        char buf[64];
        while (read(STDIN_FILENO, buf, sizeof(buf)) > 0) continue;
    }
    int rc = print_state(fd);
    close(fd);
    return rc;
}
