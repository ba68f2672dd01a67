/*
 * link.h - the byte stream to the robot: a serial port through libserialport (the robot
 * itself), a TCP connection (the simulated robot, as Pioneer's own simulator offers on
 * port 8101), or a file holding a captured stream of a robot's bytes (houghloc-sim
 * --capture), replayed as gpsd's gpsfake replays a GPS: what the daemon writes goes
 * nowhere, and the end of the file ends the replay (hl_link_ended). Each gives one file
 * descriptor for the event loop; the ARCOS connection on top (houghloc/rlink.h) does not
 * know which it talks over.
 *
 *     tcp:HOST:PORT              e.g. tcp:127.0.0.1:8101
 *     serial:DEVICE[,BAUD]       e.g. serial:/dev/ttyUSB0 (9600 baud, ARCOS's default)
 *     file:CAPTURE               e.g. file:tests/golden/arcos.capture
 */
#ifndef HOUGHLOC_DAEMON_LINK_H
#define HOUGHLOC_DAEMON_LINK_H

#include <stdbool.h>
#include <stddef.h>
#include <sys/types.h>

#define HL_LINK_SPEC_MAX 256
#define HL_LINK_WHY_LEN 320

typedef enum hl_link_kind { HL_LINK_TCP, HL_LINK_SERIAL, HL_LINK_FILE } hl_link_kind_t;

typedef struct hl_link_spec {
    hl_link_kind_t kind;
    char host[HL_LINK_SPEC_MAX];    /* tcp */
    char port[8];                   /* tcp: 1..65535 */
    char device[HL_LINK_SPEC_MAX];  /* serial */
    int baud;                       /* serial: 9600, 19200, 38400, 57600 or 115200 */
    char path[HL_LINK_SPEC_MAX];    /* file: the capture */
} hl_link_spec_t;

/** Parses a link as above. @return false with one line in @p why (HL_LINK_WHY_LEN). */
bool hl_link_spec_parse(const char *text, hl_link_spec_t *out, char *why);

typedef struct hl_link hl_link_t;

/**
 * Starts opening the link. A TCP connection may still be under way: wait for the fd to
 * become writable, then call hl_link_connected.
 * @return NULL with one line in @p why (a missing device, a permission, a refused host).
 */
hl_link_t *hl_link_open(const hl_link_spec_t *spec, char *why);
void hl_link_close(hl_link_t *l);           /* accepts NULL */

int hl_link_fd(const hl_link_t *l);
/** Whether a TCP connection is still being made. */
bool hl_link_connecting(const hl_link_t *l);
/** After the fd turned writable while connecting: @return false with why if it failed. */
bool hl_link_connected(hl_link_t *l, char *why);

/** @return bytes read (> 0), 0 if none are waiting, -1 with why on an error or the end of
 *  the stream. */
ssize_t hl_link_read(hl_link_t *l, void *buf, size_t n, char *why);
/** @return bytes written (>= 0, maybe fewer than n), -1 with why on an error. A file link
 *  takes them all and keeps none. */
ssize_t hl_link_write(hl_link_t *l, const void *buf, size_t n, char *why);

/** Whether a file link has read the end of its capture (hl_link_read said so once). */
bool hl_link_ended(const hl_link_t *l);

/* The serial transport (link_serial.c, libserialport) and the file one (link_file.c)
 * behind hl_link_open, hl_link_close, hl_link_read and hl_link_write; the TCP one is in
 * link.c. */
struct sp_port;
struct hl_link {
    hl_link_kind_t kind;
    int fd;
    bool connecting;
    bool ended;                 /* file: the end of the capture was read */
    struct sp_port *port;       /* serial */
    char name[HL_LINK_SPEC_MAX + 16];
};
bool hl_link_open_serial(hl_link_t *l, const hl_link_spec_t *spec, char *why);
void hl_link_close_serial(hl_link_t *l);
bool hl_link_open_file(hl_link_t *l, const hl_link_spec_t *spec, char *why);
ssize_t hl_link_read_file(hl_link_t *l, void *buf, size_t n, char *why);

#endif
