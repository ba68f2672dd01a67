# tests/support/support.mk - what the tests share: synthetic cluttered rooms with an ideal
# range sensor (synthroom) and the floating-point reference localizer (ref_localize),
# linked sanitized by the core's unit tests (tests/core) and plainly by the laboratory's
# benchmarks (tools/lab/bench). Its headers by the include path $(TEST_SUPPORT_INC).

TEST_SUPPORT_SRCS := tests/support/synthroom.c tests/support/ref_localize.c
TEST_SUPPORT_INC  := -Itests/support

TEST_SUPPORT_OBJS      := $(call obj,$(TEST_SUPPORT_SRCS))
TEST_SUPPORT_ASAN_OBJS := $(call asanobj,$(TEST_SUPPORT_SRCS))
TEST_SUPPORT_LIB       := $(BUILD)/lib/libhoughloc_testsupport.a
TEST_SUPPORT_ASAN_LIB  := $(BUILD)/lib/libhoughloc_testsupport_asan.a

$(TEST_SUPPORT_LIB): $(TEST_SUPPORT_OBJS)
$(TEST_SUPPORT_ASAN_LIB): $(TEST_SUPPORT_ASAN_OBJS)
