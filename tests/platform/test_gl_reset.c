/* The GPU reset query of the player (platform/egl/gl_reset.c) without a GPU: the injected reset is
 * answered once, at its frame; a driver's status query is asked on every other frame; the
 * context attributes ask for reset notification only where EGL offers it. The recovery itself
 * (a new context, GL objects and sbfx, frames that go on) runs on llvmpipe in tests/cli.sh
 * (gpu-reset-*). */
#include "check.h"
#include "egl/gl_reset.h"

static int driver_calls;
static GLenum driver_answer = GL_NO_ERROR;

static GLenum fake_status(void)
{
    driver_calls++;
    return driver_answer;
}

CHECK_TEST(injected_reset_answered_once_at_its_frame)
{
    struct gl_reset r = {.inject_frame = -1};
    gl_reset_inject(&r, 5);
    int resets = 0, at = -1;
    for (int frame = 0; frame < 20; frame++) {
        GLenum s = gl_reset_status(&r, frame);
        if (s != GL_NO_ERROR) resets++, at = frame;
        CHECK(s == GL_NO_ERROR || s == GL_GUILTY_CONTEXT_RESET, "frame %d: 0x%x", frame, s);
    }
    CHECK(resets == 1 && at == 5, "%d resets, the last at frame %d", resets, at);
    CHECK(gl_reset_status(&r, 5) == GL_NO_ERROR, "frame 5 again (after a recovery): no reset");
}

CHECK_TEST(driver_query_asked_every_frame)
{
    struct gl_reset r = {.status = fake_status, .extension = "GL_KHR_robustness", .inject_frame = -1};
    driver_calls = 0;
    for (int frame = 0; frame < 10; frame++) CHECK(gl_reset_status(&r, frame) == GL_NO_ERROR);
    CHECK(driver_calls == 10, "%d queries for 10 frames", driver_calls);
    driver_answer = GL_INNOCENT_CONTEXT_RESET;
    CHECK(gl_reset_status(&r, 10) == GL_INNOCENT_CONTEXT_RESET);
    driver_answer = GL_NO_ERROR;
    gl_reset_inject(&r, 11);
    int before = driver_calls;
    CHECK(gl_reset_status(&r, 11) == GL_GUILTY_CONTEXT_RESET);
    CHECK(driver_calls == before, "the injected answer does not ask the driver");
}

CHECK_TEST(reset_names)
{
    CHECK(strstr(gl_reset_name(GL_GUILTY_CONTEXT_RESET), "guilty") != NULL);
    CHECK(strstr(gl_reset_name(GL_INNOCENT_CONTEXT_RESET), "innocent") != NULL);
    CHECK(strstr(gl_reset_name(GL_UNKNOWN_CONTEXT_RESET), "unknown") != NULL);
}

CHECK_TEST(attributes_without_robustness_are_plain_gles3)
{
    EGLint attribs[GL_RESET_ATTRIBS_MAX];
    /* robust not asked for: the strategy is never added, whatever the display offers */
    CHECK(!gl_reset_context_attribs(EGL_NO_DISPLAY, false, attribs));
    CHECK(attribs[0] == EGL_CONTEXT_MAJOR_VERSION && attribs[1] == 3 && attribs[2] == EGL_NONE);
}

CHECK_TEST(init_without_robust_context_has_no_query)
{
    struct gl_reset r = {.status = fake_status, .inject_frame = 7};
    gl_reset_init(&r, false);
    CHECK(r.status == NULL && r.extension == NULL, "no query without a robust context");
    CHECK(r.inject_frame == 7, "an injected reset survives init (a recovery re-inits)");
}

int main(int argc, char **argv)
{
    return check_main_args(argc, argv);
}
