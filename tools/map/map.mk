# tools/map/map.mk - houghloc-map: a houghloc map (map file or the last MAP of a log) as
# a PNG picture and as a ROS map_server occupancy grid (PGM + YAML). Included by the top
# Makefile.
#
# It reads map files with the daemon's own loader (the store library, src/store) and
# logs with houghloc-eval's reader (tools/eval/runlog.o); messages go through src/bus.

MAP_TOOL_OBJS := $(BUILD)/obj/tools/map/houghloc_map.o $(BUILD)/obj/tools/map/mapgrid.o \
                 $(BUILD)/obj/tools/map/mapdraw.o $(BUILD)/obj/tools/eval/runlog.o \
                 $(BUILD)/obj/tools/eval/truth_frame.o

BINS              += $(BUILD)/bin/houghloc-map
INTEGRATION_TESTS += tests/integration/test_map_tool.sh

$(BUILD)/obj/tools/map/%.o: tools/map/%.c
	@mkdir -p $(@D)
	@echo "  CC      $<"
	$(Q)$(CC) $(TOOL_CPPFLAGS) -Itools/eval $(PKG_CFLAGS) $(CAIRO_CFLAGS) \
	    $(CFLAGS) -c -o $@ $<

$(BUILD)/bin/houghloc-map: $(MAP_TOOL_OBJS) $(STORE_LIB) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $(MAP_TOOL_OBJS) $(STORE_LIB) $(STORE_LDLIBS) $(CAIRO_LIBS)
