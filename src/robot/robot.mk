# src/robot/robot.mk - the robot link library: the ARCOS packet codec (docs/manual/arcos.md).
# Pure C11 like the core: compiled with $(ROBOT_CPPFLAGS) only, so it sees the core's and
# its own public headers and nothing else (no LCM, no generated headers); its tests
# likewise. It also holds the sonar calibration (calib.c: raw readings to millimetres).

ROBOT_SRCS      := $(sort $(wildcard src/robot/*.c))
ROBOT_OBJS      := $(call obj,$(ROBOT_SRCS))
ROBOT_ASAN_OBJS := $(call asanobj,$(ROBOT_SRCS))
ROBOT_LIB       := $(BUILD)/lib/libhoughloc_robot.a
ROBOT_ASAN_LIB  := $(BUILD)/lib/libhoughloc_robot_asan.a

ROBOT_TESTS := $(patsubst tests/robot/%.c,$(BUILD)/tests/robot/%,$(wildcard tests/robot/test_*.c))
TEST_BINS += $(ROBOT_TESTS)

$(BUILD)/obj/src/robot/%.o: src/robot/%.c
	@mkdir -p $(@D)
	@echo "  CC      $<"
	$(Q)$(CC) $(ROBOT_CPPFLAGS) $(CFLAGS) -c -o $@ $<
$(BUILD)/asan/src/robot/%.o: src/robot/%.c
	@mkdir -p $(@D)
	@echo "  CC-SAN  $<"
	$(Q)$(CC) $(ROBOT_CPPFLAGS) $(CFLAGS) $(SAN) -c -o $@ $<
$(BUILD)/asan/tests/robot/%.o: tests/robot/%.c
	@mkdir -p $(@D)
	@echo "  CC-SAN  $<"
	$(Q)$(CC) $(ROBOT_CPPFLAGS) $(CFLAGS) $(SAN) -c -o $@ $<

$(ROBOT_LIB): $(ROBOT_OBJS)
$(ROBOT_ASAN_LIB): $(ROBOT_ASAN_OBJS)

$(BUILD)/tests/robot/%: $(BUILD)/asan/tests/robot/%.o $(ROBOT_ASAN_LIB) $(CORE_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CC) $(SAN) -o $@ $^ $(CMOCKA_LIBS) $(SYS_LIBS)

# Nothing links the plain library yet (the daemon will); build it with everything so the
# unsanitized compile is checked too.
all: $(ROBOT_LIB)
