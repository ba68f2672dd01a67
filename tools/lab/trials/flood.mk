# tools/lab/trials/flood.mk - the programs of the Flood and Commands trials (make trials):
# hl-flood publishes malformed LCM messages on houghlocd's inputs (flood.c, flood_msg.c);
# hl-forge sends signed, forged, replayed, stale, unsigned and out-of-fence requests and
# checks each REPLY (forge.c, forge_req.c); hl-poison writes the Poison trial's poisoned
# copy of a log (poison.c). Included by tools/lab/lab.mk.
#
# Like houghloc-goto they see the layers' public headers (the key through the store
# library), never the generated LCM headers: messages go through src/bus.

FLOOD_OBJS := $(BUILD)/obj/tools/lab/trials/flood.o $(BUILD)/obj/tools/lab/trials/flood_msg.o \
              $(BUILD)/obj/tools/lab/trials/trial_args.o
FORGE_OBJS := $(BUILD)/obj/tools/lab/trials/forge.o $(BUILD)/obj/tools/lab/trials/forge_req.o \
              $(BUILD)/obj/tools/lab/trials/trial_args.o

POISON_OBJS := $(BUILD)/obj/tools/lab/trials/poison.o

LAB_BINS += $(BUILD)/bin/hl-flood $(BUILD)/bin/hl-forge $(BUILD)/bin/hl-poison
# houghloc-goto against hl-forge's forged replies.
LAB_INTEGRATION_TESTS += tools/lab/tests/test_forged_replies.sh

$(BUILD)/obj/tools/lab/trials/%.o: tools/lab/trials/%.c
	@mkdir -p $(@D)
	@echo "  CC      $<"
	$(Q)$(CC) $(TOOL_CPPFLAGS) $(PKG_CFLAGS) $(CFLAGS) -c -o $@ $<

$(BUILD)/bin/hl-flood: $(FLOOD_OBJS) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $(FLOOD_OBJS) $(BUS_LIB) $(BUS_LDLIBS)

$(BUILD)/bin/hl-forge: $(FORGE_OBJS) $(STORE_LIB) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $(FORGE_OBJS) $(STORE_LIB) $(STORE_LDLIBS)

$(BUILD)/bin/hl-poison: $(POISON_OBJS) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $(POISON_OBJS) $(BUS_LIB) $(BUS_LDLIBS)
