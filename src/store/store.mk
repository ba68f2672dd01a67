# src/store/store.mk - the store library: the files a daemon keeps between runs and its
# tools read, each written whole or not at all (fileio.c: temp + fsync + rename) and
# checked on the way in: the map file (mapstore.c, zlib's crc32) and its lock
# (mapstore_lock.c), the request state file (seqfile.c) and the request-signing key
# (keyfile.c, libsodium; the key's text parsed by the bus's auth.c). The daemon links it,
# and so do houghloc-map, houghloc-goto, houghloc-ctl, the console and the laboratory's
# tools, without the daemon's library.
STORE_PKGS      := zlib libsodium
STORE_CFLAGS    := $(shell pkg-config --cflags $(STORE_PKGS) 2>/dev/null)
STORE_SRCS      := $(sort $(wildcard src/store/*.c))
STORE_OBJS      := $(call obj,$(STORE_SRCS))
STORE_ASAN_OBJS := $(call asanobj,$(STORE_SRCS))
STORE_LIB       := $(BUILD)/lib/libhoughloc_store.a
STORE_ASAN_LIB  := $(BUILD)/lib/libhoughloc_store_asan.a
# What a program linking $(STORE_LIB) also needs after it.
STORE_PKG_LIBS  := $(shell pkg-config --libs $(STORE_PKGS) 2>/dev/null)
STORE_LDLIBS    := $(BUS_LIB) $(BUS_LDLIBS) $(STORE_PKG_LIBS)

STORE_TESTS := $(patsubst tests/store/%.c,$(BUILD)/tests/store/%,$(wildcard tests/store/test_*.c))
TEST_BINS += $(STORE_TESTS)

$(BUILD)/obj/src/store/%.o: src/store/%.c
	@mkdir -p $(@D)
	@echo "  CC      $<"
	$(Q)$(CC) $(STORE_CPPFLAGS) $(STORE_CFLAGS) $(CFLAGS) -c -o $@ $<
$(BUILD)/asan/src/store/%.o: src/store/%.c
	@mkdir -p $(@D)
	@echo "  CC-SAN  $<"
	$(Q)$(CC) $(STORE_CPPFLAGS) $(STORE_CFLAGS) $(CFLAGS) $(SAN) -c -o $@ $<
$(BUILD)/asan/tests/store/%.o: tests/store/%.c
	@mkdir -p $(@D)
	@echo "  CC-SAN  $<"
	$(Q)$(CC) $(STORE_CPPFLAGS) $(STORE_CFLAGS) $(CFLAGS) $(SAN) -c -o $@ $<

$(STORE_LIB): $(STORE_OBJS)
$(STORE_ASAN_LIB): $(STORE_ASAN_OBJS)

$(BUILD)/tests/store/%: $(BUILD)/asan/tests/store/%.o $(STORE_ASAN_LIB) $(BUS_ASAN_LIB) $(LCM_LIB) \
        $(CORE_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CC) $(SAN) -o $@ $< $(STORE_ASAN_LIB) $(BUS_ASAN_LIB) $(LCM_LIB) $(CORE_ASAN_LIB) \
	    $(PKG_LIBS) $(STORE_PKG_LIBS) $(CMOCKA_LIBS) $(SYS_LIBS)
