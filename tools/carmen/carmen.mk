# tools/carmen/carmen.mk - houghloc-import-carmen: CARMEN laser logs (plain or gzip) to
# LCM event logs of SONAR, ODOMETRY and GROUND_TRUTH that houghlocd replays
# (docs/manual/real-data.md). Included by the top Makefile.
#
# Like the daemon it sees include/ and never the generated LCM headers: messages are
# encoded and checked by src/bus. zlib reads the gzip logs.

ZLIB_CFLAGS := $(shell pkg-config --cflags zlib 2>/dev/null)
ZLIB_LIBS   := $(shell pkg-config --libs zlib 2>/dev/null)

CARMEN_SRCS := tools/carmen/import_carmen.c tools/carmen/carmen_args.c \
               tools/carmen/carmen_import.c tools/carmen/carmen_dump.c \
               tools/carmen/carmen_log.c tools/carmen/carmen_tum.c tools/carmen/carmen_scan.c
CARMEN_OBJS := $(call obj,$(CARMEN_SRCS))

BINS              += $(BUILD)/bin/houghloc-import-carmen
INTEGRATION_TESTS += tests/integration/test_import.sh

$(BUILD)/obj/tools/carmen/%.o: tools/carmen/%.c
	@mkdir -p $(@D)
	@echo "  CC      $<"
	$(Q)$(CC) $(TOOL_CPPFLAGS) $(PKG_CFLAGS) $(ZLIB_CFLAGS) $(CFLAGS) -c -o $@ $<

$(BUILD)/bin/houghloc-import-carmen: $(CARMEN_OBJS) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $(CARMEN_OBJS) $(BUS_LIB) $(BUS_LDLIBS) $(ZLIB_LIBS)
