# tools/console/console.mk - houghloc-console: the operator console, houghlocd's live map
# and pose in a browser, click to send the robot somewhere (docs/manual/houghloc-console.md). Included by
# the top Makefile.
#
# Like houghloc-goto it sees the layers' public headers and tools/goto (request.h), never
# the generated LCM headers: messages go through src/bus. It links tools/goto's request.o
# for the options it shares with the clients, and the store library for the key.
# The page, tools/console/page.html, is embedded by hl-embed into $(BUILD)/gen (never
# committed). (This file is read before tools/goto/goto.mk: it names request.o itself.)
# GROUND_TRUTH is moved into the map frame by tools/eval's truth_frame.c (unit-tested
# here, tests/console/test_truth_frame.c).

MHD_CFLAGS := $(shell pkg-config --cflags libmicrohttpd 2>/dev/null)
MHD_LIBS   := $(shell pkg-config --libs libmicrohttpd 2>/dev/null)

# The pure modules (libsodium apart), unit-tested under the sanitizers; the rest touches
# sockets and LCM.
CONSOLE_PURE := jbuf bridge destreq stamp access hub gate
CONSOLE_OBJS := $(patsubst %,$(BUILD)/obj/tools/console/%.o,$(CONSOLE_PURE) args listen http sender main) \
                $(BUILD)/obj/gen/console_page.o $(BUILD)/obj/tools/eval/truth_frame.o \
                $(BUILD)/obj/tools/goto/request.o
CONSOLE_ASAN_OBJS := $(patsubst %,$(BUILD)/asan/tools/console/%.o,$(CONSOLE_PURE)) \
                     $(BUILD)/asan/tools/eval/truth_frame.o
CONSOLE_TESTS := $(patsubst tests/console/%.c,$(BUILD)/tests/console/%,$(wildcard tests/console/test_*.c))
CONSOLE_CPPFLAGS := $(TOOL_CPPFLAGS) -Itools/goto -Itools/console -Itools/eval

BINS              += $(BUILD)/bin/houghloc-console
TEST_BINS         += $(CONSOLE_TESTS)
INTEGRATION_TESTS += tests/integration/test_console.sh tests/console/browser_test.sh

.PHONY: test-console
# kept between builds (make would delete them as intermediate files of the test rule)
.SECONDARY: $(CONSOLE_ASAN_OBJS) $(patsubst $(BUILD)/tests/%,$(BUILD)/asan/tests/%.o,$(CONSOLE_TESTS))

$(BUILD)/bin/hl-embed: tools/console/embed.c
	@mkdir -p $(@D)
	$(Q)$(CC) -std=c11 $(CWARN) -O1 -o $@ $<

$(BUILD)/gen/console_page.c: tools/console/page.html $(BUILD)/bin/hl-embed
	@mkdir -p $(@D)
	$(Q)$(BUILD)/bin/hl-embed $< > $@.tmp && mv $@.tmp $@

$(BUILD)/obj/tools/console/%.o: tools/console/%.c
	@mkdir -p $(@D)
	@echo "  CC      $<"
	$(Q)$(CC) $(CONSOLE_CPPFLAGS) $(PKG_CFLAGS) $(MHD_CFLAGS) $(CFLAGS) -c -o $@ $<

$(BUILD)/asan/tools/console/%.o: tools/console/%.c
	@mkdir -p $(@D)
	@echo "  CC-SAN  $<"
	$(Q)$(CC) $(CONSOLE_CPPFLAGS) $(PKG_CFLAGS) $(CFLAGS) $(SAN) -c -o $@ $<

$(BUILD)/asan/tests/console/%.o: tests/console/%.c
	@mkdir -p $(@D)
	@echo "  CC-SAN  $<"
	$(Q)$(CC) $(CONSOLE_CPPFLAGS) $(CFLAGS) $(SAN) -c -o $@ $<

$(BUILD)/bin/houghloc-console: $(CONSOLE_OBJS) $(STORE_LIB) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $(CONSOLE_OBJS) $(STORE_LIB) $(STORE_LDLIBS) $(MHD_LIBS)

$(BUILD)/tests/console/%: $(BUILD)/asan/tests/console/%.o $(CONSOLE_ASAN_OBJS) $(BUS_ASAN_LIB) $(LCM_LIB) $(CORE_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CC) $(SAN) -o $@ $^ $(CMOCKA_LIBS) $(PKG_LIBS) $(SODIUM_LIBS) $(SYS_LIBS)

# The browser test: houghlocd replaying logs/tour, the console, headless Chromium.
test-console: $(BUILD)/bin/houghloc-console $(BUILD)/bin/houghlocd
	$(Q)BUILD=$(BUILD) sh tests/console/browser_test.sh
