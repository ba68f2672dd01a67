# tools/eval/houghloc_eval.mk - houghloc-eval: ATE and RPE of a houghlocd run against
# ground truth, as evo computes them (C++17, Eigen), and its unit test. Included by the
# top Makefile.
#
# The metrics (metrics.cpp) need neither LCM nor the bus, so the test links them alone;
# the log reading (runlog.c, which houghloc-map and the tests' hl-eval also link) is
# built by the generic rule.

HLEVAL_OBJS := $(BUILD)/obj/tools/eval/houghloc_eval.o $(BUILD)/obj/tools/eval/metrics.o \
               $(BUILD)/obj/tools/eval/runlog.o
METRICS_ASAN_OBJ := $(BUILD)/asan/tools/eval/metrics.o

BINS      += $(BUILD)/bin/houghloc-eval
TEST_BINS += $(BUILD)/tests/eval/test_houghloc_eval
INTEGRATION_TESTS += tests/integration/test_houghloc_eval.sh

$(BUILD)/bin/houghloc-eval: $(HLEVAL_OBJS) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CXX) -o $@ $(HLEVAL_OBJS) $(BUS_LIB) $(BUS_LDLIBS)

# Sanitized C++ objects: static pattern rules naming only this fragment's files (the top
# Makefile's sanitized rule is C only).
$(METRICS_ASAN_OBJ) $(BUILD)/asan/tests/eval/test_houghloc_eval.o: $(BUILD)/asan/%.o: %.cpp
	@mkdir -p $(@D)
	@echo "  CXX-SAN $<"
	$(Q)$(CXX) $(TOOL_CPPFLAGS) -Itools/eval $(CXXFLAGS) $(SAN) -c -o $@ $<

$(BUILD)/tests/eval/test_houghloc_eval: $(BUILD)/asan/tests/eval/test_houghloc_eval.o \
                                        $(METRICS_ASAN_OBJ)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CXX) $(SAN) -o $@ $^ $(CMOCKA_LIBS) $(SYS_LIBS)
