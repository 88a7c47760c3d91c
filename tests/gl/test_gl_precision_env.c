/* The precision diagnostics (issue 25, src/gl/precision.c, docs/testing.md): SBFX_MEDIUMP=native and
 * SBFX_FILTER_BITS=N are read by sbfx_create, each one honoured is logged at info level by name,
 * and an invalid value fails sbfx_create with a message naming the variable. With filter bits
 * set, the fetches go through shaders_es/filtered.frag: the picture changes, by little. */
#include "gl_fixture.h"

#define SIZE 32

typedef struct log_capture {
    char text[4096];
    size_t used;
} log_capture;

static void capture_log(sbfx_log_level level, const char *message, void *user)
{
    log_capture *c = user;
    (void)level;
    int n = snprintf(c->text + c->used, sizeof(c->text) - c->used, "%s\n", message);
    if (n > 0) c->used = c->used + (size_t)n < sizeof(c->text) ? c->used + (size_t)n : sizeof(c->text) - 1;
}

static sbfx_result create_logged(log_capture *c, sbfx **fx, sbfx_target_format format)
{
    memset(c, 0, sizeof(*c));
    sbfx_desc d = {.target_divisor = 1, .target_format = format, .opacity = SBFX_OPACITY_EXACT,
                   .max_particles = 16, .log = capture_log, .log_user = c};
    return sbfx_create(&d, fx);
}

static void clear_env(void)
{
    unsetenv("SBFX_MEDIUMP");
    unsetenv("SBFX_FILTER_BITS");
}

CHECK_TEST(mediump_native_is_honoured_and_named)
{
    gl_fixture f;
    fixture_open(&f, SIZE, SIZE);
    clear_env();
    log_capture c;
    sbfx *fx = NULL;
    CHECK(create_logged(&c, &fx, SBFX_FORMAT_RGBA16F) == SBFX_OK, "%s", c.text);
    bool software = strstr(c.text, "compile their mediump as highp") != NULL;
    sbfx_destroy(fx);
    CHECK(!strstr(c.text, "SBFX_MEDIUMP"), "logged without the variable: %s", c.text);
    setenv("SBFX_MEDIUMP", "native", 1);
    CHECK(create_logged(&c, &fx, SBFX_FORMAT_RGBA16F) == SBFX_OK, "%s", c.text);
    CHECK(strstr(c.text, "SBFX_MEDIUMP=native honoured"), "the log does not name SBFX_MEDIUMP: %s", c.text);
    CHECK(!strstr(c.text, "compile their mediump as highp"), "the log still says mediump is highp: %s", c.text);
    printf("# renderer %s: mediump as highp by default %d, with SBFX_MEDIUMP=native 0\n",
           (const char *)glGetString(GL_RENDERER), software);
    sbfx_destroy(fx);
    clear_env();
    fixture_close(&f);
}

/* A fire particle with detail into RGBA32F, read back. */
static float *render_fire(gl_fixture *f, log_capture *c)
{
    sbfx *fx = NULL;
    CHECK(create_logged(c, &fx, SBFX_FORMAT_RGBA32F) == SBFX_OK, "%s", c->text);
    if (!fx) return NULL;
    sbfx_view_particle p = {.center = {0.1f, -0.1f, -4.0f}, .radius = 1.2f, .detail = {0.3f, 0.6f, 0.1f},
                            .intensity = 1.0f, .medium = SBFX_FIRE};
    CHECK(sbfx_render_view_particles(fx, &f->frame, &p, 1) == SBFX_OK, "%s", sbfx_last_error(fx));
    int w, h;
    float *rgba = fixture_read_target(fx, &w, &h);
    CHECK(w == SIZE && h == SIZE, "target %dx%d", w, h);
    sbfx_destroy(fx);
    return rgba;
}

CHECK_TEST(filter_bits_are_honoured_named_and_change_the_picture_by_little)
{
    gl_fixture f;
    fixture_open_far(&f, SIZE, SIZE);
    clear_env();
    log_capture c;
    float *plain = render_fire(&f, &c);
    setenv("SBFX_FILTER_BITS", "6", 1);
    float *rounded = render_fire(&f, &c);
    CHECK(strstr(c.text, "SBFX_FILTER_BITS=6 honoured"), "the log does not name SBFX_FILTER_BITS: %s", c.text);
    /* the detail moves by at most 2^-7 x its texel differences per axis: alpha moves a little */
    double most = 0.0, alpha_most = 0.0;
    for (int i = 0; i < SIZE * SIZE * 4; i++) {
        double d = fabs((double)plain[i] - rounded[i]);
        if (i % 4 == 3) alpha_most = fmax(alpha_most, d);
        most = fmax(most, d / fmax(1.0, fabs((double)plain[i])));
    }
    printf("# fire with detail, 6-bit weights against the texture unit's: alpha %.3g, light %.3g relative\n",
           alpha_most, most);
    CHECK(most > 0.0, "6-bit weights changed nothing: the fetch is not filtered in the shader");
    CHECK(alpha_most < 0.05, "6-bit weights moved alpha by %g", alpha_most);
    free(plain);
    free(rounded);
    clear_env();
    fixture_close(&f);
}

CHECK_TEST(invalid_values_are_refused_at_create)
{
    gl_fixture f;
    fixture_open(&f, SIZE, SIZE);
    static const struct { const char *name, *value; } bad[] = {
        {"SBFX_MEDIUMP", "half"}, {"SBFX_MEDIUMP", ""}, {"SBFX_MEDIUMP", "Native"},
        {"SBFX_FILTER_BITS", "0"}, {"SBFX_FILTER_BITS", "17"}, {"SBFX_FILTER_BITS", "8x"},
        {"SBFX_FILTER_BITS", ""}, {"SBFX_FILTER_BITS", "-8"}, {"SBFX_FILTER_BITS", "eight"},
    };
    for (size_t i = 0; i < ARRAY_SIZE(bad); i++) {
        clear_env();
        setenv(bad[i].name, bad[i].value, 1);
        log_capture c;
        sbfx *fx = NULL;
        sbfx_result r = create_logged(&c, &fx, SBFX_FORMAT_RGBA16F);
        CHECK(r == SBFX_ERR_INVALID_ARGUMENT && !fx, "%s=\"%s\": sbfx_create gave %d", bad[i].name, bad[i].value, r);
        CHECK(strstr(c.text, bad[i].name), "%s=\"%s\": the error does not name it: %s", bad[i].name, bad[i].value,
              c.text);
        CHECK(!strstr(c.text, "honoured"), "%s=\"%s\" was honoured: %s", bad[i].name, bad[i].value, c.text);
        sbfx_destroy(fx);
    }
    clear_env();
    setenv("SBFX_FILTER_BITS", "16", 1); /* the ends of the range are taken */
    log_capture c;
    sbfx *fx = NULL;
    CHECK(create_logged(&c, &fx, SBFX_FORMAT_RGBA16F) == SBFX_OK, "SBFX_FILTER_BITS=16: %s", c.text);
    sbfx_destroy(fx);
    setenv("SBFX_FILTER_BITS", "1", 1);
    CHECK(create_logged(&c, &fx, SBFX_FORMAT_RGBA16F) == SBFX_OK, "SBFX_FILTER_BITS=1: %s", c.text);
    sbfx_destroy(fx);
    clear_env();
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
