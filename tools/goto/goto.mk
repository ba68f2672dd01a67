# tools/goto/goto.mk - houghloc-goto, the destination client: sends one DESTINATION to
# houghlocd and waits for its REPLY. Included by the top Makefile.
#
# Like the daemon it sees include/ and src/daemon (for keyfile.h), never the generated
# LCM headers: messages go through src/bus. keyfile.o is linked on its own rather than
# through $(DAEMON_LIB), so the tool needs nothing else of the daemon.

GOTO_OBJS := $(BUILD)/obj/tools/goto/goto.o $(BUILD)/obj/tools/goto/goto_args.o \
             $(BUILD)/obj/src/daemon/keyfile.o

BINS              += $(BUILD)/bin/houghloc-goto
INTEGRATION_TESTS += tests/integration/test_goto.sh

$(BUILD)/obj/tools/goto/%.o: tools/goto/%.c
	@mkdir -p $(@D)
	@echo "  CC      $<"
	$(Q)$(CC) $(CORE_CPPFLAGS) -Isrc/daemon $(PKG_CFLAGS) $(CFLAGS) -c -o $@ $<

$(BUILD)/bin/houghloc-goto: $(GOTO_OBJS) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $(GOTO_OBJS) $(BUS_LIB) $(BUS_LDLIBS)
