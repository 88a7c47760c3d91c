/* The plugin `sbfx` (libgstsbfx.so): one element, `sbfx` (gstsbfx.h). */
#include "gstsbfx.h"

#ifndef SBFX_VERSION
#error "SBFX_VERSION: the Makefile's VERSION, given by the build"
#endif

static gboolean plugin_init(GstPlugin *plugin)
{
    return gst_element_register(plugin, "sbfx", GST_RANK_NONE, GST_TYPE_SBFX);
}

/* GST_PLUGIN_DEFINE's package fields. The source tree names no licence: GStreamer's "unknown". */
#define PACKAGE "sbfx"
#define GST_PACKAGE_NAME "sbfx"
#define GST_PACKAGE_ORIGIN "sbfx's source tree, integrations/gstreamer/"

GST_PLUGIN_DEFINE(GST_VERSION_MAJOR, GST_VERSION_MINOR, sbfx, "sbfx volumetric particle effects on GStreamer's GL",
                  plugin_init, SBFX_VERSION, GST_LICENSE_UNKNOWN, GST_PACKAGE_NAME, GST_PACKAGE_ORIGIN)
