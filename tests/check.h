/* Tiny self-checking test harness (kernel-selftest style, TAP-like output).
 *
 *   CHECK_TEST(name) { ... CHECK(cond, "fmt", ...); CHECK_NEAR(a, b, tol); ... }
 *   int main(void) { return check_main(); }   // or check_main_args(argc, argv)
 *
 * Each test runs in its own forked child (a crash fails that test only); output lines are
 *   ok - suite/name
 *   not ok - suite/name: reason
 *   skip - suite/name: reason
 * tests/run.sh counts them and prints "N passed, M failed, K skipped".
 * Set CHECK_NOFORK=1 to run tests in-process (for gdb/ASan reports). */
#ifndef SBFX_CHECK_H
#define SBFX_CHECK_H

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

typedef void (*check_fn)(void);
struct check_entry { const char *name; check_fn fn; };

#define CHECK_MAX_TESTS 256
static struct check_entry check_tests[CHECK_MAX_TESTS];
static int check_test_count;
static int check_failed_here; /* failures inside the running test */

#define CHECK_TEST(name)                                                                     \
    static void check_test_##name(void);                                                     \
    __attribute__((constructor)) static void check_register_##name(void)                     \
    {                                                                                        \
        if (check_test_count < CHECK_MAX_TESTS)                                              \
            check_tests[check_test_count++] = (struct check_entry){#name, check_test_##name}; \
    }                                                                                        \
    static void check_test_##name(void)

/* Prints the reason of a failure; the test goes on so that several failures show at once. */
static inline void check_fail(const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    fprintf(stdout, "#   %s:%d: ", file, line);
    va_start(ap, fmt);
    vfprintf(stdout, fmt, ap);
    va_end(ap);
    fputc('\n', stdout);
    fflush(stdout);
    check_failed_here++;
}

#define CHECK(cond, ...)                                                                     \
    do {                                                                                     \
        if (!(cond)) check_fail(__FILE__, __LINE__, "CHECK(" #cond ") " __VA_ARGS__);        \
    } while (0)

#define CHECK_NEAR(a, b, tol)                                                                \
    do {                                                                                     \
        double check_a_ = (a), check_b_ = (b), check_t_ = (tol);                             \
        if (!(fabs(check_a_ - check_b_) <= check_t_))                                        \
            check_fail(__FILE__, __LINE__, "%s = %.9g, %s = %.9g, |diff| %.3g > %.3g", #a,   \
                       check_a_, #b, check_b_, fabs(check_a_ - check_b_), check_t_);         \
    } while (0)

#define CHECK_FINITE(x)                                                                      \
    do {                                                                                     \
        double check_x_ = (x);                                                               \
        if (!isfinite(check_x_)) check_fail(__FILE__, __LINE__, "%s = %g is not finite", #x, check_x_); \
    } while (0)

/* Skips the running test with a reason (exit code 77 from the child). */
#define CHECK_SKIP(...)                                                                      \
    do {                                                                                     \
        fprintf(stdout, "#SKIP ");                                                           \
        fprintf(stdout, __VA_ARGS__);                                                        \
        fputc('\n', stdout);                                                                 \
        fflush(stdout);                                                                      \
        exit(77);                                                                            \
    } while (0)

/* Called once in the parent before it forks the first test, where a suite sets it (the GL
 * fixture loads the EGL driver there: tests/gl/gl_fixture.h); NULL for the others. */
static void (*check_before_forks)(void);

static inline const char *check_suite_name(const char *argv0)
{
    const char *slash = argv0 ? strrchr(argv0, '/') : NULL;
    return slash ? slash + 1 : (argv0 ? argv0 : "test");
}

static inline int check_run_one(const struct check_entry *t)
{
    check_failed_here = 0;
    t->fn();
    return check_failed_here ? 1 : 0;
}

static inline int check_main_args(int argc, char **argv)
{
    const char *suite = check_suite_name(argc > 0 ? argv[0] : NULL);
    const char *only = argc > 1 ? argv[1] : NULL;
    int nofork = getenv("CHECK_NOFORK") != NULL;
    int failures = 0;
    if (!nofork && check_before_forks) check_before_forks();
    for (int i = 0; i < check_test_count; i++) {
        const struct check_entry *t = &check_tests[i];
        if (only && strcmp(only, t->name) != 0) continue;
        fflush(stdout);
        int status = 0;
        if (nofork) {
            status = check_run_one(t);
        } else {
            pid_t pid = fork();
            if (pid == 0) {
                int rc = check_run_one(t);
                fflush(stdout);
                _exit(rc);
            }
            int ws = 0;
            if (pid < 0 || waitpid(pid, &ws, 0) < 0) status = 2;
            else if (WIFEXITED(ws)) status = WEXITSTATUS(ws);
            else status = 128 + (WIFSIGNALED(ws) ? WTERMSIG(ws) : 0);
        }
        if (status == 0) printf("ok - %s/%s\n", suite, t->name);
        else if (status == 77) printf("skip - %s/%s\n", suite, t->name);
        else if (status >= 128) printf("not ok - %s/%s: killed by signal %d\n", suite, t->name, status - 128), failures++;
        else printf("not ok - %s/%s\n", suite, t->name), failures++;
        fflush(stdout);
    }
    return failures ? 1 : 0;
}

static inline int check_main(void) { return check_main_args(0, NULL); }

#endif
