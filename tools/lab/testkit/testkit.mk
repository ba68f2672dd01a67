# tools/lab/testkit/testkit.mk - the test kit: synthetic scenes (synthroom) and the
# floating-point reference localizer (ref_localize) and the benchmarks' loop-closure graph
# (corridor), linked by the core's unit tests
# (tests/core, sanitized) and by the benchmarks.

TESTKIT_SRCS := tools/lab/testkit/synthroom.c tools/lab/testkit/ref_localize.c \
                tools/lab/testkit/corridor.c

TESTKIT_OBJS      := $(call obj,$(TESTKIT_SRCS))
TESTKIT_ASAN_OBJS := $(call asanobj,$(TESTKIT_SRCS))
TESTKIT_LIB       := $(BUILD)/lib/libhoughloc_testkit.a
TESTKIT_ASAN_LIB  := $(BUILD)/lib/libhoughloc_testkit_asan.a

$(TESTKIT_LIB): $(TESTKIT_OBJS)
$(TESTKIT_ASAN_LIB): $(TESTKIT_ASAN_OBJS)
