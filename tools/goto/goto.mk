# tools/goto/goto.mk - the two clients of houghlocd's requests: houghloc-goto sends one
# DESTINATION, houghloc-ctl one COMMAND (set-pose, save, relocalize); each waits for its
# REPLY. Both are thin mains over request.c (options, signing, publishing, the wait).
# Included by the top Makefile.
#
# They see the layers' public headers (TOOL_CPPFLAGS), never the generated LCM headers:
# messages go through src/bus. The signing key is read by the store library
# (houghloc/keyfile.h), so the tools need nothing of the daemon.

REQUEST_OBJS := $(BUILD)/obj/tools/goto/request.o
GOTO_OBJS := $(BUILD)/obj/tools/goto/goto.o $(BUILD)/obj/tools/goto/goto_args.o \
             $(REQUEST_OBJS)
CTL_OBJS  := $(BUILD)/obj/tools/goto/ctl.o $(BUILD)/obj/tools/goto/ctl_args.o \
             $(REQUEST_OBJS)

BINS              += $(BUILD)/bin/houghloc-goto $(BUILD)/bin/houghloc-ctl
INTEGRATION_TESTS += tests/integration/test_goto.sh tests/integration/test_ctl.sh \
                     tests/integration/test_recipe.sh

$(BUILD)/obj/tools/goto/%.o: tools/goto/%.c
	@mkdir -p $(@D)
	@echo "  CC      $<"
	$(Q)$(CC) $(TOOL_CPPFLAGS) $(PKG_CFLAGS) $(CFLAGS) -c -o $@ $<

$(BUILD)/bin/houghloc-goto: $(GOTO_OBJS) $(STORE_LIB) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $(GOTO_OBJS) $(STORE_LIB) $(STORE_LDLIBS)

$(BUILD)/bin/houghloc-ctl: $(CTL_OBJS) $(STORE_LIB) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $(CTL_OBJS) $(STORE_LIB) $(STORE_LDLIBS)
