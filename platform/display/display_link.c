/* Connector present or not: when to look, what to do. */
#include "display/display_link.h"

bool link_check_due(struct display_link *l, int64_t now_ns)
{
    if (now_ns < l->next_check_ns) return false;
    l->next_check_ns = now_ns + LINK_CHECK_INTERVAL_NS;
    l->checks++;
    return true;
}

enum link_action link_update(struct display_link *l, bool connected)
{
    if (connected == !l->disconnected) return LINK_NONE;
    l->disconnected = !connected;
    if (connected) {
        l->replugs++;
        return LINK_RESUME;
    }
    l->unplugs++;
    return LINK_PAUSE;
}
