# src/daemon/daemon.mk - houghlocd: the daemon (config, poll loop, cycle, publishing, map
# persistence, authentication keys). The only code that owns fds, timers and signals.
# It sees every layer's public headers and its own folder, never the generated LCM
# headers (messages go through src/bus); of the internal ones only its own folder,
# include/internal/daemon (houghloc-internal/daemon_config.h, which it implements for the
# laboratory's tools), never the core's.

DAEMON_CPPFLAGS := $(PUBLIC_INC) $(DAEMON_INTERNAL_INC) -Isrc/daemon $(HL_DEFS)
DAEMON_PKGS     := inih libsystemd zlib libserialport
DAEMON_CFLAGS   := $(shell pkg-config --cflags $(DAEMON_PKGS) 2>/dev/null) $(PKG_CFLAGS)
DAEMON_LIBS     := $(shell pkg-config --libs $(DAEMON_PKGS) 2>/dev/null)

# Everything but main.c goes into a library that the tests and tools link.
DAEMON_LIB_SRCS := $(sort $(filter-out src/daemon/main.c,$(wildcard src/daemon/*.c)))
DAEMON_OBJS      := $(patsubst %.c,$(BUILD)/obj/%.o,$(DAEMON_LIB_SRCS))
DAEMON_ASAN_OBJS := $(patsubst %.c,$(BUILD)/asan/%.o,$(DAEMON_LIB_SRCS))
DAEMON_LIB       := $(BUILD)/lib/libhoughloc_daemon.a
DAEMON_ASAN_LIB  := $(BUILD)/lib/libhoughloc_daemon_asan.a
# What a program linking $(DAEMON_LIB) also needs after it.
DAEMON_LDLIBS    := $(ROBOT_LIB) $(STORE_LIB) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB) $(DAEMON_LIBS) $(PKG_LIBS) $(SODIUM_LIBS) $(SYS_LIBS)
DAEMON_ASAN_LDLIBS := $(ROBOT_ASAN_LIB) $(STORE_ASAN_LIB) $(BUS_ASAN_LIB) $(LCM_LIB) $(CORE_ASAN_LIB) $(DAEMON_LIBS) $(PKG_LIBS) $(SODIUM_LIBS) $(SYS_LIBS)

DAEMON_TESTS := $(patsubst tests/daemon/%.c,$(BUILD)/tests/daemon/%,$(wildcard tests/daemon/test_*.c))
TEST_BINS += $(DAEMON_TESTS)
BINS      += $(BUILD)/bin/houghlocd

$(BUILD)/obj/src/daemon/%.o: src/daemon/%.c
	@mkdir -p $(@D)
	@echo "  CC      $<"
	$(Q)$(CC) $(DAEMON_CPPFLAGS) $(DAEMON_CFLAGS) $(CFLAGS) -c -o $@ $<
$(BUILD)/asan/src/daemon/%.o: src/daemon/%.c
	@mkdir -p $(@D)
	@echo "  CC-SAN  $<"
	$(Q)$(CC) $(DAEMON_CPPFLAGS) $(DAEMON_CFLAGS) $(CFLAGS) $(SAN) -c -o $@ $<
# The daemon's tests also read the store tests' map file fixture (tests/store).
$(BUILD)/asan/tests/daemon/%.o: tests/daemon/%.c
	@mkdir -p $(@D)
	@echo "  CC-SAN  $<"
	$(Q)$(CC) $(DAEMON_CPPFLAGS) -Itests/store $(DAEMON_CFLAGS) $(CFLAGS) $(SAN) -c -o $@ $<

$(DAEMON_LIB): $(DAEMON_OBJS)
$(DAEMON_ASAN_LIB): $(DAEMON_ASAN_OBJS)

$(BUILD)/bin/houghlocd: $(BUILD)/obj/src/daemon/main.o $(DAEMON_LIB) $(ROBOT_LIB) $(STORE_LIB) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $(BUILD)/obj/src/daemon/main.o $(DAEMON_LIB) $(DAEMON_LDLIBS)

$(BUILD)/tests/daemon/%: $(BUILD)/asan/tests/daemon/%.o $(DAEMON_ASAN_LIB) $(ROBOT_ASAN_LIB) $(STORE_ASAN_LIB) $(BUS_ASAN_LIB) $(LCM_LIB) $(CORE_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CC) $(SAN) -o $@ $< $(DAEMON_ASAN_LIB) $(DAEMON_ASAN_LDLIBS) $(CMOCKA_LIBS)

INTEGRATION_TESTS += tests/integration/test_daemon.sh tests/integration/test_mapmsg.sh tests/integration/test_maplock.sh

# 100 kill -9 trials of a replay (the test suite runs 20).
.PHONY: crash-trials
crash-trials: $(BUILD)/bin/houghlocd
	$(Q)BUILD=$(BUILD) sh tests/integration/crash_trials.sh 100

# test_alloc counts the allocations of houghloc's own code (see the test).
$(BUILD)/tests/daemon/test_alloc: $(BUILD)/asan/tests/daemon/test_alloc.o $(DAEMON_ASAN_LIB) $(ROBOT_ASAN_LIB) $(STORE_ASAN_LIB) $(BUS_ASAN_LIB) $(LCM_LIB) $(CORE_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CC) $(SAN) -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc -o $@ $< $(DAEMON_ASAN_LIB) $(DAEMON_ASAN_LDLIBS) $(CMOCKA_LIBS)
