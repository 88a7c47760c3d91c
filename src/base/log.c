/* Errors and logging: every room reports through these, so none calls back into sbfx.c. A
 * failure's message is kept as the module's last error and sent to the host's log callback. */
#include <stdio.h>
#include "base/base.h"

static const char *const result_strings[] = {
    [0] = "ok",
    [1] = "invalid argument",
    [2] = "no OpenGL ES 3.0 context",
    [3] = "OpenGL error",
    [4] = "shader compile or link failed",
    [5] = "missing data file",
    [6] = "out of memory",
    [7] = "particle pool full",
    [8] = "unknown effect",
};

const char *sbfx_result_string(sbfx_result result)
{
    unsigned index = (unsigned)(-(int)result);
    return index < ARRAY_SIZE(result_strings) ? result_strings[index] : "unknown error";
}

static void emit(sbfx *fx, sbfx_log_level level, const char *message)
{
    if (fx->log) fx->log(level, message, fx->log_user);
}

sbfx_result sbfx_fail(sbfx *fx, sbfx_result result, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(fx->last_error, sizeof(fx->last_error), fmt, ap);
    va_end(ap);
    emit(fx, SBFX_LOG_ERROR, fx->last_error);
    return result;
}

void sbfx_log(sbfx *fx, sbfx_log_level level, const char *fmt, ...)
{
    char message[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(message, sizeof(message), fmt, ap);
    va_end(ap);
    emit(fx, level, message);
}

const char *sbfx_last_error(const sbfx *fx)
{
    return fx ? fx->last_error : "sbfx: NULL handle";
}
