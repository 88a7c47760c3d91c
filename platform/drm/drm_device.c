/* DRM/KMS discovery: card, connector, mode, CRTC, primary plane, master, saved CRTC. */
#include "drm/drm_device.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "drm/drm_mode_spec.h"

static void connector_name(const drmModeConnector *c, char *out, size_t n)
{
    const char *type = drmModeGetConnectorTypeName(c->connector_type);
    snprintf(out, n, "%s-%u", type ? type : "Unknown", c->connector_type_id);
}

double drm_mode_refresh(const drmModeModeInfo *m)
{
    if (!m->htotal || !m->vtotal) return m->vrefresh;
    double hz = m->clock * 1000.0 / ((double)m->htotal * m->vtotal);
    if (m->flags & DRM_MODE_FLAG_INTERLACE) hz *= 2.0;
    if (m->flags & DRM_MODE_FLAG_DBLSCAN) hz /= 2.0;
    if (m->vscan > 1) hz /= m->vscan;
    return hz;
}

static int open_card(struct drm_device *d, const char *path, char *err, size_t n)
{
    snprintf(d->path, sizeof(d->path), "%s", path);
    d->fd = open(path, O_RDWR | O_CLOEXEC);
    if (d->fd < 0) {
        int rc = -errno;
        if (errno == ENOENT)
            snprintf(err, n, "DRM device %s does not exist (no display driver loaded? see ls /dev/dri)", path);
        else if (errno == EACCES)
            snprintf(err, n, "DRM device %s: permission denied (run as root or in group 'video')", path);
        else
            snprintf(err, n, "DRM device %s: cannot open it: %s", path, strerror(errno));
        return rc;
    }
    drmVersion *v = drmGetVersion(d->fd);
    snprintf(d->driver, sizeof(d->driver), "%s", v && v->name ? v->name : "?");
    drmFreeVersion(v);
    return 0;
}

static bool connector_matches(const drmModeConnector *c, const char *wanted)
{
    if (c->connector_type == DRM_MODE_CONNECTOR_WRITEBACK) return false;
    if (!wanted) return c->connection == DRM_MODE_CONNECTED && c->count_modes > 0;
    char name[32];
    connector_name(c, name, sizeof(name));
    return strcmp(name, wanted) == 0;
}

/* Lists "HDMI-A-1 (connected), DP-1 (disconnected)" for messages. */
static void list_connectors(int fd, const drmModeRes *res, char *out, size_t n)
{
    out[0] = '\0';
    for (int i = 0; i < res->count_connectors; i++) {
        drmModeConnector *c = drmModeGetConnector(fd, res->connectors[i]);
        if (!c) continue;
        char name[32];
        connector_name(c, name, sizeof(name));
        size_t used = strlen(out);
        snprintf(out + used, n - used, "%s%s (%s)", used ? ", " : "", name,
                 c->connection == DRM_MODE_CONNECTED ? "connected" : "not connected");
        drmModeFreeConnector(c);
    }
    if (!out[0]) snprintf(out, n, "none");
}

static drmModeConnector *find_connector(struct drm_device *d, const drmModeRes *res,
                                        const char *wanted, char *err, size_t n)
{
    for (int i = 0; i < res->count_connectors; i++) {
        drmModeConnector *c = drmModeGetConnector(d->fd, res->connectors[i]);
        if (c && connector_matches(c, wanted)) return c;
        drmModeFreeConnector(c);
    }
    char list[256];
    list_connectors(d->fd, res, list, sizeof(list));
    if (wanted)
        snprintf(err, n, "DRM device %s (%s): no connector '%s'; connectors: %s", d->path, d->driver,
                 wanted, list);
    else
        snprintf(err, n, "DRM device %s (%s): no connected display; connectors: %s", d->path,
                 d->driver, list);
    return NULL;
}

static int pick_mode(struct drm_device *d, const drmModeConnector *c, const char *wanted,
                     char *err, size_t n)
{
    int w = 0, h = 0, hz = 0, best = -1;
    if (wanted && mode_spec_parse(wanted, &w, &h, &hz) != 0) {
        snprintf(err, n, "mode '%s' is not WxH or WxH@HZ (e.g. 1920x1080@60)", wanted);
        return -EINVAL;
    }
    for (int i = 0; i < c->count_modes; i++) {
        const drmModeModeInfo *m = &c->modes[i];
        if (wanted && (m->hdisplay != w || m->vdisplay != h)) continue;
        if (wanted && hz && (int)(drm_mode_refresh(m) + 0.5) != hz) continue;
        if (best < 0 || (!wanted && (m->type & DRM_MODE_TYPE_PREFERRED))) best = i;
        if (wanted || (m->type & DRM_MODE_TYPE_PREFERRED)) break;
    }
    if (c->connection != DRM_MODE_CONNECTED || best < 0) {
        snprintf(err, n, "DRM device %s: connector %s %s", d->path, d->connector_name,
                 c->connection != DRM_MODE_CONNECTED ? "has no display connected"
                                                     : "offers no such mode (see modetest -c)");
        return c->connection != DRM_MODE_CONNECTED ? -ENODEV : -EINVAL;
    }
    d->mode = c->modes[best];
    return 0;
}

/* The CRTC of the connector's current encoder, else the first one an encoder can drive. */
static int pick_crtc(struct drm_device *d, const drmModeRes *res, const drmModeConnector *c,
                     char *err, size_t n)
{
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < c->count_encoders; i++) {
            if (pass == 0 && c->encoder_id != c->encoders[i]) continue;
            drmModeEncoder *e = drmModeGetEncoder(d->fd, c->encoders[i]);
            if (!e) continue;
            for (int k = 0; k < res->count_crtcs; k++) {
                bool ok = pass == 0 ? res->crtcs[k] == e->crtc_id : (e->possible_crtcs & (1u << k));
                if (!ok) continue;
                d->crtc_id = res->crtcs[k];
                d->crtc_index = k;
                drmModeFreeEncoder(e);
                return 0;
            }
            drmModeFreeEncoder(e);
        }
    snprintf(err, n, "DRM device %s: no CRTC can drive connector %s", d->path, d->connector_name);
    return -ENODEV;
}

static int plane_type(int fd, uint32_t plane_id)
{
    drmModeObjectProperties *props = drmModeObjectGetProperties(fd, plane_id, DRM_MODE_OBJECT_PLANE);
    int type = -1;
    for (uint32_t i = 0; props && i < props->count_props && type < 0; i++) {
        drmModePropertyRes *p = drmModeGetProperty(fd, props->props[i]);
        if (p && strcmp(p->name, "type") == 0) type = (int)props->prop_values[i];
        drmModeFreeProperty(p);
    }
    drmModeFreeObjectProperties(props);
    return type;
}

/* The CRTC's primary plane: atomic commits name it; legacy calls use it implicitly, so without
 * one (no universal planes) only atomic is ruled out, by drm_atomic_init. */
static void pick_plane(struct drm_device *d)
{
    if (drmSetClientCap(d->fd, DRM_CLIENT_CAP_UNIVERSAL_PLANES, 1) != 0) return;
    drmModePlaneRes *planes = drmModeGetPlaneResources(d->fd);
    for (uint32_t i = 0; planes && i < planes->count_planes && !d->plane_id; i++) {
        drmModePlane *p = drmModeGetPlane(d->fd, planes->planes[i]);
        if (p && (p->possible_crtcs & (1u << d->crtc_index)) &&
            plane_type(d->fd, p->plane_id) == DRM_PLANE_TYPE_PRIMARY)
            d->plane_id = p->plane_id;
        drmModeFreePlane(p);
    }
    drmModeFreePlaneResources(planes);
}

/* Connector, mode and CRTC on an open card. */
static int pick_output(struct drm_device *d, const struct drm_device_desc *desc, char *err, size_t n)
{
    drmModeRes *res = drmModeGetResources(d->fd);
    if (!res) {
        snprintf(err, n, "DRM device %s (%s) has no display (KMS) resources: a render-only GPU? "
                 "The display controller is another /dev/dri/card*", d->path, d->driver);
        return -ENODEV;
    }
    int rc = -ENODEV;
    drmModeConnector *c = find_connector(d, res, desc->connector, err, n);
    if (c) {
        d->connector_id = c->connector_id;
        connector_name(c, d->connector_name, sizeof(d->connector_name));
        rc = pick_mode(d, c, desc->mode, err, n);
        if (rc == 0) rc = pick_crtc(d, res, c, err, n);
        drmModeFreeConnector(c);
    }
    drmModeFreeResources(res);
    return rc;
}

static int become_master(struct drm_device *d, char *err, size_t n)
{
    if (drmIsMaster(d->fd) || drmSetMaster(d->fd) == 0) return 0;
    int rc = -errno;
    snprintf(err, n, "DRM device %s (%s) is in use: another program is DRM master (a display "
             "server or another sbfx-play; %s); stop it first", d->path, d->driver, strerror(errno));
    return rc ? rc : -EBUSY;
}

static int try_card(struct drm_device *d, const char *path, const struct drm_device_desc *desc,
                    char *err, size_t n)
{
    int rc = open_card(d, path, err, n);
    if (rc == 0) rc = pick_output(d, desc, err, n);
    if (rc && d->fd >= 0) {
        close(d->fd);
        d->fd = -1;
    }
    return rc;
}

static int find_card(struct drm_device *d, const struct drm_device_desc *desc, char *err, size_t n)
{
    if (desc->path) return try_card(d, desc->path, desc, err, n);
    char why[384] = "", path[32];
    int found = 0;
    for (int i = 0; i < DRM_DEVICE_MAX_CARDS; i++) {
        snprintf(path, sizeof(path), "/dev/dri/card%d", i);
        if (access(path, F_OK) != 0) continue;
        found++;
        if (try_card(d, path, desc, why, sizeof(why)) == 0) return 0;
    }
    if (!found)
        snprintf(err, n, "no DRM device in /dev/dri (no display driver loaded?); give one with --device");
    else
        snprintf(err, n, "no DRM device in /dev/dri drives a display (last: %s); give one with --device", why);
    return -ENODEV;
}

int drm_device_open(struct drm_device *d, const struct drm_device_desc *desc, char *err, size_t n)
{
    memset(d, 0, sizeof(*d));
    d->fd = -1;
    int rc = find_card(d, desc, err, n);
    if (rc == 0) rc = become_master(d, err, n);
    if (rc == 0) pick_plane(d);
    if (rc == 0) d->saved_crtc = drmModeGetCrtc(d->fd, d->crtc_id); /* NULL: nothing to restore */
    if (rc) drm_device_close(d);
    return rc;
}

int drm_device_restore(struct drm_device *d, char *err, size_t n)
{
    if (d->fd < 0) return 0;
    drmModeCrtc *s = d->saved_crtc;
    int r;
    if (s && s->mode_valid && s->buffer_id)
        r = drmModeSetCrtc(d->fd, s->crtc_id, s->buffer_id, s->x, s->y, &d->connector_id, 1, &s->mode);
    else
        r = drmModeSetCrtc(d->fd, d->crtc_id, 0, 0, 0, NULL, 0, NULL); /* it was off */
    if (r == 0) return 0;
    int rc = -errno;
    snprintf(err, n, "DRM device %s: restoring CRTC %u (drmModeSetCrtc): %s", d->path, d->crtc_id,
             strerror(errno));
    return rc;
}

void drm_device_close(struct drm_device *d)
{
    if (d->saved_crtc) drmModeFreeCrtc(d->saved_crtc);
    d->saved_crtc = NULL;
    if (d->props.mode_blob) drmModeDestroyPropertyBlob(d->fd, d->props.mode_blob);
    d->props.mode_blob = 0;
    if (d->fd >= 0) close(d->fd);
    d->fd = -1;
}

int drm_device_connector_connected(const struct drm_device *d)
{
    /* count_modes 1 (not 0): the kernel then reports the current state instead of probing
     * the connector again (libdrm's drmModeGetConnectorCurrent does the same, with mallocs) */
    struct drm_mode_modeinfo mode;
    struct drm_mode_get_connector c;
    memset(&c, 0, sizeof(c));
    c.connector_id = d->connector_id;
    c.count_modes = 1;
    c.modes_ptr = (uint64_t)(uintptr_t)&mode;
    if (drmIoctl(d->fd, DRM_IOCTL_MODE_GETCONNECTOR, &c) != 0) return -errno;
    return c.connection == DRM_MODE_CONNECTED;
}
