/* GL tests of the GPU timer ring (src/gl/gpu_timer.c, issue 11 item 2) on the surfaceless context:
 * results arrive a few frames late tagged with their level, never more than the ring holds in
 * flight, a host's active time query is left alone (that frame is not timed), and without the
 * extension init says so (the fallback path). */
#include "gl_fixture.h"
#include "gl/gpu_timer.h"

#ifndef GL_TIME_ELAPSED_EXT
#define GL_TIME_ELAPSED_EXT 0x88BF
#endif

/* Some GPU work: clears of the fixture's output target. */
static void some_work(gl_fixture *f, int n)
{
    glBindFramebuffer(GL_FRAMEBUFFER, f->out_fbo);
    for (int i = 0; i < n; i++) {
        glClearColor(i * 0.01f, 0.5f, 0.25f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

/* The context and a timer on it; skips the test where the extension is not listed. */
static void open_timer(gl_fixture *f, int size, gpu_timer *t)
{
    fixture_open(f, size, size);
    if (!gpu_timer_init(t))
        CHECK_SKIP("GL_EXT_disjoint_timer_query is not listed");
}

/* One frame's work, timed as level `level`. */
static void timed_frame(gpu_timer *t, gl_fixture *f, int level, int clears)
{
    gpu_timer_begin(t, level);
    some_work(f, clears);
    gpu_timer_end(t);
}

CHECK_TEST(results_arrive_late_tagged_with_their_level)
{
    gl_fixture f;
    gpu_timer t;
    open_timer(&f, 256, &t);
    int got = 0, next_level = 0, max_in_flight = 0;
    double total = 0;
    for (int frame = 0; frame < 40; frame++) {
        timed_frame(&t, &f, frame, 4);
        glFlush(); /* the host's swap: results become available after a flush */
        usleep(2000); /* the rest of the host's frame: time for the rasteriser threads */
        if (t.count > max_in_flight)
            max_in_flight = t.count;
        double ms;
        int level;
        bool valid;
        while (gpu_timer_poll(&t, &ms, &level, &valid)) {
            CHECK(level >= next_level, "level %d after %d", level, next_level); /* in order */
            CHECK(ms >= 0 && isfinite(ms), "%g ms", ms);
            next_level = level + 1;
            got += valid;
            total += valid ? ms : 0.0;
        }
    }
    glFinish();
    double ms;
    int level;
    bool valid;
    for (int i = 0; i < 10 && t.count; i++)
        while (gpu_timer_poll(&t, &ms, &level, &valid))
            got += valid, total += valid ? ms : 0.0;
    printf("# %d of 40 frames timed (%d dropped: ring of %d full), %d disjoint, mean %.3f ms\n",
           got, t.dropped, GPU_TIMER_RING, t.disjoint, got ? total / got : 0.0);
    CHECK(t.failed == NULL, "%s: 0x%04x", t.failed, t.error);
    CHECK(max_in_flight <= GPU_TIMER_RING, "%d", max_in_flight);
    CHECK(got + t.dropped + t.disjoint * GPU_TIMER_RING >= 40 - GPU_TIMER_RING, "%d timed", got);
    CHECK(got > 0, "no frame timed");
    gpu_timer_destroy(&t);
    CHECK(glGetError() == GL_NO_ERROR);
    fixture_close(&f);
}

CHECK_TEST(never_waits_when_the_ring_is_full)
{
    gl_fixture f;
    gpu_timer t;
    open_timer(&f, 64, &t);
    for (int frame = 0; frame < GPU_TIMER_RING + 3; frame++) /* no poll: the ring fills */
        timed_frame(&t, &f, 0, 1);
    CHECK(t.count == GPU_TIMER_RING && t.dropped == 3, "count %d dropped %d", t.count, t.dropped);
    CHECK(t.failed == NULL, "%s", t.failed);
    gpu_timer_destroy(&t);
    fixture_close(&f);
}

CHECK_TEST(host_time_query_left_alone)
{
    gl_fixture f;
    gpu_timer t;
    open_timer(&f, 64, &t);
    GLuint host = 0;
    glGenQueries(1, &host);
    glBeginQuery(GL_TIME_ELAPSED_EXT, host);
    timed_frame(&t, &f, 2, 1);
    GLint current = 0;
    glGetQueryiv(GL_TIME_ELAPSED_EXT, GL_CURRENT_QUERY, &current);
    CHECK((GLuint)current == host, "current query %d, host's %u", current, host);
    glEndQuery(GL_TIME_ELAPSED_EXT);
    CHECK(t.host_busy == 1 && t.count == 0 && t.failed == NULL, "busy %d count %d %s",
          t.host_busy, t.count, t.failed ? t.failed : "");
    CHECK(glGetError() == GL_NO_ERROR);
    GLuint done = 0;
    glFinish();
    glGetQueryObjectuiv(host, GL_QUERY_RESULT_AVAILABLE, &done);
    CHECK(done, "the host's query never finished");
    glDeleteQueries(1, &host);
    gpu_timer_destroy(&t);
    fixture_close(&f);
}

CHECK_TEST(fallback_without_the_extension)
{
    fixture_hide_extensions("GL_EXT_disjoint_timer_query");
    gl_fixture f;
    fixture_open(&f, 64, 64);
    fixture_require_hidden("GL_EXT_disjoint_timer_query");
    gpu_timer t;
    CHECK(!gpu_timer_init(&t), "init succeeded without the extension");
    gpu_timer_begin(&t, 0); /* harmless: nothing happens */
    gpu_timer_end(&t);
    double ms;
    int level;
    bool valid;
    CHECK(!gpu_timer_poll(&t, &ms, &level, &valid));
    CHECK(glGetError() == GL_NO_ERROR);
    gpu_timer_destroy(&t);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
