# src/bus/bus.mk - the bus library: LCM messages <-> houghloc structs, log checking,
# message authentication (libsodium). The only code under src/ that sees lcm-gen output.

SODIUM_LIBS := $(shell pkg-config --libs libsodium 2>/dev/null)

BUS_SRCS      := $(sort $(wildcard src/bus/*.c))
BUS_OBJS      := $(call obj,$(BUS_SRCS))
BUS_ASAN_OBJS := $(call asanobj,$(BUS_SRCS))
BUS_LIB       := $(BUILD)/lib/libhoughloc_bus.a
BUS_ASAN_LIB  := $(BUILD)/lib/libhoughloc_bus_asan.a
# What a program linking $(BUS_LIB) also needs after it.
BUS_LDLIBS    := $(LCM_LIB) $(CORE_LIB) $(PKG_LIBS) $(SODIUM_LIBS) $(SYS_LIBS)

BUS_TESTS := $(patsubst tests/bus/%.c,$(BUILD)/tests/bus/%,$(wildcard tests/bus/test_*.c))
TEST_BINS += $(BUS_TESTS)

# Its own include paths: the core's and the bus's public headers and the generated code.
$(BUILD)/obj/src/bus/%.o: src/bus/%.c | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CC      $<"
	$(Q)$(CC) $(BUS_CPPFLAGS) $(PKG_CFLAGS) $(CFLAGS) -c -o $@ $<
$(BUILD)/asan/src/bus/%.o: src/bus/%.c | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CC-SAN  $<"
	$(Q)$(CC) $(BUS_CPPFLAGS) $(PKG_CFLAGS) $(CFLAGS) $(SAN) -c -o $@ $<

$(BUS_LIB): $(BUS_OBJS)
$(BUS_ASAN_LIB): $(BUS_ASAN_OBJS)

# Every bus test links with $(SAN): test_codec_noalloc counts allocations through
# AddressSanitizer's malloc hook, so it needs no link rule of its own.
$(BUILD)/tests/bus/%: $(BUILD)/asan/tests/bus/%.o $(BUS_ASAN_LIB) $(LCM_LIB) $(CORE_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CC) $(SAN) -o $@ $^ $(CMOCKA_LIBS) $(PKG_LIBS) $(SODIUM_LIBS) $(SYS_LIBS)
