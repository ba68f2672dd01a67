/* link_serial.c - the robot's serial port through libserialport (link.h). */
#define _XOPEN_SOURCE 700   /* realpath */
#include "link.h"

#include <errno.h>
#include <fcntl.h>
#include <libserialport.h>
#include <limits.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#define WHY(...) snprintf(why, HL_LINK_WHY_LEN, __VA_ARGS__)

/* libserialport's last error, with the hint a robot user needs for the usual ones. */
static void explain(char *why, const char *name, const char *step)
{
    int err = errno;
    char *msg = sp_last_error_message();
    const char *hint = err == EACCES ? " (is this user in the 'dialout' group?)"
                       : err == ENOENT ? " (is the robot's cable plugged in?)"
                       : "";
    WHY("%.200s: %s: %s%s", name, step, msg ? msg : strerror(err), hint);
    if (msg)
        sp_free_error_message(msg);
}

bool hl_link_open_serial(hl_link_t *l, const hl_link_spec_t *spec, char *why)
{
    /* libserialport knows a port only by its /dev name (it looks it up under
     * /sys/class/tty), so the stable udev links (/dev/serial/by-id/...) are resolved */
    char real[PATH_MAX];
    if (!realpath(spec->device, real)) {
        WHY("%.200s: %s (is the robot's cable plugged in?)", l->name, strerror(errno));
        return false;
    }
    if (sp_get_port_by_name(real, &l->port) != SP_OK) {
        l->port = NULL;
        WHY("%.150s: %.100s is not a serial port libserialport knows", l->name, real);
        return false;
    }
    if (sp_open(l->port, SP_MODE_READ_WRITE) != SP_OK) {
        explain(why, l->name, "cannot open");
        sp_free_port(l->port);
        l->port = NULL;
        return false;
    }
    /* ARCOS: 8 data bits, no parity, one stop bit, no flow control */
    if (sp_set_baudrate(l->port, spec->baud) != SP_OK || sp_set_bits(l->port, 8) != SP_OK ||
        sp_set_parity(l->port, SP_PARITY_NONE) != SP_OK ||
        sp_set_stopbits(l->port, 1) != SP_OK ||
        sp_set_flowcontrol(l->port, SP_FLOWCONTROL_NONE) != SP_OK) {
        explain(why, l->name, "cannot configure");
        return false;
    }
    if (sp_get_port_handle(l->port, &l->fd) != SP_OK || l->fd < 0) {
        explain(why, l->name, "no file descriptor");
        return false;
    }
    int flags = fcntl(l->fd, F_GETFL);
    if (flags < 0 || fcntl(l->fd, F_SETFL, flags | O_NONBLOCK) != 0) {
        WHY("%.200s: cannot make it non-blocking: %s", l->name, strerror(errno));
        return false;
    }
    return true;
}

void hl_link_close_serial(hl_link_t *l)
{
    if (!l->port)
        return;
    sp_close(l->port);      /* harmless on a port that did not open */
    sp_free_port(l->port);
    l->port = NULL;
    l->fd = -1;
}
