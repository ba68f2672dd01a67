/* args.c - houghloc-console's command line (args.h). */
#include "args.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "truth_frame.h"

#define STR_(x) #x
#define STR(x) STR_(x)

static const char usage_text[] =
    "Usage: " PROG " [options]\n"
    "\n"
    "The operator console of houghlocd: serves one self-contained web page showing the\n"
    "live map, the robot's pose and confidence, its trajectory, the destination under way,\n"
    "the way planned to it and the daemon's status; a click on the map sends the robot\n"
    "there (drag from the click to give the heading to arrive with), the STOP button or\n"
    "the Escape key stops it at once. It subscribes to MAP, POSE, STATUS, REPLY and PATH\n"
    "(and GROUND_TRUTH with --ground-truth) and publishes DESTINATION and COMMAND STOP,\n"
    "signed with --key when the daemon has one; the daemon's geofence still applies.\n"
    "\n"
    "Options:\n"
    "  --lcm-url URL       the LCM network (default $LCM_DEFAULT_URL, else\n"
    "                      " REQ_DEFAULT_URL ")\n"
    "  --prefix P          the daemon's channel prefix (default none)\n"
    "  --key FILE          sign every DESTINATION and STOP with the key in FILE (64\n"
    "                      hexadecimal digits, mode 600), as a daemon configured with a\n"
    "                      key requires, and show only REPLY messages signed with it;\n"
    "                      the browser never sees the key\n"
    "  --listen ADDR:PORT  where to serve the page (default 127.0.0.1:" STR(CONSOLE_DEFAULT_PORT) ",\n"
    "                      this host only)\n"
    "  --token-file FILE   the token (16 to 128 letters, digits, '-', '_', '.', '~'; mode\n"
    "                      600); default: a random one, printed at start\n"
    "  --token-out FILE    write the random token to FILE (made anew, mode 600) instead\n"
    "                      of printing it\n"
    "  --ground-truth      also show GROUND_TRUTH (the simulated robot's true pose), in\n"
    "                      the map frame: its first pose heard is drawn at the daemon's\n"
    "                      start pose (start the console before the robot moves)\n"
    "  --start X,Y,DEG     the daemon's start pose, [start] in its configuration\n"
    "                      (default 0,0,0, the daemon's default)\n"
    "  --help              this text\n"
    "  --version           the version\n"
    "\n"
    "Every request needs the token: open http://ADDR:PORT/?token=TOKEN once (the page\n"
    "then holds a session cookie), or send \"Authorization: Bearer TOKEN\" (scripts).\n"
    "Log lines go to standard error, each starting with \"" PROG ": \"; the first\n"
    "names the page's address with the token. SIGINT or SIGTERM stop it.\n"
    "\n"
    "Examples:\n"
    "  " PROG "\n"
    "      then open http://127.0.0.1:" STR(CONSOLE_DEFAULT_PORT) "/ on this machine\n"
    "  " PROG " --key /etc/houghloc/key --listen 0.0.0.0:8047 --token-file ~/.console-token\n"
    "      serve the robot's network, destinations signed\n"
    "\n"
    "Exit status:\n"
    "  0  stopped by SIGINT or SIGTERM; also --help, --version\n"
    "  1  error: LCM or the web server could not start, a key or token file refused\n"
    "  2  bad usage\n";

bool console_parse_listen(const char *s, console_options_t *o)
{
    const char *colon = strrchr(s, ':');
    if (!colon || colon == s)
        return false;
    size_t hn = (size_t)(colon - s);
    if (hn >= sizeof o->host)
        return false;
    char host[sizeof o->host];
    memcpy(host, s, hn);
    host[hn] = '\0';
    /* the port: 1..65535, decimal digits only */
    const char *p = colon + 1;
    if (!*p || strlen(p) > 5 || strspn(p, "0123456789") != strlen(p) || *p == '0')
        return false;
    long port = strtol(p, NULL, 10);
    if (port < 1 || port > 65535)
        return false;
    memset(&o->addr, 0, sizeof o->addr);
    if (host[0] == '[' && hn > 2 && host[hn - 1] == ']') {
        char v6[sizeof o->host];
        memcpy(v6, host + 1, hn - 2);
        v6[hn - 2] = '\0';
        struct sockaddr_in6 *a = (struct sockaddr_in6 *)&o->addr;
        if (inet_pton(AF_INET6, v6, &a->sin6_addr) != 1)
            return false;
        a->sin6_family = AF_INET6;
        a->sin6_port = htons((uint16_t)port);
        o->addrlen = sizeof *a;
        o->loopback = IN6_IS_ADDR_LOOPBACK(&a->sin6_addr);
    } else {
        struct sockaddr_in *a = (struct sockaddr_in *)&o->addr;
        const char *v4 = strcmp(host, "localhost") == 0 ? "127.0.0.1" : host;
        if (inet_pton(AF_INET, v4, &a->sin_addr) != 1)
            return false;
        a->sin_family = AF_INET;
        a->sin_port = htons((uint16_t)port);
        o->addrlen = sizeof *a;
        o->loopback = (ntohl(a->sin_addr.s_addr) >> 24) == 127;
    }
    o->port = (uint16_t)port;
    memcpy(o->host, host, hn + 1);
    return true;
}

/* Sets option @p name to @p v. @return WAITING, or EXIT_USAGE after the message. */
static int set_value(console_options_t *o, const char *name, const char *v)
{
    if (!*v)
        return req_usage_error(PROG, "%s is empty", name);
    if (strcmp(name, "--listen") == 0) {
        if (!console_parse_listen(v, o))
            return req_usage_error(PROG,
                                   "--listen \"%s\": give ADDR:PORT, e.g. 127.0.0.1:8047 or "
                                   "[::1]:8047",
                                   v);
        o->listen = v;
    } else if (strcmp(name, "--start") == 0) {
        char why[HL_TRUTH_FRAME_WHY_LEN];
        if (!hl_truth_frame_parse_pose(v, &o->start, why))
            return req_usage_error(PROG, "--start %s", why);
    } else if (strcmp(name, "--token-out") == 0) {
        o->token_out = v;
    } else {
        o->token_file = v;
    }
    return WAITING;
}

/* "--name=VALUE", or "--name" with the value in the next argument (then `pending`, which
 * on_positional takes, as req_walk_args hands the option callback one argument). */
static int take_value(console_options_t *o, const char *arg, const char *name)
{
    size_t n = strlen(name);
    if (arg[n] == '=')
        return set_value(o, name, arg + n + 1);
    o->pending = name;
    return WAITING;
}

static int on_option(void *user, const char *arg)
{
    console_options_t *o = user;
    if (o->pending)
        return req_usage_error(PROG, "%s needs a value", o->pending);
    static const char *const valued[] = { "--listen", "--token-file", "--token-out", "--start" };
    for (int i = 0; i < 4; i++) {
        size_t n = strlen(valued[i]);
        if (strncmp(arg, valued[i], n) == 0 && (arg[n] == '\0' || arg[n] == '='))
            return take_value(o, arg, valued[i]);
    }
    if (strcmp(arg, "--ground-truth") == 0) {
        o->ground_truth = true;
        return WAITING;
    }
    /* request.c's --timeout and --deadline are for clients that wait for an answer */
    if ((strncmp(arg, "--timeout", 9) == 0 && (arg[9] == '\0' || arg[9] == '=')) ||
        (strncmp(arg, "--deadline", 10) == 0 && (arg[10] == '\0' || arg[10] == '=')))
        return req_usage_error(PROG, "unknown option \"%s\"", arg);
    return REQ_NOT_MINE;
}

static int on_positional(void *user, const char *arg)
{
    console_options_t *o = user;
    if (!o->pending)
        return req_usage_error(PROG, "unexpected argument \"%s\"", arg);
    const char *name = o->pending;
    o->pending = NULL;
    return set_value(o, name, arg);
}

int console_parse_args(int argc, char **argv, console_options_t *o)
{
    if (!console_parse_listen("127.0.0.1:" STR(CONSOLE_DEFAULT_PORT), o))
        return EXIT_ERROR;
    const req_args_t args = { .prog = PROG, .usage = usage_text, .positional = on_positional,
                              .option = on_option, .user = o };
    int rc = req_walk_args(&args, argc, argv, &o->req);
    if (rc != WAITING)
        return rc;
    if (o->pending)
        return req_usage_error(PROG, "%s needs a value", o->pending);
    if (o->token_file && o->token_out)
        return req_usage_error(PROG, "--token-out writes a random token: it does not go "
                                     "with --token-file");
    return WAITING;
}
