/* Display unplug and replug decisions (platform/display/display_link.c) with injected connector states:
 * a pause once when it goes, a resume (with a new modeset) once when it comes back, no action
 * for the same state seen again, and the connector asked at most once a second. The real
 * driver path (vkms's connector forced off and back through sysfs) is tests/vm/guest.sh's
 * display-unplug. */
#include "check.h"
#include "display/display_link.h"

#define MS INT64_C(1000000)

CHECK_TEST(unplug_pauses_once_replug_resumes_once)
{
    struct display_link l = {0};
    const bool seen[] = {true, true, false, false, false, true, true, false, true};
    const enum link_action want[] = {LINK_NONE, LINK_NONE, LINK_PAUSE, LINK_NONE, LINK_NONE,
                                     LINK_RESUME, LINK_NONE, LINK_PAUSE, LINK_RESUME};
    for (int i = 0; i < 9; i++) {
        enum link_action a = link_update(&l, seen[i]);
        CHECK(a == want[i], "state %d (%s): action %d, expected %d", i,
              seen[i] ? "connected" : "disconnected", a, want[i]);
    }
    CHECK(l.unplugs == 2 && l.replugs == 2 && !l.disconnected, "unplugs %llu, replugs %llu",
          (unsigned long long)l.unplugs, (unsigned long long)l.replugs);
}

CHECK_TEST(starts_connected)
{
    struct display_link l = {0};
    CHECK(link_update(&l, true) == LINK_NONE, "a connected display at start is no replug");
    CHECK(l.replugs == 0);
}

CHECK_TEST(checked_at_most_once_a_second)
{
    struct display_link l = {0};
    int due = 0;
    for (int64_t t = 0; t < 5000 * MS; t += 16 * MS) due += link_check_due(&l, t); /* 60 Hz */
    CHECK(due == 5, "%d checks in 5 s of frames", due);
    for (int64_t t = 5000 * MS; t < 10000 * MS; t += LINK_PAUSED_FRAME_NS) due += link_check_due(&l, t);
    CHECK(due == 10, "%d checks in 10 s (paused frames at 10 Hz for the last 5)", due);
}

int main(int argc, char **argv)
{
    return check_main_args(argc, argv);
}
