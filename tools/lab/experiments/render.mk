# tools/lab/experiments/render.mk - the figure renderer (cairo -> PNG) used by the experiment
# runner, and its tests (tools/lab/tests/test_render.cpp, make lab-test). Included by
# tools/lab/lab.mk.
#
# A program linking $(RENDER_LIB) also needs $(RENDER_LDLIBS) after it.

RENDER_SRCS := tools/lab/experiments/render.cpp tools/lab/experiments/render_geom.cpp \
               tools/lab/experiments/render_out.cpp

RENDER_LIB       := $(BUILD)/lib/libhoughloc_render.a
RENDER_ASAN_LIB  := $(BUILD)/lib/libhoughloc_render_asan.a
RENDER_OBJS      := $(call obj,$(RENDER_SRCS))
RENDER_ASAN_OBJS := $(patsubst %.cpp,$(BUILD)/asan/%.o,$(RENDER_SRCS))
RENDER_LDLIBS    := $(CORE_LIB) $(CAIRO_LIBS) $(SYS_LIBS)

RENDER_TESTS  := $(BUILD)/tests/lab/test_render
LAB_TEST_BINS += $(RENDER_TESTS)

$(RENDER_LIB): $(RENDER_OBJS)
$(RENDER_ASAN_LIB): $(RENDER_ASAN_OBJS)

# Sanitized C++ objects (the top Makefile's sanitized rule is C only). Static pattern
# rules naming only this fragment's files, so they cannot clash with rules that other
# fragments write for tools/lab/experiments.
$(RENDER_ASAN_OBJS): $(BUILD)/asan/%.o: %.cpp | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CXX-SAN $<"
	$(Q)$(CXX) $(CPPFLAGS) $(CAIRO_CFLAGS) $(CXXFLAGS) $(SAN) -c -o $@ $<

$(BUILD)/asan/tools/lab/tests/test_render.o: $(BUILD)/asan/%.o: %.cpp | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CXX-SAN $<"
	$(Q)$(CXX) $(CPPFLAGS) -Itools/lab/experiments $(CAIRO_CFLAGS) $(CXXFLAGS) $(SAN) -c -o $@ $<

$(BUILD)/tests/lab/test_render: $(BUILD)/asan/tools/lab/tests/test_render.o \
                                $(RENDER_ASAN_LIB) $(CORE_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CXX) $(SAN) -o $@ $^ $(CMOCKA_LIBS) $(CAIRO_LIBS) $(SYS_LIBS)
