/* Network addresses as sbfx-play's flags and board profiles give them, parsed without touching
 * the network (pure: the flags are checked before anything is opened):
 *   --dis [ADDR:]PORT     an IPv4 address (local, broadcast or multicast group) and a UDP port
 *   --mqtt HOST[:PORT]    a broker: a name, an IPv4 address or [an IPv6 one], and a TCP port */
#ifndef SBFX_NET_ADDRESS_H
#define SBFX_NET_ADDRESS_H

#include <netinet/in.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct udp_endpoint {
    struct in_addr addr;   /* INADDR_ANY when only a port was given */
    uint16_t port;
    bool multicast;
    char text[64];         /* as given, for messages */
};

/* "[ADDR:]PORT": ADDR a dotted IPv4 address, PORT 1..65535. 0 or -EINVAL with why. */
int udp_endpoint_parse(const char *text, struct udp_endpoint *out, char *err, size_t n);
/* "HOST[:PORT]" ("[v6]:PORT" for an IPv6 literal); *port 0 when not given. 0 or -EINVAL with why. */
int mqtt_endpoint_parse(const char *text, char *host, size_t host_size, int *port, char *err, size_t n);

#endif
