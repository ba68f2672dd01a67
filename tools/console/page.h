/* page.h - the console's web page, tools/console/page.html, embedded at build time into
 * $(BUILD)/gen/console_page.c by embed.c (never committed). */
#ifndef HOUGHLOC_TOOLS_CONSOLE_PAGE_H
#define HOUGHLOC_TOOLS_CONSOLE_PAGE_H

#include <stddef.h>

extern const char hl_console_page[];
extern const size_t hl_console_page_len;

#endif
