/* tests/vm helper: sets a V4L2 control found by its name, e.g.
 *   v4l2_ctrl /dev/video0 "Percentage of Dropped Buffers" 100
 * (vivid then stops returning frames: the player's no-frame timeout). Works while another
 * program streams from the device. Exit status 0, or 1 with a message. */
#include <errno.h>
#include <fcntl.h>
#include <linux/videodev2.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

static int find_control(int fd, const char *name, uint32_t *id)
{
    struct v4l2_queryctrl q = {.id = V4L2_CTRL_FLAG_NEXT_CTRL};
    while (ioctl(fd, VIDIOC_QUERYCTRL, &q) == 0) {
        if (strcmp((const char *)q.name, name) == 0) {
            *id = q.id;
            return 0;
        }
        q.id |= V4L2_CTRL_FLAG_NEXT_CTRL;
    }
    return -1;
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: v4l2_ctrl DEVICE NAME VALUE\n");
        return 1;
    }
    int fd = open(argv[1], O_RDWR | O_NONBLOCK);
    if (fd < 0) {
        perror(argv[1]);
        return 1;
    }
    struct v4l2_control c = {.value = atoi(argv[3])};
    if (find_control(fd, argv[2], &c.id) != 0) {
        fprintf(stderr, "v4l2_ctrl: %s has no control '%s'\n", argv[1], argv[2]);
        close(fd);
        return 1;
    }
    int rc = ioctl(fd, VIDIOC_S_CTRL, &c);
    if (rc != 0) fprintf(stderr, "v4l2_ctrl: VIDIOC_S_CTRL '%s' = %d: %s\n", argv[2], c.value, strerror(errno));
    close(fd);
    return rc == 0 ? 0 : 1;
}
