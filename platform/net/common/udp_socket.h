/* A non-blocking UDP (IPv4) socket that receives on [ADDR:]PORT, as DIS traffic arrives:
 *   PORT                 any local address (unicast and broadcast datagrams to the port)
 *   ADDR:PORT, ADDR a    local address          only datagrams sent to it
 *                        broadcast address      only broadcasts (255.255.255.255, 192.168.1.255)
 *                        multicast group        the group is joined (224.0.0.0/4), on the
 *                                               interface named, else the one the kernel picks
 * SO_REUSEADDR lets other programs on the host (a second image generator, a logger) listen to
 * the same broadcast or group. Datagrams are read in batches (recvmmsg) into buffers the caller
 * made once; nothing is allocated per datagram. Errors: a negative errno and a message naming
 * the address and what to do. */
#ifndef SBFX_UDP_SOCKET_H
#define SBFX_UDP_SOCKET_H

#include <netinet/in.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "net/common/net_address.h"

/* interface: a name ("eth1") for the multicast join, or NULL/"" for the kernel's choice. */
int udp_open(const struct udp_endpoint *e, const char *interface, int *fd, char *err, size_t n);

/* One received datagram: its bytes in the caller's buffer, its length (the datagram's, which may
 * exceed the buffer: then truncated is set). */
struct udp_datagram {
    uint8_t *data;
    size_t capacity;
    size_t length;
    bool truncated;
    struct sockaddr_in from;  /* the sender */
};

/* Reads up to count waiting datagrams into d[0..count): how many (0: none waits), or a negative
 * errno. Never blocks. */
int udp_receive(int fd, struct udp_datagram *d, int count);

#endif
