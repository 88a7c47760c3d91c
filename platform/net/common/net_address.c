/* [ADDR:]PORT and HOST[:PORT] (net_address.h). */
#include "net/common/net_address.h"

#include <arpa/inet.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int udp_endpoint_parse(const char *text, struct udp_endpoint *out, char *err, size_t n)
{
    memset(out, 0, sizeof(*out));
    const char *colon = strrchr(text, ':');
    const char *port_text = colon ? colon + 1 : text;
    char addr[32] = "";
    if (colon && (size_t)(colon - text) >= sizeof(addr)) goto err_syntax;
    if (colon) memcpy(addr, text, (size_t)(colon - text));
    char *end = NULL;
    long port = port_text[0] >= '0' && port_text[0] <= '9' ? strtol(port_text, &end, 10) : -1;
    if (port < 1 || port > 65535 || *end) goto err_syntax;
    out->port = (uint16_t)port;
    out->addr.s_addr = htonl(INADDR_ANY);
    if (colon && inet_pton(AF_INET, addr, &out->addr) != 1) goto err_syntax;
    out->multicast = IN_MULTICAST(ntohl(out->addr.s_addr));
    snprintf(out->text, sizeof(out->text), "%s", text);
    return 0;

err_syntax:
    snprintf(err, n, "expected [ADDR:]PORT (e.g. 3000, 239.1.2.3:3000 or 192.168.1.255:3000; ADDR an IPv4 "
             "address, PORT 1..65535), got '%s'", text);
    return -EINVAL;
}

int mqtt_endpoint_parse(const char *text, char *host, size_t host_size, int *port, char *err, size_t n)
{
    const char *colon = NULL, *end = text + strlen(text);
    if (text[0] == '[') { /* [v6]:port */
        const char *close = strchr(text, ']');
        if (!close || (close[1] && close[1] != ':')) goto err_syntax;
        colon = close[1] ? close + 1 : NULL;
        text++, end = close;
    } else if ((colon = strchr(text, ':')) && strchr(colon + 1, ':')) {
        colon = NULL; /* a bare IPv6 literal: no port */
    } else if (colon) {
        end = colon;
    }
    if (end == text || (size_t)(end - text) >= host_size) goto err_syntax;
    snprintf(host, host_size, "%.*s", (int)(end - text), text);
    *port = 0;
    if (colon) {
        char *stop = NULL;
        long p = colon[1] >= '0' && colon[1] <= '9' ? strtol(colon + 1, &stop, 10) : -1;
        if (p < 1 || p > 65535 || *stop) goto err_syntax;
        *port = (int)p;
    }
    return 0;

err_syntax:
    snprintf(err, n, "expected HOST[:PORT] (e.g. broker.local, 10.0.0.2:1883 or [fd00::2]:8883; PORT 1..65535), "
             "got '%s'", text);
    return -EINVAL;
}
