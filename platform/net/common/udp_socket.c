/* The DIS socket (udp_socket.h). */
#define _GNU_SOURCE /* recvmmsg */
#include "net/common/udp_socket.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <net/if.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#define UDP_BATCH_MAX 64
#define RECEIVE_BUFFER (4 << 20) /* a burst of traffic waits here between two frames */

static int fail(int fd, const char *what, const struct udp_endpoint *e, const char *hint, char *err, size_t n)
{
    int rc = -errno;
    snprintf(err, n, "%s %s: %s%s", what, e->text, strerror(errno), hint);
    close(fd);
    return rc;
}

static int join_group(int fd, const struct udp_endpoint *e, const char *interface, char *err, size_t n)
{
    struct ip_mreqn req = {.imr_multiaddr = e->addr};
    if (interface && interface[0] && !(req.imr_ifindex = (int)if_nametoindex(interface))) {
        int rc = -errno;
        snprintf(err, n, "joining the multicast group %s: no network interface '%s' (ip link lists them)",
                 e->text, interface);
        close(fd);
        return rc;
    }
    if (setsockopt(fd, IPPROTO_IP, IP_ADD_MEMBERSHIP, &req, sizeof(req)) != 0)
        return fail(fd, "joining the multicast group", e, " (is there a route for 224.0.0.0/4, or name the "
                    "interface in the board's dis.interface?)", err, n);
    return 0;
}

int udp_open(const struct udp_endpoint *e, const char *interface, int *out, char *err, size_t n)
{
    int fd = socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) {
        int rc = -errno;
        snprintf(err, n, "socket(AF_INET, SOCK_DGRAM) for %s: %s (a unit's RestrictAddressFamilies= "
                 "without AF_INET?)", e->text, strerror(errno));
        return rc;
    }
    int one = 1, size = RECEIVE_BUFFER;
    if (setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one)) != 0)
        return fail(fd, "SO_REUSEADDR on", e, "", err, n);
    /* best effort: the kernel caps it at net.core.rmem_max */
    (void)setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &size, sizeof(size));
    struct sockaddr_in sa = {.sin_family = AF_INET, .sin_port = htons(e->port), .sin_addr = e->addr};
    if (bind(fd, (const struct sockaddr *)&sa, sizeof(sa)) != 0)
        return fail(fd, "binding", e,
                    errno == EADDRNOTAVAIL ? " (ADDR must be an address of this machine, a broadcast address "
                                             "or a multicast group)"
                    : errno == EACCES      ? " (ports under 1024 need privileges: DIS uses 3000, CIGI 8004)"
                    : errno == EADDRINUSE  ? " (another program holds the port without SO_REUSEADDR)"
                                           : "",
                    err, n);
    int rc = e->multicast ? join_group(fd, e, interface, err, n) : 0;
    if (rc) return rc;
    *out = fd;
    return 0;
}

int udp_receive(int fd, struct udp_datagram *d, int count)
{
    struct mmsghdr msgs[UDP_BATCH_MAX];
    struct iovec iov[UDP_BATCH_MAX];
    if (count > UDP_BATCH_MAX) count = UDP_BATCH_MAX;
    for (int i = 0; i < count; i++) {
        iov[i] = (struct iovec){.iov_base = d[i].data, .iov_len = d[i].capacity};
        msgs[i] = (struct mmsghdr){.msg_hdr = {.msg_name = &d[i].from, .msg_namelen = sizeof(d[i].from),
                                               .msg_iov = &iov[i], .msg_iovlen = 1}};
    }
    int got = recvmmsg(fd, msgs, (unsigned)count, MSG_DONTWAIT | MSG_TRUNC, NULL);
    if (got < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR ? 0 : -errno;
    for (int i = 0; i < got; i++) {
        d[i].length = msgs[i].msg_len;
        d[i].truncated = (msgs[i].msg_hdr.msg_flags & MSG_TRUNC) != 0 || msgs[i].msg_len > d[i].capacity;
    }
    return got;
}
