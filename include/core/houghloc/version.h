/* version.h - the houghloc release every program reports with --version. */
#ifndef HOUGHLOC_VERSION_H
#define HOUGHLOC_VERSION_H

#define HL_VERSION "0.3.0"

#endif
