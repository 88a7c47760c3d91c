/* The procedural detail volume and the lit-smoke texture, generated once per test run and shared
 * by every GL test (issue 26: reference data computed once per run).
 *
 * sbfx_create generates the 128 x 128 x 32 turbulence volume on the CPU (src/tables/detail_gen.c:
 * ~1 s, ~5 s under ASan), and the GL suites create a module in almost every one of their
 * hundreds of forked tests: that generation was most of their time. The GL tests are linked with
 * -Wl,--wrap=sbfx_detail_generate (Makefile, GL_TEST_WRAP), so the module's call lands here:
 *   - without SBFX_TEST_CACHE (a test binary run by hand), the real generator runs, as before;
 *   - with it (tests/run.sh sets a fresh folder per run and build, removed at the end), the
 *     first test to ask for a (size, frames, seed) runs the real generator and stores its
 *     output there (under a lock, so tests running in parallel wait instead of generating it
 *     again); every later one reads those exact floats back.
 * What the tests see is bit for bit what the generator makes, and it ran, sanitised in the
 * ASan tier, in this run; the folder lives for one run only, so no earlier build's generator
 * can ever answer. test_detail (unit) tests the generator itself, unwrapped.
 *
 * The smoke texture (src/tables/smoke_texture.c: two smooth noises and an fBm per variant, then
 * the mip levels) is made the same way for every module whose scene has a lit medium, and is
 * cached the same way (-Wl,--wrap=sbfx_smoke_texture_generate; test_lit (unit) tests the
 * generator unwrapped). */
#include <fcntl.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/file.h>
#include <unistd.h>

void __real_sbfx_detail_generate(int size, int frames, uint32_t seed, float *out);
void __wrap_sbfx_detail_generate(int size, int frames, uint32_t seed, float *out);
int __real_sbfx_smoke_texture_generate(int size, int variants, uint32_t seed, uint8_t *out, float *scratch);
int __wrap_sbfx_smoke_texture_generate(int size, int variants, uint32_t seed, uint8_t *out, float *scratch);
size_t sbfx_smoke_texture_bytes(int size, int variants);

static bool read_all(const char *path, void *out, size_t bytes)
{
    FILE *f = fopen(path, "rb");
    if (!f) return false;
    size_t got = fread(out, 1, bytes, f);
    bool whole = got == bytes && fgetc(f) == EOF;
    fclose(f);
    return whole;
}

static void write_all(const char *path, const void *v, size_t bytes)
{
    char tmp[4200];
    snprintf(tmp, sizeof(tmp), "%s.%d", path, (int)getpid());
    FILE *f = fopen(tmp, "wb");
    if (!f) return;
    bool ok = fwrite(v, 1, bytes, f) == bytes;
    ok = fclose(f) == 0 && ok;
    if (!ok || rename(tmp, path) != 0) remove(tmp); /* the next test generates it again */
}

/* What a cached generator's one call makes: make(args) writes `bytes` into out. */
typedef struct generation {
    void (*make)(struct generation *g, void *out);
    int size, count;
    uint32_t seed;
    float *scratch;
    int result;
} generation;

/* Reads NAME's bytes from the cache, or generates them (under a lock, so tests running in
 * parallel wait instead of generating them again) and stores them there. */
static void cached(const char *dir, const char *name, generation *g, void *out, size_t bytes)
{
    char path[4096];
    snprintf(path, sizeof(path), "%s/%s", dir, name);
    if (read_all(path, out, bytes)) return;
    char lock_path[4200];
    snprintf(lock_path, sizeof(lock_path), "%s.lock", path);
    int lock = open(lock_path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (lock >= 0) flock(lock, LOCK_EX);
    if (!read_all(path, out, bytes)) { /* not made while this test waited for the lock */
        g->make(g, out);
        if (g->result == 0) write_all(path, out, bytes);
    }
    if (lock >= 0) close(lock); /* releases the lock */
}

static const char *cache_dir(void)
{
    const char *dir = getenv("SBFX_TEST_CACHE");
    return dir && *dir ? dir : NULL;
}

static void make_detail(generation *g, void *out)
{
    __real_sbfx_detail_generate(g->size, g->count, g->seed, out);
}

void __wrap_sbfx_detail_generate(int size, int frames, uint32_t seed, float *out)
{
    const char *dir = cache_dir();
    if (!dir || !out || size < 1 || frames < 1) {
        __real_sbfx_detail_generate(size, frames, seed, out);
        return;
    }
    char name[128];
    snprintf(name, sizeof(name), "detail-%dx%dx%d-seed%u.f32", size, size, frames, (unsigned)seed);
    generation g = {make_detail, size, frames, seed, NULL, 0};
    cached(dir, name, &g, out, (size_t)size * size * frames * sizeof(float));
}

static void make_smoke(generation *g, void *out)
{
    g->result = __real_sbfx_smoke_texture_generate(g->size, g->count, g->seed, out, g->scratch);
}

int __wrap_sbfx_smoke_texture_generate(int size, int variants, uint32_t seed, uint8_t *out, float *scratch)
{
    const char *dir = cache_dir();
    size_t bytes = sbfx_smoke_texture_bytes(size, variants);
    if (!dir || !out || !scratch || bytes == 0)
        return __real_sbfx_smoke_texture_generate(size, variants, seed, out, scratch);
    char name[128];
    snprintf(name, sizeof(name), "smoke-%d-x%d-seed%u.rgba8", size, variants, (unsigned)seed);
    generation g = {make_smoke, size, variants, seed, scratch, 0};
    cached(dir, name, &g, out, bytes);
    return g.result;
}
